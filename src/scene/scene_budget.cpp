#include "scene/scene_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

#include "core/sim_time.h"
#include "scene/cloud_lattice.h"
#include "scene/grid_scan.h"
#include "scene/integrator_catalogue.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace {

// Large figures in a short form ("4.2e+13").
std::string figure(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

[[noreturn]] void refuse(const SourceLocation& where, const std::string& message) { throw InputError(where, message); }

// Where a flexible body's key was set: its line, or the --set that changed it.
SourceLocation flex_key(const SceneDef& scene, const FlexBodyDef& flex, const std::string& key) {
  const std::string dotted = "flex_body." + flex.name + "." + key;
  if (scene.origin.count(dotted)) return scene.locate(dotted);
  SourceLocation where = flex.where;
  where.key = dotted;
  return where;
}

// The key to blame for a body's bonds and bytes: the one a --set changed, else grid_spacing.
SourceLocation size_key(const SceneDef& scene, const FlexBodyDef& flex) {
  for (const char* key : {"grid_spacing", "horizon_ratio"}) {
    const SourceLocation where = flex_key(scene, flex, key);
    if (where.file == "--set") return where;
  }
  return flex_key(scene, flex, "grid_spacing");
}

// Particles and stored neighbours (each bond counted from both ends) of a flexible body, exact:
// the runs of cells the filling scan visits, and for every grid offset within the neighbour
// search's reach the cells whose partner at that offset is a cell too (runs of row j against the
// runs of row j + b shifted by a). Linear in the runs; a thin sliver, whose particles are mostly
// near an edge with a fraction of an interior particle's neighbours, is counted as it is.
struct BodyCount {
  double particles = 0.0, neighbours = 0.0;
  bool off_grid = false;  // bonds keep their own lengths (kBytesPerNeighborOffGrid more each)
};

// Neighbours within `reach` spacings of a particle: the grid offsets in that disc (on the grid),
// or its area (off it, where the points are as dense on average but not on whole offsets).
double neighbours_per_particle(double reach, bool on_grid) {
  const long r = static_cast<long>(std::ceil(reach)) + 1;
  double offsets = 0.0;
  for (long b = -r; b <= r; ++b)
    for (long a = -r; a <= r; ++a)
      if (!(a == 0 && b == 0) && double(a * a + b * b) <= reach * reach * (1 + 1e-9)) offsets += 1.0;
  return on_grid ? offsets : std::max(offsets, kPi * reach * reach);
}

// A body of particles given one by one: its count, and as neighbours an interior particle's count
// for every particle (an upper bound on the grid). Where a graded file gives volumes of their own,
// a particle of volume V sees about cell / V times as many (its neighbourhood is as finely
// divided as it is).
BodyCount count_cloud(const FlexBodyDef& flex) {
  BodyCount count;
  const ParticleCloud& cloud = *flex.particles;
  count.particles = static_cast<double>(cloud.size());
  const double reach = flex.horizon_ratio + (flex.partial_volume_correction ? 0.5 : 0.0);
  const CloudLattice lattice = cloud_nodes(cloud, flex.grid_spacing, flex.thickness, cloud.source);
  count.off_grid = !lattice.on_grid || flex.jitter > 0.0;
  const double per_particle = neighbours_per_particle(reach, !count.off_grid);
  if (lattice.cell_volumes) {
    count.neighbours = count.particles * per_particle;
    return count;
  }
  const double cell = flex.grid_spacing * flex.grid_spacing * flex.thickness;
  for (long k = 0; k < cloud.size(); ++k) count.neighbours += per_particle * std::max(1.0, cell / cloud.volume[k]);
  return count;
}

BodyCount count_particles_and_neighbours(const FlexBodyDef& flex, const GridFrame& frame) {
  if (flex.particles) return count_cloud(flex);
  // runs by row, rows in increasing order
  std::vector<long> row_of;                      // row index j of each stored row
  std::vector<std::vector<std::pair<long, long>>> runs;
  BodyCount count;
  scan_grid(flex.shape, flex.holes, frame, {}, [&](long j, long begin, long end) {
    if (row_of.empty() || row_of.back() != j) {
      row_of.push_back(j);
      runs.emplace_back();
    }
    runs.back().emplace_back(begin, end);
    count.particles += static_cast<double>(end - begin);
  });
  // the offsets the neighbour search finds (pd_body.cpp): |offset| <= reach, in cells
  const double reach = flex.horizon_ratio + (flex.partial_volume_correction ? 0.5 : 0.0);
  const long r = static_cast<long>(std::ceil(reach)) + 1;
  for (long b = -r; b <= r; ++b) {
    for (long a = -r; a <= r; ++a) {
      if ((a == 0 && b == 0) || double(a * a + b * b) > reach * reach * (1 + 1e-9)) continue;
      // rows j and j + b (targets increase with j, so one pointer walks the rows once)
      size_t other = 0;
      for (size_t k = 0; k < row_of.size(); ++k) {
        const long target = row_of[k] + b;
        while (other < row_of.size() && row_of[other] < target) ++other;
        if (other >= row_of.size() || row_of[other] != target) continue;
        const auto& here = runs[k];
        const auto& there = runs[other];
        size_t p = 0, q = 0;
        while (p < here.size() && q < there.size()) {
          // cell i of row j pairs with cell i + a of row j + b
          const long lo = std::max(here[p].first, there[q].first - a);
          const long hi = std::min(here[p].second, there[q].second - a);
          if (hi > lo) count.neighbours += static_cast<double>(hi - lo);
          if (here[p].second < there[q].second - a) ++p;
          else ++q;
        }
      }
    }
  }
  return count;
}

// Instants k * interval in [0, end_time], k = 0, 1, ...: the rows or frames a schedule lands on
// (cli/run_command.cpp), counted with the tolerance the run's clock uses (core/sim_time.h).
double schedule_instants(double end_time, double interval, double dt) {
  return std::floor((end_time + time_tolerance(dt, end_time)) / interval) + 1.0;
}

// The scene's time-stepping figures: dt against end_time, steps, rows, frames.
void check_time(const SceneDef& scene, const RunPlan& plan, SceneBudget& budget) {
  const SolverDef& s = scene.solver;
  const LimitsDef& l = scene.limits;
  const IntegratorTraits* traits = find_integrator(s.integrator);
  const bool adaptive = traits != nullptr && traits->is_adaptive;
  const bool dt_given = scene.origin.count("solver.dt") != 0;
  if (s.dt > s.end_time)
    refuse(scene.locate(dt_given ? "solver.dt" : "solver.end_time"),
           "dt = " + format_number(s.dt) + " exceeds end_time = " + format_number(s.end_time) +
               "; the run would not take a single step");

  // fixed steps: at least end_time / dt whole ones (more where a step is cut short to land on
  // an output time)
  budget.steps = std::ceil(s.end_time / s.dt - 1e-9);
  // blame the value the command line gave, if one did
  const bool until_flag = scene.locate("solver.end_time").file == "command line" &&
                          scene.locate("solver.dt").file != "command line";
  const SourceLocation steps_key = scene.locate(until_flag ? "solver.end_time" : "solver.dt");
  if (!adaptive && !(budget.steps <= l.max_steps))
    refuse(steps_key, "the run would take " + format_count(budget.steps) + " steps (end_time " +
                          format_number(s.end_time) + " s / dt " + format_number(s.dt) +
                          " s), more than limits.max_steps = " + format_count(l.max_steps) +
                          "; raise dt, lower end_time, or raise limits.max_steps");

  // rows of series.csv: one at each output time, plus the last state when the end is not one.
  // Without an interval, a row every tenth step.
  const double interval = s.output_interval > 0.0 ? s.output_interval : 10.0 * s.dt;
  const bool rows_given = s.output_interval > 0.0;
  if (adaptive && !rows_given) {
    budget.rows = 0.0;
  } else {
    budget.rows = schedule_instants(s.end_time, interval, s.dt);
    if (!time_reached((budget.rows - 1) * interval, s.end_time, s.dt)) budget.rows += 1;
  }
  // an interval shorter than a fixed step writes a row after every step, but the schedule still
  // counts its output times, so they are what is bounded (a tiny interval is refused, not run)
  const bool every_step = !adaptive && interval < s.dt * (1 - 1e-9);
  if (!(budget.rows <= l.max_output_rows))
    refuse(rows_given ? scene.locate("solver.output_interval") : steps_key,
           (every_step ? "an output interval of " + format_number(interval) + " s (shorter than dt = " +
                             format_number(s.dt) + " s) counts " + format_count(budget.rows) + " output times"
                       : "series.csv would get " + format_count(budget.rows) + " rows") +
               ", more than limits.max_output_rows = " + format_count(l.max_output_rows) +
               "; raise solver.output_interval or limits.max_output_rows");

  // rendered frames: only an interval the user gave can be shorter than a step (the default is
  // a whole number of steps)
  if (plan.frame_every > 0.0) {
    if (!adaptive && plan.frame_every_given && plan.frame_every < s.dt * (1 - 1e-9))
      refuse(plan.frame_every_where, "a frame every " + format_number(plan.frame_every) +
                                         " s is shorter than a step (dt = " + format_number(s.dt) +
                                         " s); give at least dt");
    budget.frames = schedule_instants(s.end_time, plan.frame_every, s.dt);
    if (!(budget.frames <= l.max_frames))
      refuse(plan.frame_every_where,
             "the run would render " + format_count(budget.frames) + " frames (one every " +
                 format_number(plan.frame_every) + " s" + (plan.frame_every_given ? "" : ", the default") +
                 "), more than limits.max_frames = " + format_count(l.max_frames) +
                 (plan.frame_every_given ? "; give a longer interval or raise limits.max_frames"
                                         : "; give --frame-every or raise limits.max_frames"));
  }
}

// Particles (exact), bonds and bytes of every flexible body, against the scene's limits.
void check_particles(const SceneDef& scene, SceneBudget& budget) {
  const LimitsDef& l = scene.limits;
  std::vector<double> body_memory;  // bytes per body
  for (const FlexBodyDef& flex : scene.flex_bodies) {
    // the grid must fit its 32-bit indices and be scanned in bounded time
    const Vec2 extent = grid_extent_cells(flex.shape, flex.grid_spacing);
    if (!(extent.maxCoeff() <= 2e9))
      refuse(flex_key(scene, flex, "grid_spacing"), "the grid of flexible body '" + flex.name + "' would span " +
                                                 format_count(std::ceil(extent.maxCoeff())) +
                                                 " cells across, more than 2000000000; raise grid_spacing");
    const GridFrame frame = grid_frame(flex.shape, flex.grid_spacing);
    const double work = grid_scan_work(flex.shape, flex.holes, frame);
    if (!(work <= l.max_grid_rows))
      refuse(flex_key(scene, flex, "grid_spacing"), "placing the particles of flexible body '" + flex.name +
                                                 "' would scan " + format_count(work) +
                                                 " grid rows (rows x shapes, plus the rows polygon edges span), "
                                                 "more than limits.max_grid_rows = " + format_count(l.max_grid_rows) +
                                                 "; raise grid_spacing or simplify the shape");
    // the exact count, by the scan that fills the grid
    BodyCount count = count_particles_and_neighbours(flex, frame);
    // a jittered shape: its particles as dense as on the grid, its neighbours not on whole offsets
    if (!flex.particles && flex.jitter > 0.0) {
      const double reach = flex.horizon_ratio + (flex.partial_volume_correction ? 0.5 : 0.0);
      count.neighbours *= neighbours_per_particle(reach, false) / neighbours_per_particle(reach, true);
      count.off_grid = true;
    }
    const double particles = count.particles;
    budget.particles += particles;
    budget.bonds += count.neighbours / 2;
    const std::string& integrator = scene.solver.integrator;
    body_memory.push_back(particles * (kBytesPerParticle + integrator_bytes_per_particle(integrator)) +
                          count.neighbours * (kBytesPerNeighbor + (count.off_grid ? kBytesPerNeighborOffGrid : 0.0) +
                                              iteration_matrices(scene.solver) *
                                                  integrator_bytes_per_neighbor(integrator)));
    budget.memory += body_memory.back();
    if (!(budget.particles <= l.max_particles))
      refuse(flex_key(scene, flex, "grid_spacing"),
             "flexible body '" + flex.name + "' has " + format_count(particles) + " particles" +
                 (scene.flex_bodies.size() > 1 ? ", bringing the scene to " + format_count(budget.particles)
                                               : std::string()) +
                 ", more than limits.max_particles = " + format_count(l.max_particles) +
                 " for the whole scene; raise grid_spacing or limits.max_particles");
  }
  if (!scene.flex_bodies.empty()) budget.memory += kProgramBytes;
  const double cap = memory_cap(l);
  if (!(budget.memory <= cap)) {
    SourceLocation where = scene.locate("limits.max_memory");
    if (scene.origin.count("limits.max_memory") == 0 && !scene.flex_bodies.empty()) {
      // the body that costs most, at the key that made it so
      const FlexBodyDef* largest = &scene.flex_bodies.front();
      for (size_t k = 0; k < scene.flex_bodies.size(); ++k)
        if (body_memory[k] > body_memory[largest - scene.flex_bodies.data()]) largest = &scene.flex_bodies[k];
      where = size_key(scene, *largest);
    }
    refuse(where, "the flexible bodies need about " + figure(budget.memory / 1e9) + " GB (" + format_count(budget.particles) +
                      " particles, " + format_count(budget.bonds) + " bonds), more than the memory limit of " +
                      figure(cap / 1e9) + " GB; raise grid_spacing, lower horizon_ratio, or set limits.max_memory (bytes)");
  }
}

void check_threads(const SceneDef& scene, const RunPlan& plan) {
  const int cap = thread_cap(scene.limits);
  const std::string why = " threads, more than " + std::to_string(cap) + " (" +
                          (scene.limits.max_threads > 0 ? std::string("limits.max_threads")
                                                        : "4 x the " + std::to_string(machine_cores()) +
                                                              " cores of this machine; limits.max_threads raises it") +
                          ")";
  if (scene.solver.threads > cap)
    refuse(scene.locate("solver.threads"), "solver.threads asks for " + std::to_string(scene.solver.threads) + why);
  if (plan.threads > cap) refuse(plan.threads_where, "asks for " + std::to_string(plan.threads) + why);
}

}  // namespace

