#include "study/sweep_def.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "output/series_row.h"
#include "scene/scene_loader.h"
#include "scene/toml_reader.h"
#include "study/scene_reference.h"

namespace periflex {

namespace {

// A TOML value as the text --set reads back to the same value: a float in the fewest digits
// that give the same double, and still a float (1.0, not 1).
std::string value_text(const toml::node& node) {
  if (const auto* d = node.as_floating_point()) {
    char text[40];
    for (int digits = 15; digits <= 17; ++digits) {
      std::snprintf(text, sizeof text, "%.*g", digits, d->get());
      if (std::strtod(text, nullptr) == d->get()) break;
    }
    std::string out = text;
    if (out.find_first_of(".eEn") == std::string::npos) out += ".0";
    return out;
  }
  std::ostringstream out;
  node.visit([&out](const auto& value) { out << value; });
  return out.str();
}

// Every gathered column must be one the run writes: a misspelt name would otherwise leave its
// column of sweep.csv empty after the whole sweep has run.
void check_series(const SweepDef& sweep, const SweepRun& run, const SceneDef& scene) {
  const std::vector<std::string> columns = series_columns(scene);
  for (const std::string& name : sweep.series) {
    if (std::find(columns.begin(), columns.end(), name) != columns.end()) continue;
    std::string expected;
    for (const std::string& c : columns) expected += (expected.empty() ? "" : ", ") + c;
    throw InputError(sweep.series_where, "run " + run.folder + " writes no series.csv column '" + name +
                                             "'; expected one of: " + expected);
  }
}

}  // namespace

SweepDef parse_sweep(const std::string& toml_text, const std::string& display_path) {
  ReadContext context;
  context.file = display_path;
  toml::table root = parse_toml_located(toml_text, display_path);
  SweepDef sweep;
  sweep.path = display_path;
  TableReader top(context, root, "", "the sweep file");

  // [sweep]
  const toml::table* table = top.optional_table("sweep");
  if (!table) top.fail_missing("sweep", "a sweep file needs a [sweep] table");
  TableReader s(context, *table, "sweep", "[sweep]");
  SceneReference head = read_scene_reference(s, display_path);
  sweep.name = std::move(head.name);
  sweep.scene_path = std::move(head.scene_path);
  sweep.overrides = std::move(head.overrides);
  // the bounds of the command line's --jobs; a memory limit beyond any machine is a typo
  sweep.jobs = static_cast<int>(s.integer("jobs", 2, 1));
  if (sweep.jobs > kMaxSweepJobs) s.fail("jobs", "at most " + std::to_string(kMaxSweepJobs) + " runs at once");
  sweep.timeout_seconds = s.number("timeout", 3600.0, Sign::kPositive);
  const double memory_gb = s.number("memory_gb", 4.0, Sign::kPositive);
  if (memory_gb > kMaxSweepMemoryGb) s.fail("memory_gb", "at most 1e6 (a petabyte) of address space per run");
  sweep.memory_bytes = memory_gb * 1e9;
  if (s.has("series")) sweep.series_where = context.locate(s.node("series"), s.key_path("series"));
  sweep.series = s.strings("series");
  s.finish();

  // [[parameter]]: a key and its values
  const toml::array* parameters = top.optional_array("parameter");
  if (!parameters || parameters->empty())
    top.fail_missing("parameter", "a sweep needs at least one [[parameter]] with a key and values");
  int index = 0;
  for (const toml::node& item : *parameters) {
    const std::string path = "parameter." + std::to_string(index++);
    const toml::table* t = item.as_table();
    if (!t) context.fail(&item, path, "expected a table ([[parameter]])");
    TableReader p(context, *t, path, "[[parameter]]");
    SweepParameter parameter;
    parameter.key = p.required_string("key");
    if (parameter.key.empty() || parameter.key.find('=') != std::string::npos)
      p.fail("key", "expected a dotted scene key such as \"solver.dt\"");
    const toml::node* values = p.node("values");
    if (!values) p.fail_missing("values", "the values the key takes, as an array");
    const toml::array* array = values->as_array();
    if (!array || array->empty()) p.fail("values", "expected a non-empty array of values");
    parameter.where = context.locate(values, p.key_path("values"));
    for (const toml::node& value : *array) parameter.values.push_back(value_text(value));
    p.finish();
    for (const SweepParameter& other : sweep.parameters)
      if (other.key == parameter.key) p.fail("key", "'" + parameter.key + "' is swept twice");
    sweep.parameters.push_back(parameter);
  }
  top.finish();
  return sweep;
}

SweepDef load_sweep(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    SourceLocation where;
    where.file = path;
    throw InputError(where, "cannot read the sweep file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_sweep(text.str(), path);
}

std::vector<SweepRun> expand_sweep(const SweepDef& sweep) {
  // the size of the grid, before a scene is read for each of its runs
  double count = 1.0;
  std::string product;
  for (const SweepParameter& p : sweep.parameters) {
    count *= static_cast<double>(p.values.size());
    product += (product.empty() ? "" : " x ") + std::to_string(p.values.size());
  }
  if (count > kMaxSweepRuns) {
    char text[160];
    std::snprintf(text, sizeof text, "the grid has %.0f runs (%s values), more than %.0f; split the sweep", count,
                  product.c_str(), kMaxSweepRuns);
    throw InputError(sweep.parameters.back().where, text);
  }
  std::vector<SweepRun> runs;
  const size_t axes = sweep.parameters.size();
  std::vector<size_t> at(axes, 0);
  for (;;) {
    SweepRun run;
    char folder[32];
    std::snprintf(folder, sizeof folder, "run_%04zu", runs.size() + 1);
    run.folder = folder;
    run.overrides = sweep.overrides;
    for (size_t a = 0; a < axes; ++a) {
      const SweepParameter& p = sweep.parameters[a];
      run.values.push_back(p.values[at[a]]);
      run.overrides.push_back(p.key + "=" + p.values[at[a]]);
    }
    // the scene must take every value: a refusal is reported at the parameter in the sweep file
    SceneDef scene;
    try {
      scene = load_scene(sweep.scene_path, run.overrides);
    } catch (const InputError& error) {
      // an override's error names it ("override 'key=value'"): the parameter it came from, or
      // the sweep's own `set`; an error of the scene itself keeps its place in the scene
      SourceLocation where = error.where();
      const bool from_override = error.detail().find("override '") != std::string::npos;
      if (from_override) {
        where = SourceLocation{sweep.path, 0, 0, "sweep.set"};
        for (size_t a = 0; a < axes; ++a) {
          const std::string set = sweep.parameters[a].key + "=" + run.values[a];
          if (error.detail().find("'" + set + "'") != std::string::npos) where = sweep.parameters[a].where;
        }
      }
      throw InputError(where, "run " + run.folder + ": " + error.detail());
    }
    check_series(sweep, run, scene);
    runs.push_back(run);
    // the next combination, the last axis fastest
    size_t a = axes;
    while (a > 0) {
      --a;
      if (++at[a] < sweep.parameters[a].values.size()) break;
      at[a] = 0;
      if (a == 0) return runs;
    }
  }
}

}  // namespace periflex
