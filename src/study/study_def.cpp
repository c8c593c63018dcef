#include "study/study_def.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "scene/integrator_catalogue.h"
#include "scene/toml_reader.h"
#include "study/scene_reference.h"

namespace periflex {

namespace {

// A list of numbers under `key`, or a single number; every entry positive.
std::vector<double> positive_list(TableReader& reader, std::string_view key) {
  const toml::node* node = reader.node(key);
  if (!node) return {};
  const std::string dotted = reader.key_path(key);
  std::vector<double> out;
  if (node->is_array()) out = read_number_list(reader.context(), *node, dotted);
  else out.push_back(read_number(reader.context(), *node, dotted, Sign::kPositive));
  for (double v : out)
    if (!(v > 0.0)) reader.fail(key, "every entry must be positive");
  return out;
}

// The place of every key of `table` in the file, as "<prefix>.<key>".
void locate_keys(const ReadContext& context, const toml::table& table, const std::string& prefix,
                 std::map<std::string, SourceLocation>& out) {
  for (const auto& [key, node] : table) {
    const std::string path = prefix + "." + std::string(key.str());
    out[path] = context.locate(&node, path);
  }
}

}  // namespace

int theoretical_order(const std::string& integrator) {
  const IntegratorTraits* traits = find_integrator(integrator);
  return traits != nullptr ? traits->order : 0;
}

std::string format_g(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

SourceLocation study_location(const StudyDef& study, const std::string& key) {
  const auto located = study.locations.find(key);
  if (located != study.locations.end()) return located->second;
  SourceLocation where;
  where.file = study.path;
  where.key = key;
  return where;
}

bool is_adaptive_integrator(const std::string& integrator) {
  const IntegratorTraits* traits = find_integrator(integrator);
  return traits != nullptr && traits->is_adaptive;
}

StudyDef parse_study(const std::string& toml_text, const std::string& display_path) {
  ReadContext context;
  context.file = display_path;
  toml::table root = parse_toml_located(toml_text, display_path);

  StudyDef study;
  study.path = display_path;
  TableReader top(context, root, "", "the study file");

  // [study]
  const toml::table* table = top.optional_table("study");
  if (!table) top.fail_missing("study", "a study file needs a [study] table");
  TableReader s(context, *table, "study", "[study]");
  SceneReference head = read_scene_reference(s, display_path);
  study.name = std::move(head.name);
  study.scene_path = std::move(head.scene_path);
  study.scene_overrides = std::move(head.overrides);
  study.mode = s.choice("mode", {"time", "refine"}, "time") == "refine" ? StudyDef::Mode::kRefine
                                                                          : StudyDef::Mode::kTime;
  study.reference = s.choice("reference", {"pendulum_exact", "slider_crank_exact", "converged", "csv"}, "converged");
  // a reference trajectory from a file: which file, its time column and the compared columns
  locate_keys(context, *table, "study", study.locations);
  if (s.has("reference_file")) study.reference_file = path_beside(display_path, s.required_string("reference_file"));
  study.reference_time_column = s.string("reference_time_column", "t");
  study.columns = s.strings("columns");
  if (study.reference == "csv" && study.reference_file.empty())
    s.fail_missing("reference_file", "reference = \"csv\" needs the file of the reference trajectory");
  if (study.reference != "csv" && (!study.reference_file.empty() || !study.columns.empty()))
    s.fail(study.reference_file.empty() ? "columns" : "reference_file",
           "only a reference = \"csv\" study reads a reference file and its columns");
  study.reference_integrator = s.string("reference_integrator", "rk4");
  study.reference_dt = s.number("reference_dt", 0.0, Sign::kNonNegative, true);
  if (s.has("reference_correction"))
    study.reference_correction = s.choice("reference_correction", {"none", "baumgarte", "projection"}, "none");
  study.end_time = s.number("end_time", 0.0, Sign::kNonNegative, true);
  study.compare_interval = s.number("compare_interval", 0.0, Sign::kNonNegative, true);
  study.repeats = static_cast<int>(s.integer("repeats", 1, 1));
  if (study.repeats > kMaxStudyRepeats) s.fail("repeats", "at most " + std::to_string(kMaxStudyRepeats) + " timed repeats");
  study.probes = s.strings("probes");
  study.crack_direction = s.axis("crack_direction", Vec2::UnitX());
  s.finish();

  // [[method]]
  if (const toml::array* methods = top.optional_array("method")) {
    int index = 0;
    for (const toml::node& node : *methods) {
      const std::string path = "method." + std::to_string(index);
      const toml::table* t = node.as_table();
      if (!t) context.fail(&node, path, "[[method]] entries must be tables");
      TableReader m(context, *t, path, "[[method]] " + std::to_string(index));
      StudyMethodDef def;
      def.where = m.where();
      def.integrator = m.required_string("integrator");
      def.dt = positive_list(m, "dt");
      def.tolerances = positive_list(m, "tol");
      def.atol_ratio = m.number("atol_ratio", 1e-3, Sign::kPositive);
      def.corrections = m.strings("correction");
      for (const std::string& c : def.corrections)
        if (c != "none" && c != "baumgarte" && c != "projection")
          m.fail("correction", "unknown correction '" + c + "' (none, baumgarte, projection)");
      if (def.dt.empty() && def.tolerances.empty())
        m.fail_missing("dt", "a method needs time steps (dt) or tolerances (tol)");
      m.finish();
      study.methods.push_back(std::move(def));
      ++index;
    }
  }

  // [refine]
  if (const toml::table* refine = top.optional_table("refine")) {
    TableReader r(context, *refine, "refine", "[refine]");
    locate_keys(context, *refine, "refine", study.locations);
    study.refine.quantity = r.choice("quantity", {"wave_speed", "cantilever_frequency"}, "wave_speed");
    study.refine.flex_body = r.string("flex_body", "");
    study.refine.grid_spacing = positive_list(r, "grid_spacing");
    study.refine.horizon_ratio = positive_list(r, "horizon_ratio");
    study.refine.probe = r.string("probe", "");
    r.finish();
  }
  top.finish();

  if (study.mode == StudyDef::Mode::kTime && study.methods.empty())
    top.fail_missing("method", "a time study needs at least one [[method]]");
  if (study.mode == StudyDef::Mode::kRefine && study.methods.size() > 1)
    top.fail("method", "a refine study runs one method (one [[method]] with one dt)");
  return study;
}

StudyDef load_study(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    SourceLocation where;
    where.file = path;
    throw InputError(where, "cannot read the study file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_study(text.str(), path);
}

}  // namespace periflex
