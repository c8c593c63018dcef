#include "study/study_runner.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "scene/toml_reader.h"
#include "solve/simulation.h"
#include "solve/snapshot.h"
#include "study/reference_csv.h"
#include "study/reference_solution.h"

namespace periflex {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Which run columns are compared: the selected probes' x and y, or the columns a csv study
// names. Distances are taken per group: an x column with its y column is one point (the
// distance between points), any other column alone (the absolute difference).
struct ProbeSelection {
  std::vector<int> scene_index;        // probes (exact references)
  std::vector<std::string> names;      // compared column names
  std::vector<int> columns;            // their index in Sample::probe_values
  std::vector<std::array<int, 2>> groups;  // positions in `columns`; second -1 for a single column
};

// Pairs "<p>.x" with "<p>.y" when both are compared.
std::vector<std::array<int, 2>> column_groups(const std::vector<std::string>& names) {
  std::vector<std::array<int, 2>> groups;
  std::vector<char> used(names.size(), 0);
  const auto ends_with = [](const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
  };
  for (size_t k = 0; k < names.size(); ++k) {
    if (used[k]) continue;
    used[k] = 1;
    int partner = -1;
    if (ends_with(names[k], ".x")) {
      const std::string y = names[k].substr(0, names[k].size() - 2) + ".y";
      for (size_t j = 0; j < names.size(); ++j)
        if (!used[j] && names[j] == y) partner = static_cast<int>(j);
    }
    if (partner >= 0) used[partner] = 1;
    groups.push_back({static_cast<int>(k), partner});
  }
  return groups;
}

ProbeSelection select_probes(const StudyDef& study, const SceneDef& scene,
                             const std::vector<std::string>& columns) {
  ProbeSelection sel;
  const auto column_index = [&](const std::string& wanted) {
    for (size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == wanted) return static_cast<int>(c);
    return -1;
  };
  if (!study.columns.empty()) {
    // the columns a csv study names, as series.csv would name them
    for (const std::string& name : study.columns) {
      const int c = column_index(name);
      if (c < 0) {
        std::string available;
        for (const std::string& a : columns) available += (available.empty() ? "" : ", ") + a;
        const SourceLocation where = study_location(study, "study.columns");
        throw InputError(where, "the scene has no column '" + name + "' to compare (its probe columns: " +
                                    (available.empty() ? "none" : available) + ")");
      }
      sel.names.push_back(name);
      sel.columns.push_back(c);
    }
    sel.groups = column_groups(sel.names);
    return sel;
  }
  std::vector<std::string> names = study.probes;
  if (names.empty())
    for (const ProbeDef& p : scene.probes) names.push_back(p.name);
  if (names.empty())
    throw InputError(study_location(study, "study.probes"), "the scene declares no [[probe]] to compare");
  for (const std::string& name : names) {
    int index = -1;
    for (size_t k = 0; k < scene.probes.size(); ++k)
      if (scene.probes[k].name == name) index = static_cast<int>(k);
    const int cx = column_index("probe." + name + ".x"), cy = column_index("probe." + name + ".y");
    if (index < 0 || cx < 0 || cy < 0)
      throw InputError(study_location(study, "study.probes"), "the scene has no probe '" + name + "'");
    sel.scene_index.push_back(index);
    sel.names.push_back("probe." + name + ".x");
    sel.names.push_back("probe." + name + ".y");
    sel.columns.push_back(cx);
    sel.columns.push_back(cy);
  }
  sel.groups = column_groups(sel.names);
  return sel;
}

// Crack length along a direction: how far the furthest newly damaged particle lies beyond the
// initial notch tip (or beyond the body's near edge when there is no initial damage).
class CrackGauge {
 public:
  CrackGauge(const Snapshot& start, const Vec2& direction) : direction_(direction) {
    const auto& g = *start.geometry;
    initial_damage_ = start.damage;
    baseline_ = std::numeric_limits<double>::infinity();
    double notch_tip = -std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < g.reference_x.size(); ++i) {
      const double s = projection(g, i);
      baseline_ = std::min(baseline_, s);
      if (i < initial_damage_.size() && initial_damage_[i] > 0.0f) notch_tip = std::max(notch_tip, s);
    }
    if (std::isfinite(notch_tip)) baseline_ = notch_tip;
  }

