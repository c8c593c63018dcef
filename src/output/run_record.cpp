// run.json of a checkpoint folder: written and read with nlohmann::json.
#include "output/run_record.h"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "output/atomic_file.h"
#include "output/checkpoint_file.h"

namespace periflex {

namespace {

std::string full_digits(double value) {
  char number[40];
  std::snprintf(number, sizeof number, "%.17g", value);
  return number;
}

}  // namespace

std::vector<std::string> RunRecord::scene_overrides() const {
  std::vector<std::string> all = overrides;
  if (dt) all.push_back("solver.dt=" + full_digits(*dt));
  if (integrator) all.push_back("solver.integrator=\"" + *integrator + "\"");
  return all;
}

uint64_t scene_identity_hash(const std::string& scene_text, const std::vector<std::string>& overrides,
                             std::optional<double> dt, const std::optional<std::string>& integrator) {
  // each part with a separator no scene text or flag value contains
  uint64_t h = text_hash(scene_text);
  for (const std::string& set : overrides) h = text_hash("\x1f--set " + set, h);
  if (dt) h = text_hash("\x1f--dt " + full_digits(*dt), h);
  if (integrator) h = text_hash("\x1f--integrator " + *integrator, h);
  return h;
}

void write_run_record(const std::string& dir, const RunRecord& record) {
  nlohmann::json j;
  j["format"] = "periflex run record";
  j["program_version"] = record.program_version;
  j["scene"] = record.scene_path;
  j["set"] = record.overrides;
  j["dt"] = record.dt ? nlohmann::json(*record.dt) : nlohmann::json(nullptr);
  j["integrator"] = record.integrator ? nlohmann::json(*record.integrator) : nlohmann::json(nullptr);
  j["until"] = record.until ? nlohmann::json(*record.until) : nlohmann::json(nullptr);
  char hash[24];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(record.scene_hash));
  j["scene_hash"] = hash;
  write_file_atomically(dir + "/" + kRunRecordName, j.dump(2) + "\n");
}

RunRecord read_run_record(const std::string& dir) {
  const std::string path = dir + "/" + kRunRecordName;
  std::ifstream in(path);
  if (!in) {
    throw CheckpointError("'" + path + "' is missing: the folder was not written by `periflex run --checkpoint-every`, "
                          "or by a version that did not record its scene");
  }
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.value("format", "") != "periflex run record") throw CheckpointError("'" + path + "' is not a periflex run record");
    RunRecord r;
    r.program_version = j.at("program_version").get<std::string>();
    r.scene_path = j.at("scene").get<std::string>();
    r.overrides = j.at("set").get<std::vector<std::string>>();
    if (!j.at("dt").is_null()) r.dt = j.at("dt").get<double>();
    if (!j.at("integrator").is_null()) r.integrator = j.at("integrator").get<std::string>();
    // records written before the end time was kept have none: the scene's end time stands
    if (j.contains("until") && !j.at("until").is_null()) r.until = j.at("until").get<double>();
    const std::string hash = j.at("scene_hash").get<std::string>();
    size_t used = 0;
    r.scene_hash = std::stoull(hash, &used, 16);
    if (used != hash.size()) throw CheckpointError("'" + path + "': scene_hash is not a hexadecimal number");
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw CheckpointError("'" + path + "' is not a readable run record: " + e.what());
  } catch (const std::logic_error& e) {  // stoull
    throw CheckpointError("'" + path + "': scene_hash is not a hexadecimal number");
  }
}

}  // namespace periflex
