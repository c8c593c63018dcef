// periflex against MuJoCo at equal accuracy, in one run on one machine: the IFToMM A01 pendulum
// (2000 s) and A02 double four-bar (10 s). For each program and each of its integrators, the
// largest time step (or loosest tolerance) whose max position error stays within 1e-3 m of the
// reference; the cheapest of those settings is each program's, and the ratio of their CPU times
// is the figure. Run by bench/mujoco_compare.sh, which writes the MuJoCo models (MJCF).
//
//   mujoco_compare <a01.xml> <a02.xml> [--quick] [--only=a01|a02]
//
// MuJoCo's closed loops (A02) are soft equality constraints: its settings include the MJCF's
// defaults and the hardest MuJoCo allows (impedance 0.9999, time constant 2 dt).
//
// Both programs record the benchmark's point after every step into a kept buffer (MuJoCo: the
// hinge angle, mapped to the point after the run; periflex: the probe) and are compared with
// the reference afterwards, so the timed loop is stepping alone. CPU time of the process, one
// thread.
#include <mujoco/mujoco.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"
#include "study/reference_solution.h"

namespace periflex {
namespace {

constexpr double kTarget = 1e-3;  // max position error [m]
constexpr double kGravity = 9.81;
constexpr double kInf = std::numeric_limits<double>::infinity();

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// A recorded trajectory: time and the benchmark's point (x, y in the plane of motion).
struct Track {
  std::vector<double> t, x, y;
  void clear() {
    t.clear();
    x.clear();
    y.clear();
  }
};

// One setting tried: its name, error against the reference and CPU seconds (inf: gave up).
struct Trial {
  std::string program, setting;
  double error = kInf, cpu = kInf;
  bool passed() const { return error <= kTarget && std::isfinite(cpu); }
};

// The A02 reference: the parallelogram's equation 3 theta'' + 3.5 g cos(theta) = 0 by RK4 at
// 1e-5 s from theta = pi/2, theta' = -1 (as the repository's tests integrate it), read between
// the grid points by cubic Hermite interpolation (its error is far below the RK4 error).
class FourBarReference {
 public:
  explicit FourBarReference(double end) : h_(1e-5) {
    auto accel = [](double th) { return -3.5 * kGravity * std::cos(th) / 3.0; };
    const long steps = std::lround(end / h_) + 2;
    theta_.reserve(steps + 1);
    omega_.reserve(steps + 1);
    double th = M_PI / 2, w = -1.0;
    for (long i = 0; i <= steps; ++i) {
      theta_.push_back(th);
      omega_.push_back(w);
      const double k1q = w, k1v = accel(th);
      const double k2q = w + h_ / 2 * k1v, k2v = accel(th + h_ / 2 * k1q);
      const double k3q = w + h_ / 2 * k2v, k3v = accel(th + h_ / 2 * k2q);
      const double k4q = w + h_ * k3v, k4v = accel(th + h_ * k3q);
      th += h_ / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
      w += h_ / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  }
  // B0's x at time t
  double b0_x(double t) const {
    const double s = t / h_;
    const long i = std::min(static_cast<long>(s), static_cast<long>(theta_.size()) - 2);
    const double u = s - static_cast<double>(i);
    const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u;
    const double h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
    const double th = h00 * theta_[i] + h10 * h_ * omega_[i] + h01 * theta_[i + 1] + h11 * h_ * omega_[i + 1];
    return std::cos(th);
  }

 private:
  double h_;
  std::vector<double> theta_, omega_;
};

// ---- MuJoCo -----------------------------------------------------------------------------

// A loaded MJCF model and the map from its joint angles to the benchmark's point.
struct MujocoModel {
  mjModel* model = nullptr;
  std::vector<double> qvel0;  // initial joint rates
  double solimp0[2] = {0, 0}, solref0[2] = {0, 0};  // the MJCF's equality settings (the first)
  // the point from the first hinge angle (A01: the bob; A02: B0), in the plane (x, up)
  std::function<void(double, double&, double&)> point;
  ~MujocoModel() {
    if (model) mj_deleteModel(model);
  }
};

// Steps to `span` at (integrator, dt), the first angle recorded after every step; false when the
// CPU time passed `budget` first.
bool run_mujoco(const MujocoModel& mm, int integrator, bool hard, double dt, double span, double budget,
                Track& track, double& cpu) {
  mjModel* m = mm.model;
  m->opt.integrator = integrator;
  m->opt.timestep = dt;
  // equality constraints: the MJCF's (MuJoCo's defaults), or as hard as MuJoCo lets them be
  // (impedance 0.9999, time constant 2 dt, critically damped)
  for (int e = 0; e < m->neq; ++e) {
    m->eq_solimp[mjNIMP * e] = hard ? 0.9999 : mm.solimp0[0];
    m->eq_solimp[mjNIMP * e + 1] = hard ? 0.9999 : mm.solimp0[1];
    m->eq_solref[mjNREF * e] = hard ? 2 * dt : mm.solref0[0];
    m->eq_solref[mjNREF * e + 1] = hard ? 1.0 : mm.solref0[1];
  }
  mjData* d = mj_makeData(m);
  for (size_t k = 0; k < mm.qvel0.size(); ++k) d->qvel[k] = mm.qvel0[k];
  const long steps = static_cast<long>(std::ceil(span / dt - 1e-9));
  std::vector<double> angle(static_cast<size_t>(steps));
  bool finished = true;
  const double start = cpu_seconds();
  for (long k = 0; k < steps; ++k) {
    mj_step(m, d);
    angle[static_cast<size_t>(k)] = d->qpos[0];
    if (k % 1024 == 0 && cpu_seconds() - start > budget) {
      finished = false;
      break;
    }
  }
  cpu = cpu_seconds() - start;
  mj_deleteData(d);
  track.clear();
  if (!finished) return false;
  for (long k = 0; k < steps; ++k) {
    double x = 0, y = 0;
    mm.point(angle[static_cast<size_t>(k)], x, y);
    track.t.push_back((k + 1) * dt);
    track.x.push_back(x);
    track.y.push_back(y);
  }
  return true;
}

// ---- periflex ---------------------------------------------------------------------------

// Steps the scene (with its solver settings) to `span`, probe 0 recorded after every step.
bool run_periflex(const SceneDef& scene, double span, double budget, Track& track, double& cpu) {
  track.clear();
  const long steps = static_cast<long>(std::ceil(span / scene.solver.dt - 1e-9));
  track.t.reserve(static_cast<size_t>(steps));
  track.x.reserve(static_cast<size_t>(steps));
  track.y.reserve(static_cast<size_t>(steps));
  const double start = cpu_seconds();
  try {
    Simulation sim(scene);
    sim.initialize();
    for (long k = 0; k < steps; ++k) {
      sim.step();
      const Vec2 p = sim.probe_position(0);
      track.t.push_back(sim.time());
      track.x.push_back(p.x());
      track.y.push_back(p.y());
      if (k % 1024 == 0 && cpu_seconds() - start > budget) {
        cpu = cpu_seconds() - start;
        return false;
      }
    }
  } catch (const NumericalError&) {
    cpu = cpu_seconds() - start;
    track.clear();
    return true;  // a run that stops has no error figure: it fails below
  }
  cpu = cpu_seconds() - start;
  return true;
}

// ---- the search -------------------------------------------------------------------------

using ErrorOf = std::function<double(const Track&)>;

// One benchmark: MuJoCo's integrators over a ladder of time steps, periflex's over time steps
// (fixed-step) or tolerances (dopri54); for each, the first rung from the cheap end that meets
// the target. A run stops once it costs more than the cheapest passing setting so far (times
// 1.5, for the noise of a shared machine): it could not be the cheapest.
struct Benchmark {
  std::string name;
  double span = 0.0;
  const MujocoModel* mujoco = nullptr;
  SceneDef scene;
  ErrorOf error;
  std::vector<double> fixed_steps;   // the dt ladder, largest first
  std::vector<double> tolerances;    // dopri54 rtol ladder, loosest first
  double dopri_macro = 0.0;          // dopri54's macro step (projection after each)
  double cap = 10.0;                 // CPU seconds a run may take before any setting passed
};

// A ladder gives up once six rungs in a row have not lowered its smallest error (a model error
// the step size does not reach, or an unstable scheme).
struct Stall {
  double lowest = kInf;
  int since = 0;
  bool stalled(double error) {
    if (error < 0.9 * lowest) {
      lowest = error;
      since = 0;
    } else {
      ++since;
    }
    return since >= 6;
  }
};

double track_error(const Track& track, const ErrorOf& error) {
  if (track.t.empty()) return kInf;
  for (size_t k = 0; k < track.t.size(); ++k) {
    if (!std::isfinite(track.x[k]) || !std::isfinite(track.y[k])) return kInf;
  }
  return error(track);
}

void print_trial(const Trial& t) {
  std::printf("  %-9s %-38s max error %-10.3g CPU %s\n", t.program.c_str(), t.setting.c_str(), t.error,
              std::isfinite(t.cpu) ? (std::to_string(t.cpu) + " s").c_str() : "(stopped: dearer than the best)");
}

struct Choice {
  Trial mujoco, periflex;
  std::function<double()> time_mujoco, time_periflex;
};

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

Choice search(const Benchmark& b) {
  Choice choice;
  Track track;
  double best = kInf;
  auto budget = [&] { return std::isfinite(best) ? 1.5 * best : b.cap; };
  std::printf("%s over %g s: settings tried (target max error %g m)\n", b.name.c_str(), b.span, kTarget);

  // MuJoCo: Euler (semi-implicit), RK4, implicit, each over the dt ladder
  const std::pair<int, const char*> mj_integrators[] = {{mjINT_RK4, "RK4"}, {mjINT_EULER, "Euler"},
                                                         {mjINT_IMPLICIT, "implicit"}};
  double best_mujoco = kInf;
  for (const bool hard : {false, true}) {
    if (hard && b.mujoco->model->neq == 0) continue;
    for (const auto& [integrator, label] : mj_integrators) {
      Stall stall;
      for (double dt : b.fixed_steps) {
        Trial t{"MuJoCo", std::string(label) + (hard ? ", hard equality" : "") + ", dt " + number(dt)};
        double cpu = 0;
        const bool finished = run_mujoco(*b.mujoco, integrator, hard, dt, b.span, budget(), track, cpu);
        if (finished) {
          t.cpu = cpu;
          t.error = track_error(track, b.error);
        }
        print_trial(t);
        if (!finished || stall.stalled(t.error)) break;  // smaller steps cost more still
        if (t.passed()) {
          if (t.cpu < best_mujoco) {
            best_mujoco = t.cpu;
            choice.mujoco = t;
            const int integ = integrator;
            choice.time_mujoco = [&b, integ, hard, dt] {
              Track tr;
              double c = 0;
              run_mujoco(*b.mujoco, integ, hard, dt, b.span, 1e9, tr, c);
              return c;
            };
          }
          best = std::min(best, t.cpu);
          break;
        }
      }
    }
  }

  // periflex: rk4 and verlet over the dt ladder, dopri54 over the tolerance ladder, projection
  best = kInf;
  double best_periflex = kInf;
  auto try_scene = [&](const SceneDef& scene, const std::string& setting, Stall& stall) {
    Trial t{"periflex", setting};
    double cpu = 0;
    const bool finished = run_periflex(scene, b.span, budget(), track, cpu);
    if (finished) {
      t.cpu = cpu;
      t.error = track_error(track, b.error);
    }
    print_trial(t);
    if (finished && t.passed() && t.cpu < best_periflex) {
      best_periflex = t.cpu;
      choice.periflex = t;
      choice.time_periflex = [&b, scene] {
        Track tr;
        double c = 0;
        run_periflex(scene, b.span, 1e9, tr, c);
        return c;
      };
    }
    if (finished && t.passed()) best = std::min(best, t.cpu);
    return finished && !stall.stalled(t.error) ? (t.passed() ? 1 : 0) : -1;
  };
  for (const char* integrator : {"rk4", "verlet"}) {
    Stall stall;
    for (double dt : b.fixed_steps) {
      SceneDef scene = b.scene;
      scene.solver.integrator = integrator;
      scene.solver.dt = dt;
      if (try_scene(scene, std::string(integrator) + " + projection, dt " + number(dt), stall) != 0) break;
    }
  }
  Stall stall;
  for (double rtol : b.tolerances) {
    SceneDef scene = b.scene;
    scene.solver.integrator = "dopri54";
    scene.solver.dt = b.dopri_macro;
    scene.solver.rtol = rtol;
    scene.solver.atol = 1e-2 * rtol;
    if (try_scene(scene, "dopri54 + projection, rtol " + number(rtol) + ", dt " + number(b.dopri_macro), stall) != 0)
      break;
  }
  return choice;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The chosen settings timed again, alternately, `repeats` times each: the ratio of the medians.
void report(const Benchmark& b, const Choice& c, int repeats) {
  if (!c.time_mujoco || !c.time_periflex) {
    std::printf("%s: %s reached no setting within %g m\n\n", b.name.c_str(),
                c.time_mujoco ? "periflex" : "MuJoCo", kTarget);
    return;
  }
  std::vector<double> mj, pf;
  for (int r = 0; r < repeats; ++r) {
    mj.push_back(c.time_mujoco());
    pf.push_back(c.time_periflex());
  }
  const double tm = median(mj), tp = median(pf);
  std::printf("%s, cheapest settings reaching %g m (median CPU of %d runs each):\n", b.name.c_str(), kTarget,
              repeats);
  std::printf("  MuJoCo   %-40s error %-10.3g CPU %.4f s\n", c.mujoco.setting.c_str(), c.mujoco.error, tm);
  std::printf("  periflex %-40s error %-10.3g CPU %.4f s\n", c.periflex.setting.c_str(), c.periflex.error, tp);
  std::printf("  ratio periflex / MuJoCo = %.2f\n\n", tp / tm);
}

std::vector<double> ladder(double largest, double smallest) {
  // four rungs per halving
  std::vector<double> out;
  for (double dt = largest; dt >= smallest * (1 - 1e-9); dt /= std::pow(2.0, 0.25)) out.push_back(dt);
  return out;
}

std::vector<double> tolerance_ladder(double loosest, double tightest) {
  // four rungs per decade
  std::vector<double> out;
  for (int k = 0;; ++k) {
    const double rtol = loosest * std::pow(10.0, -0.25 * k);
    if (rtol < tightest * (1 - 1e-9)) break;
    out.push_back(rtol);
  }
  return out;
}

MujocoModel load_mujoco(const char* file) {
  MujocoModel mm;
  char error[1000] = "";
  mm.model = mj_loadXML(file, nullptr, error, sizeof error);
  if (!mm.model) {
    std::fprintf(stderr, "mujoco_compare: cannot load %s: %s\n", file, error);
    std::exit(2);
  }
  if (mm.model->neq > 0) {
    for (int k = 0; k < 2; ++k) {
      mm.solimp0[k] = mm.model->eq_solimp[k];
      mm.solref0[k] = mm.model->eq_solref[k];
    }
  }
  return mm;
}

// The mapped point against MuJoCo's own kinematics at a few angles (the MJCF and the map agree).
void check_point_map(const MujocoModel& mm, const char* site) {
  const int id = mj_name2id(mm.model, mjOBJ_SITE, site);
  mjData* d = mj_makeData(mm.model);
  for (double a : {0.0, 0.7, 2.5}) {
    d->qpos[0] = a;
    for (int k = 1; k < mm.model->nq; ++k) d->qpos[k] = k % 2 ? -a : a;  // the parallelogram's angles
    mj_kinematics(mm.model, d);
    double x = 0, y = 0;
    mm.point(a, x, y);
    if (id < 0 || std::hypot(d->site_xpos[3 * id] - x, d->site_xpos[3 * id + 2] - y) > 1e-12) {
      std::fprintf(stderr, "mujoco_compare: site '%s' of the model does not match the benchmark's point\n", site);
      std::exit(2);
    }
  }
  mj_deleteData(d);
}

}  // namespace
}  // namespace periflex

int main(int argc, char** argv) {
  using namespace periflex;
  if (argc < 3) {
    std::fprintf(stderr, "usage: mujoco_compare <a01.xml> <a02.xml> [--quick] [--only=a01|a02]\n");
    return 2;
  }
  bool quick = false;
  std::string only;  // "a01" or "a02": that benchmark alone
  for (int k = 3; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--quick") {
      quick = true;
    } else if (arg.rfind("--only=", 0) == 0) {
      only = arg.substr(7);
    } else {
      std::fprintf(stderr, "mujoco_compare: unknown option '%s' (--quick, --only=a01|a02)\n", arg.c_str());
      return 2;
    }
  }
  omp_set_num_threads(1);
  const std::string root = PERIFLEX_SOURCE_ROOT;