  double length(const Snapshot& now) const {
    const auto& g = *now.geometry;
    double tip = baseline_;
    for (size_t i = 0; i < now.damage.size() && i < g.reference_x.size(); ++i) {
      const float before = i < initial_damage_.size() ? initial_damage_[i] : 0.0f;
      // a particle that lost a quarter of its bonds during the run is on the crack
      if (now.damage[i] - before > 0.25f) tip = std::max(tip, projection(g, i));
    }
    return tip - baseline_;
  }

 private:
  double projection(const SceneGeometry& g, size_t i) const {
    return direction_.x() * g.reference_x[i] + direction_.y() * g.reference_y[i];
  }
  Vec2 direction_;
  std::vector<float> initial_damage_;
  double baseline_ = 0.0;
};

// What one run recorded at the comparison times (index 0 is t = 0).
struct Track {
  std::vector<double> times;
  std::vector<std::vector<double>> probes;  // x0, y0, x1, y1, ... of the selected probes
  std::vector<double> crack;
  std::vector<long> broken;
  std::vector<double> balance;              // energy balance at each comparison time [J]
  double violation = 0.0, energy_error = 0.0, max_kinetic = 0.0;
  long steps = 0;
  double wall = 0.0;
};

bool scene_has_fracture(const SceneDef& scene) {
  for (const FlexBodyDef& f : scene.flex_bodies)
    if (f.fracture) return true;
  return false;
}