double integrator_bytes_per_particle(const std::string& integrator) {
  const IntegratorTraits* traits = find_integrator(integrator);
  return traits != nullptr ? traits->stage_bytes_per_particle : 0.0;
}

int iteration_matrices(const SolverDef& solver) {
  if (!(solver.output_interval > 0.0) || !(solver.dt > 0.0)) return 1;
  const double steps = solver.output_interval / solver.dt;
  return std::abs(steps - std::round(steps)) <= 1e-9 * steps ? 1 : 2;
}

double integrator_bytes_per_neighbor(const std::string& integrator) {
  const IntegratorTraits* traits = find_integrator(integrator);
  return traits != nullptr ? traits->tangent_bytes_per_neighbor : 0.0;
}

int machine_cores() {
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? static_cast<int>(n) : 1;
}

int thread_cap(const LimitsDef& limits) { return limits.max_threads > 0 ? limits.max_threads : 4 * machine_cores(); }

double memory_cap(const LimitsDef& limits) {
  if (limits.max_memory > 0.0) return limits.max_memory;
  // 80% of what the machine has; half of what this process may map (the address space also holds
  // the program, thread stacks, allocator arenas and vectors while they grow)
  double available = 0.8 * static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    available = std::min(available, 0.5 * static_cast<double>(limit.rlim_cur));
  return available > 0.0 ? available : 1e9;
}

SceneBudget check_scene_budget(const SceneDef& scene, const RunPlan& plan) {
  SceneBudget budget;
  check_time(scene, plan, budget);
  check_threads(scene, plan);
  check_particles(scene, budget);
  return budget;
}

}  // namespace periflex