  // A01: one hinge about y at the origin; the bob starts at (1, 0, 0) and falls along -z
  MujocoModel a01 = load_mujoco(argv[1]);
  a01.qvel0 = {0.0};
  a01.point = [](double a, double& x, double& y) {
    x = std::cos(a);
    y = -std::sin(a);
  };
  check_point_map(a01, "bob");
  // A02: crank0's hinge angle from the upright; B0 = (sin a, cos a)
  MujocoModel a02 = load_mujoco(argv[2]);
  a02.qvel0 = {1.0, -1.0, 1.0, -1.0, 1.0};
  a02.point = [](double a, double& x, double& y) {
    x = std::sin(a);
    y = std::cos(a);
  };
  check_point_map(a02, "b0");

  std::printf("MuJoCo %s, periflex %s, one thread, CPU time of the process\n\n", mj_versionString(),
              PERIFLEX_VERSION);

  Benchmark b1;
  b1.name = "A01 pendulum";
  b1.span = quick ? 200.0 : 2000.0;
  b1.mujoco = &a01;
  b1.scene = load_scene(root + "/scenes/benchmarks/a01_pendulum.toml");
  b1.scene.solver.threads = 1;
  const auto exact = make_pendulum_exact(b1.scene);
  b1.error = [&exact](const Track& tr) {
    double worst = 0;
    for (size_t k = 0; k < tr.t.size(); ++k) {
      const auto r = exact->probe_values(tr.t[k]);
      worst = std::max(worst, std::hypot(tr.x[k] - r[0], tr.y[k] - r[1]));
    }
    return worst;
  };
  b1.fixed_steps = ladder(0.1, 1e-4);
  b1.tolerances = tolerance_ladder(1e-5, 1e-11);
  b1.dopri_macro = 0.1;
  b1.cap = quick ? 2.0 : 10.0;

  Benchmark b2;
  b2.name = "A02 double four-bar";
  b2.span = 10.0;
  b2.mujoco = &a02;
  b2.scene = load_scene(root + "/scenes/benchmarks/a02_double_four_bar.toml");
  b2.scene.solver.threads = 1;
  const FourBarReference four_bar(b2.span + 0.1);
  b2.error = [&four_bar](const Track& tr) {
    double worst = 0;
    for (size_t k = 0; k < tr.t.size(); ++k) worst = std::max(worst, std::abs(tr.x[k] - four_bar.b0_x(tr.t[k])));
    return worst;
  };
  b2.fixed_steps = ladder(0.05, 1e-5);
  b2.tolerances = tolerance_ladder(1e-2, 1e-8);
  b2.dopri_macro = 0.05;
  b2.cap = quick ? 2.0 : 10.0;

  const int repeats = quick ? 1 : 5;
  Choice c1, c2;
  if (only != "a02") c1 = search(b1);
  if (only != "a01") c2 = search(b2);
  std::printf("\n");
  if (only != "a02") report(b1, c1, repeats);
  if (only != "a01") report(b2, c2, repeats);
  return 0;
}