// One run of `scene` to the comparison times; records only when asked (timing repeats do not).
Track run_once(const SceneDef& scene, const StudyDef& study, const std::vector<double>& times,
               double time_slack, bool record, const StudyStop& stop) {
  Track track;
  auto start = Clock::now();
  Simulation sim(scene);
  sim.initialize();
  track.wall += seconds_since(start);

  const bool fracture = scene_has_fracture(scene);
  ProbeSelection sel;
  std::unique_ptr<CrackGauge> gauge;
  Snapshot snapshot;
  if (record) sel = select_probes(study, scene, sim.probe_columns());

  // samples are output: they happen outside the timed sections
  const auto take_sample = [&]() {
    const Sample s = sim.sample();
    track.times.push_back(sim.time());
    std::vector<double> p;
    for (int c : sel.columns) p.push_back(s.probe_values[c]);
    track.probes.push_back(std::move(p));
    track.violation = std::max(track.violation, s.violation_position);
    track.energy_error = std::max(track.energy_error, std::abs(s.energies.balance));
    track.balance.push_back(s.energies.balance);
    track.max_kinetic = std::max(track.max_kinetic, s.energies.kinetic);
    track.broken.push_back(s.broken_bonds);
    if (fracture) {
      sim.fill_snapshot(snapshot);
      if (!gauge) gauge = std::make_unique<CrackGauge>(snapshot, study.crack_direction);
      track.crack.push_back(gauge->length(snapshot));
    }
  };
  if (record) take_sample();

  for (size_t k = 1; k < times.size(); ++k) {
    start = Clock::now();
    while (sim.time() < times[k] - time_slack) {
      if (stop && stop()) throw StudyStopped("stopped at t = " + format_g(sim.time()) + " s");
      sim.step();
    }
    track.wall += seconds_since(start);
    if (record) take_sample();
  }
  track.steps = sim.step_count();
  return track;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Largest distance between matching groups of two rows of compared values (a point's x and y
// together, any other column alone).
double probe_distance(const std::vector<double>& a, const std::vector<double>& b,
                      const std::vector<std::array<int, 2>>& groups) {
  double worst = 0.0;
  for (const auto& [i, j] : groups)
    worst = std::max(worst, j < 0 ? std::abs(a[i] - b[i]) : std::hypot(a[i] - b[i], a[j] - b[j]));
  return worst;
}

std::string correction_name(CorrectionDef::Method m) {
  switch (m) {
    case CorrectionDef::Method::kNone: return "none";
    case CorrectionDef::Method::kBaumgarte: return "baumgarte";
    case CorrectionDef::Method::kProjection: return "projection";
  }
  return "none";
}

CorrectionDef::Method correction_method(const std::string& name) {
  if (name == "none") return CorrectionDef::Method::kNone;
  if (name == "projection") return CorrectionDef::Method::kProjection;
  return CorrectionDef::Method::kBaumgarte;
}

// The reference the runs are measured against, at the comparison times of each run.
class Reference {
 public:
  virtual ~Reference() = default;
  // Probe coordinates (selected probes) at comparison index k, where the run stood at time t.
  virtual std::vector<double> probes(size_t k, double t) const = 0;
  virtual double crack(size_t) const { return 0.0; }
  virtual long broken(size_t) const { return 0; }
};

class ExactReference final : public Reference {
 public:
  ExactReference(std::unique_ptr<ReferenceSolution> solution, std::vector<int> scene_index)
      : solution_(std::move(solution)), scene_index_(std::move(scene_index)) {}
  std::vector<double> probes(size_t, double t) const override {
    const std::vector<double> all = solution_->probe_values(t);
    std::vector<double> out;
    for (int i : scene_index_) {
      out.push_back(all[2 * i]);
      out.push_back(all[2 * i + 1]);
    }
    return out;
  }

 private:
  std::unique_ptr<ReferenceSolution> solution_;
  std::vector<int> scene_index_;
};

// A reference trajectory read from a file, interpolated to the times the runs stood at.
class CsvReference final : public Reference {
 public:
  explicit CsvReference(ReferenceCsv csv) : csv_(std::move(csv)) {}
  std::vector<double> probes(size_t, double t) const override { return csv_.values(t); }

 private:
  ReferenceCsv csv_;
};

class ConvergedReference final : public Reference {
 public:
  explicit ConvergedReference(Track track) : track_(std::move(track)) {}
  std::vector<double> probes(size_t k, double t) const override {
    // runs land on the comparison times (checked when the study is set up)
    const double slack = 1e-6 * (track_.times.size() > 1 ? track_.times[1] - track_.times[0] : 1.0);
    if (std::abs(t - track_.times[k]) > slack)
      throw std::logic_error("a run missed a comparison time of the converged reference");
    return track_.probes[k];
  }
  double crack(size_t k) const override { return track_.crack.empty() ? 0.0 : track_.crack[k]; }
  long broken(size_t k) const override { return track_.broken[k]; }
  const Track& track() const { return track_; }

 private:
  Track track_;
};

// True when `interval` is a whole multiple of `dt` (to a relative 1e-6).
bool divides(double interval, double dt) {
  const double n = interval / dt;
  return std::abs(n - std::round(n)) < 1e-6 * std::max(1.0, n) && std::round(n) >= 1.0;
}

}  // namespace

void check_step_count(const SceneDef& scene, double dt, const SourceLocation& where) {
  const double steps = scene.solver.end_time / dt;
  if (!(steps <= scene.limits.max_steps))
    throw InputError(where, "dt " + format_g(dt) + " takes " + format_count(std::ceil(steps - 1e-9)) +
                                " steps to the end time " + format_g(scene.solver.end_time) +
                                " s, more than limits.max_steps = " + format_count(scene.limits.max_steps) +
                                " (raise dt, lower end_time, or raise the scene's limits.max_steps)");
}

SceneDef study_scene(const StudyDef& study) {
  SceneDef scene = load_scene(study.scene_path, study.scene_overrides);
  if (study.end_time > 0.0) scene.solver.end_time = study.end_time;
  return scene;
}

StudyResult run_study(const StudyDef& study, const StudyLog& log_fn, const StudyStop& stop) {
  const auto log = [&](const std::string& line) {
    if (log_fn) log_fn(line);
  };
  StudyResult result;
  result.study = study;
  const SceneDef base = study_scene(study);
  result.scene_name = base.name;
  result.has_fracture = scene_has_fracture(base);
  const double end_time = base.solver.end_time;
  const double interval = study.compare_interval > 0.0 ? study.compare_interval : end_time / 100.0;
  const long count = std::lround(end_time / interval);
  if (count < 1 || std::abs(count * interval - end_time) > 1e-9 * end_time)
    throw InputError(study_location(study, "study.compare_interval"),
                     "compare_interval " + format_g(interval) + " must divide the end time " + format_g(end_time));
  std::vector<double> times(count + 1);
  for (long k = 0; k <= count; ++k) times[k] = k * interval;
  result.times = times;

  // every fixed-step run must land on the comparison times, in no more steps than the scene allows
  double smallest_dt = std::numeric_limits<double>::infinity();
  for (const StudyMethodDef& m : study.methods) {
    for (double dt : m.dt) {
      smallest_dt = std::min(smallest_dt, dt);
      check_step_count(base, dt, m.where);
      // adaptive integrators too: their internal steps stop at the end of every step of dt
      if (!divides(interval, dt))
        throw InputError(m.where, "dt " + format_g(dt) + " does not divide the comparison interval " +
                                      format_g(interval) + "; choose steps that do, or change compare_interval");
    }
  }

  // the reference
  std::unique_ptr<Reference> reference;
  std::vector<std::array<int, 2>> groups;  // how compared columns make distances
  {
    Simulation probe_sim(base);
    const ProbeSelection sel = select_probes(study, base, probe_sim.probe_columns());
    groups = sel.groups;
    std::vector<double> start_probes;
    if (study.reference == "csv") {
      // a user's trajectory: its columns named as the run's, covering the whole study
      const SourceLocation where = study_location(study, "study.reference_file");
      ReferenceCsv csv = load_reference_csv(study.reference_file, study.reference_time_column, sel.names, where);
      csv.require_span(0.0, end_time, where);
      result.reference_description = "trajectory from " + study.reference_file + " (" +
                                     std::to_string(csv.samples()) + " samples, t = " + format_g(csv.first_time()) +
                                     " to " + format_g(csv.last_time()) +
                                     " s; degree-5 Lagrange interpolation between them)";
      reference = std::make_unique<CsvReference>(std::move(csv));
      start_probes = reference->probes(0, 0.0);
      for (size_t k = 0; k < times.size(); ++k)
        result.excursion =
            std::max(result.excursion, probe_distance(reference->probes(k, times[k]), start_probes, groups));
    } else if (study.reference != "converged") {
      auto solution = make_reference_solution(study.reference, base);
      result.reference_description = solution->describe();
      reference = std::make_unique<ExactReference>(std::move(solution), sel.scene_index);
      start_probes = reference->probes(0, 0.0);
      for (size_t k = 0; k < times.size(); ++k)
        result.excursion =
            std::max(result.excursion, probe_distance(reference->probes(k, times[k]), start_probes, groups));
    } else {
      SceneDef ref_scene = base;
      ref_scene.solver.integrator = study.reference_integrator;
      double ref_dt = study.reference_dt > 0.0 ? study.reference_dt : smallest_dt / 8.0;
      if (!std::isfinite(ref_dt)) ref_dt = base.solver.dt / 8.0;
      check_step_count(base, ref_dt, study_location(study, "study.reference_dt"));
      if (!divides(interval, 2.0 * ref_dt))
        throw InputError(study_location(study, "study.reference_dt"),
                         "twice the reference step must divide the comparison interval " + format_g(interval));
      if (!study.reference_correction.empty())
        ref_scene.solver.correction.method = correction_method(study.reference_correction);
      ref_scene.solver.dt = ref_dt;
      log("reference: " + study.reference_integrator + " at dt = " + format_g(ref_dt));
      Track fine = run_once(ref_scene, study, times, 1e-6 * ref_dt, true, stop);
      ref_scene.solver.dt = 2.0 * ref_dt;
      const Track coarse = run_once(ref_scene, study, times, 2e-6 * ref_dt, true, stop);
      // the fine run's own error, estimated by the change from twice its step
      for (size_t k = 0; k < times.size(); ++k)
        result.reference_error = std::max(result.reference_error, probe_distance(fine.probes[k], coarse.probes[k], groups));
      result.reference_wall_time = fine.wall;
      result.reference_description = "converged run: " + study.reference_integrator + " at dt = " +
                                     format_g(ref_dt) + " (" + correction_name(ref_scene.solver.correction.method) +
                                     "); its error, estimated against dt = " + format_g(2.0 * ref_dt) + ": " +
                                     format_g(result.reference_error) + " m";
      for (size_t k = 0; k < times.size(); ++k)
        result.excursion = std::max(result.excursion, probe_distance(fine.probes[k], fine.probes[0], groups));
      reference = std::make_unique<ConvergedReference>(std::move(fine));
    }
  }
  log("reference: " + result.reference_description);
  const double scale = result.excursion > 0.0 ? result.excursion : 1.0;

  // the grid, until `stop` asks (the run under way is then dropped)
  for (const StudyMethodDef& m : study.methods) {
    if (result.stopped) break;
    const bool adaptive = !m.tolerances.empty();
    std::vector<std::string> corrections = m.corrections;
    if (corrections.empty()) corrections.push_back(correction_name(base.solver.correction.method));
    std::vector<double> steps = m.dt, tols = m.tolerances;
    if (adaptive && steps.empty()) steps.push_back(base.solver.dt);
    if (!adaptive) tols.assign(1, 0.0);
    for (const std::string& correction : corrections) {
      for (double tol : tols) {
        for (double dt : steps) {
          if (result.stopped) break;
          StudyRow row;
          row.integrator = m.integrator;
          row.correction = correction;
          row.dt = dt;
          row.tol = tol;
          SceneDef scene = base;
          scene.solver.integrator = m.integrator;
          scene.solver.dt = dt;
          scene.solver.correction.method = correction_method(correction);
          if (adaptive) {
            scene.solver.rtol = tol;
            scene.solver.atol = tol * m.atol_ratio;
          }
          const double slack = 1e-6 * dt;
          try {
            const Track track = run_once(scene, study, times, slack, true, stop);
            std::vector<double> walls{track.wall};
            for (int r = 1; r < study.repeats; ++r)
              walls.push_back(run_once(scene, study, times, slack, false, stop).wall);
            row.wall_time = median(walls);
            row.steps = track.steps;
            row.violation = track.violation;
            row.energy_error = track.energy_error;
            row.energy_error_rel = track.max_kinetic > 0.0 ? track.energy_error / track.max_kinetic : 0.0;
            for (double b : track.balance)
              row.energy_trace.push_back(track.max_kinetic > 0.0 ? std::abs(b) / track.max_kinetic : std::abs(b));
            double sum_sq = 0.0;
            const long end_broken = reference->broken(times.size() - 1);
            for (size_t k = 0; k < track.times.size(); ++k) {
              const double e = probe_distance(track.probes[k], reference->probes(k, track.times[k]), groups);
              row.error_max = std::max(row.error_max, e);
              sum_sq += e * e;
              if (result.has_fracture) {
                row.crack_tip_error = std::max(row.crack_tip_error, std::abs(track.crack[k] - reference->crack(k)));
                row.broken_bond_error =
                    std::max(row.broken_bond_error, std::abs(double(track.broken[k] - reference->broken(k))) /
                                                        std::max<double>(1.0, double(end_broken)));
              }
            }
            row.error_rms = std::sqrt(sum_sq / double(track.times.size()));
            if (!std::isfinite(row.error_max)) row.status = "failed: probe positions not finite";
          } catch (const NumericalError& e) {
            row.status = "failed: " + e.diagnostic().quantity;
          } catch (const StudyStopped&) {
            result.stopped = true;
            log(row.integrator + " " + row.correction + " dt=" + format_g(dt) + ": stopped, not measured");
            break;
          }
          if (!row.ok()) {
            const double nan = std::numeric_limits<double>::quiet_NaN();
            row.error_max = row.error_rms = row.energy_error = row.energy_error_rel = row.violation = nan;
            row.crack_tip_error = row.broken_bond_error = nan;
            row.wall_time = nan;
          }
          row.error_max_rel = row.error_max / scale;
          row.error_rms_rel = row.error_rms / scale;
          log(row.integrator + " " + row.correction + (adaptive ? " tol=" + format_g(tol) : "") +
              " dt=" + format_g(dt) + ": " +
              (row.ok() ? "error " + format_g(row.error_max_rel) + " in " + format_g(row.wall_time) + " s"
                        : row.status));
          result.rows.push_back(row);
        }
      }
    }
  }

  // orders, above both round-off and the reference's own error
  const double floor = std::max(1e-13, 10.0 * result.reference_error / scale);
  result.orders = observed_orders(result.rows, floor);
  return result;
}

}  // namespace periflex
