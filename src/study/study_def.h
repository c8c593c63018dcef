// What a study file (TOML) asks for: a scene, a grid of methods and a reference to measure
// errors against. docs/work_precision.md documents every key; scenes/studies/ holds examples.
//
//   [study]
//   scene = "pendulum.toml"            # relative to the study file
//   mode = "time"                      # time: integrators x steps; refine: grid spacing x horizon
//   reference = "pendulum_exact"       # pendulum_exact | slider_crank_exact | converged | csv
//   reference_file = "a01.csv"         # csv: a time column and named columns, relative to the study
//   columns = ["probe.bob.x", "probe.bob.y"]   # csv: the columns compared (default: probes' x, y)
//   end_time = 2.0                     # default: the scene's
//   compare_interval = 0.01            # simulated seconds between error samples
//   repeats = 3                        # wall time is the median over repeats
//   [[method]]
//   integrator = "rk4"
//   dt = [1e-2, 5e-3, 2.5e-3]
//   correction = ["baumgarte", "projection"]
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec2.h"

namespace periflex {

// One row of the method grid: an integrator at each step (or tolerance) and correction.
struct StudyMethodDef {
  std::string integrator;
  std::vector<double> dt;            // fixed steps; for adaptive integrators the initial step
  std::vector<double> tolerances;    // adaptive integrators: rtol = tol, atol = tol * atol_ratio
  double atol_ratio = 1e-3;
  std::vector<std::string> corrections;  // none | baumgarte | projection; empty: the scene's
  SourceLocation where;
};

// The spatial study of a flexible body: a quantity with a known answer as the grid is refined.
struct RefineDef {
  // "wave_speed": longitudinal wave speed of a bar against sqrt(E / rho);
  // "cantilever_frequency": first bending frequency against Euler-Bernoulli.
  std::string quantity = "wave_speed";
  std::string flex_body;                 // default: the first flexible body
  std::vector<double> grid_spacing;      // default: the scene's
  std::vector<double> horizon_ratio;     // default: the scene's
  std::string probe;                     // probe whose motion gives the quantity; default: the first
};

// Timed repeats of each run (the file's repeats and --repeats alike).
constexpr int kMaxStudyRepeats = 1000;

struct StudyDef {
  std::string name;                  // default: file stem
  std::string path;                  // the study file
  std::string scene_path;            // resolved against the study file's folder
  std::vector<std::string> scene_overrides;  // "key=value" applied to the scene
  enum class Mode { kTime, kRefine } mode = Mode::kTime;
  std::string reference = "converged";  // pendulum_exact | slider_crank_exact | converged | csv
  std::string reference_file;           // csv: resolved against the study file's folder
  std::string reference_time_column = "t";  // csv: the time column (series.csv's name by default)
  std::vector<std::string> columns;     // csv: compared columns; empty: x and y of the compared probes
  std::string reference_integrator = "rk4";
  double reference_dt = 0.0;            // converged reference; default: smallest dt / 8
  std::string reference_correction;     // default: the scene's
  double end_time = 0.0;                // 0: the scene's
  double compare_interval = 0.0;        // 0: end_time / 100
  int repeats = 1;
  std::vector<std::string> probes;      // compared probes; empty: all
  Vec2 crack_direction = Vec2::UnitX(); // flexible scenes: the tip is the damaged particle furthest along it
  std::vector<StudyMethodDef> methods;
  RefineDef refine;
  // where each key of [study] and [refine] stands in the file ("study.end_time" -> line,
  // column), for the errors found when the study runs
  std::map<std::string, SourceLocation> locations;
};

// Reads and validates a study file. Throws InputError with file, line and key.
StudyDef load_study(const std::string& path);
// As load_study, from text; `display_path` also anchors the scene path.
StudyDef parse_study(const std::string& toml_text, const std::string& display_path);

// Theoretical order of accuracy of a named integrator (0 when unknown).
int theoretical_order(const std::string& integrator);
// True for integrators that choose their own step from rtol / atol.
// A number as ostream writes it by default (6 significant digits), for tables and labels.
std::string format_g(double v);
// The study file and a dotted key, with the key's line and column when the file has it, for
// InputError.
SourceLocation study_location(const StudyDef& study, const std::string& key);
bool is_adaptive_integrator(const std::string& integrator);

}  // namespace periflex
