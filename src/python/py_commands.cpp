#include "python/py_commands.h"

#include <omp.h>
#include <pybind11/stl.h>

#include <csignal>
#include <exception>
#include <mutex>
#include <stdexcept>

#include "cli/interrupt.h"
#include "cli/run_command.h"
#include "cli/sweep_command.h"
#include "core/error.h"
#include "study/refine_study.h"
#include "study/study_def.h"
#include "study/study_report.h"
#include "study/study_runner.h"
#include "study/sweep_def.h"

namespace py = pybind11;

namespace periflex::pycommands {

namespace {

// One command at a time in this process: they share the interrupt flag and OpenMP's thread count.
std::mutex command_mutex;

// While a command runs: the interpreter released, the program's handlers of SIGINT, SIGTERM and
// SIGHUP in place of the interpreter's (a Ctrl-C stops the command between two steps, its
// outputs closed, as in the program), OpenMP's thread count kept. All put back afterwards.
class AsTheProgram {
 public:
  AsTheProgram() : lock_(command_mutex) {
    for (int k = 0; k < 3; ++k) sigaction(kSignals[k], nullptr, &saved_[k]);
    threads_ = omp_get_max_threads();
  }
  ~AsTheProgram() {
    omp_set_num_threads(threads_);
    for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &saved_[k], nullptr);
  }
  AsTheProgram(const AsTheProgram&) = delete;
  AsTheProgram& operator=(const AsTheProgram&) = delete;

 private:
  static constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
  py::gil_scoped_release release_;  // first: the lock is waited for without the interpreter
  std::unique_lock<std::mutex> lock_;
  struct sigaction saved_[3] = {};
  int threads_ = 1;
};

// After a command stopped by a signal: KeyboardInterrupt for Ctrl-C (the others end the
// interpreter as they would have).
void raise_when_interrupted(int exit_code) {
  const int signal_number = pending_interrupt();
  if (signal_number == 0 || exit_code != interrupt_exit_code(signal_number)) return;
  if (signal_number == SIGINT) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  std::raise(signal_number);
}

py::dict study_row(const StudyRow& r) {
  py::dict d;
  d["integrator"] = r.integrator;
  d["correction"] = r.correction;
  d["dt"] = r.dt;
  d["tol"] = r.tol;
  d["error_max"] = r.error_max;
  d["error_rms"] = r.error_rms;
  d["error_max_rel"] = r.error_max_rel;
  d["error_rms_rel"] = r.error_rms_rel;
  d["energy_error"] = r.energy_error;
  d["energy_error_rel"] = r.energy_error_rel;
  d["violation"] = r.violation;
  d["crack_tip_error"] = r.crack_tip_error;
  d["broken_bond_error"] = r.broken_bond_error;
  d["wall_time"] = r.wall_time;
  d["steps"] = r.steps;
  d["status"] = r.status;
  d["energy_trace"] = r.energy_trace;
  d["grid_spacing"] = r.grid_spacing;
  d["horizon_ratio"] = r.horizon_ratio;
  d["particles"] = r.particles;
  d["measured"] = r.measured;
  d["expected"] = r.expected;
  return d;
}

py::dict study_table(const StudyResult& result, const StudyOutputs& files) {
  py::list rows, orders;
  for (const StudyRow& r : result.rows) rows.append(study_row(r));
  for (const ObservedOrder& o : result.orders) {
    py::dict d;
    d["integrator"] = o.integrator;
    d["correction"] = o.correction;
    d["against_tolerance"] = o.against_tolerance;
    d["slope"] = o.slope;
    d["points"] = o.points;
    d["theory"] = o.theory;
    orders.append(d);
  }
  py::dict out;
  out["name"] = result.study.name;
  out["scene"] = result.scene_name;
  out["reference"] = result.reference_description;
  out["reference_error"] = result.reference_error;
  out["reference_wall_time"] = result.reference_wall_time;
  out["excursion"] = result.excursion;
  out["times"] = result.times;
  out["quantity"] = result.quantity;
  out["quantity_unit"] = result.quantity_unit;
  out["rows"] = rows;
  out["orders"] = orders;
  py::dict written;
  written["csv"] = files.csv_path;
  written["markdown"] = files.markdown_path;
  written["plot"] = files.plot_path.empty() ? py::object(py::none()) : py::str(files.plot_path);
  written["energy_plot"] = files.energy_plot_path.empty() ? py::object(py::none()) : py::str(files.energy_plot_path);
  out["files"] = written;
  return out;
}

// `periflex run`: the exit code and the output folder; a run stopped by an error raises it (after
// its outputs and summary.json are written, as the program leaves them).
py::tuple run(const RunOptions& options) {
  RunOutcome outcome;
  {
    AsTheProgram program;
    outcome = run_and_report(options);
  }
  raise_when_interrupted(outcome.exit_code);
  if (outcome.failure) std::rethrow_exception(outcome.failure);
  return py::make_tuple(outcome.exit_code, outcome.out_dir);
}

// `periflex study`: the rows of study.csv and the observed orders, the files written.
py::dict study(const std::string& path, const std::string& out_dir, int repeats, bool quiet) {
  StudyResult result;
  StudyOutputs files;
  bool stopped_in_reference = false;
  {
    AsTheProgram program;
    StudyDef def = load_study(path);
    if (repeats > 0) def.repeats = repeats;
    const std::string out = out_dir.empty() ? "out/study-" + def.name : out_dir;
    const StudyLog log = [&](const std::string& line) {
      if (!quiet) std::printf("  %s\n", line.c_str());
      std::fflush(stdout);
    };
    catch_interrupts();
    const StudyStop stop = [] { return pending_interrupt() != 0; };
    try {
      result = def.mode == StudyDef::Mode::kRefine ? run_refine_study(def, log, stop) : run_study(def, log, stop);
      files = write_study_outputs(result, out);
    } catch (const StudyStopped&) {
      stopped_in_reference = true;
    }
  }
  if (stopped_in_reference || result.stopped) raise_when_interrupted(interrupt_exit_code(pending_interrupt()));
  return study_table(result, files);
}

// `periflex sweep`: the exit code and the sweep folder, whose sweep.csv holds the table.
py::tuple sweep(SweepOptions options) {
  if (options.out_dir.empty() && options.collect_dir.empty())
    options.out_dir = "out/sweep-" + load_sweep(options.sweep_path).name;
  int exit_code = 0;
  {
    AsTheProgram program;
    exit_code = sweep_or_throw(options);
  }
  raise_when_interrupted(exit_code);
  return py::make_tuple(exit_code, options.collect_dir.empty() ? options.out_dir : options.collect_dir);
}

}  // namespace

void bind(py::module_& m) {
  py::class_<RunOptions>(m, "_RunOptions", "The options of `periflex run` (cli/run_command.h).")
      .def(py::init<>())
      .def_readwrite("scene_path", &RunOptions::scene_path)
      .def_readwrite("overrides", &RunOptions::overrides)
      .def_readwrite("until", &RunOptions::until)
      .def_readwrite("dt", &RunOptions::dt)
      .def_readwrite("integrator", &RunOptions::integrator)
      .def_readwrite("out_dir", &RunOptions::out_dir)
      .def_readwrite("threads", &RunOptions::threads)
      .def_readwrite("quiet", &RunOptions::quiet)
      .def_readwrite("vtk_every", &RunOptions::vtk_every)
      .def_readwrite("checkpoint_every", &RunOptions::checkpoint_every)
      .def_readwrite("checkpoint_dir", &RunOptions::checkpoint_dir)
      .def_readwrite("restart_path", &RunOptions::restart_path)
      .def_readwrite("render", &RunOptions::render)
      .def_readwrite("frame_every", &RunOptions::frame_every)
      .def_readwrite("size_text", &RunOptions::size_text)
      .def_readwrite("samples", &RunOptions::samples)
      .def_readwrite("frames_dir", &RunOptions::frames_dir)
      .def_readwrite("movie_path", &RunOptions::movie_path)
      .def_readwrite("fps", &RunOptions::fps)
      .def_readwrite("snapshot_at", &RunOptions::snapshot_at)
      .def_readwrite("screenshot_path", &RunOptions::screenshot_path)
      .def_readwrite("colormap", &RunOptions::colormap)
      .def_readwrite("field", &RunOptions::field)
      .def_readwrite("camera", &RunOptions::camera)
      .def_readwrite("deform", &RunOptions::deform)
      .def_readwrite("draw_contacts", &RunOptions::draw_contacts)
      .def_readwrite("plot", &RunOptions::plot)
      .def_readwrite("plot_against", &RunOptions::plot_against);
  py::class_<SweepOptions>(m, "_SweepOptions", "The options of `periflex sweep` (cli/sweep_command.h).")
      .def(py::init<>())
      .def_readwrite("sweep_path", &SweepOptions::sweep_path)
      .def_readwrite("out_dir", &SweepOptions::out_dir)
      .def_readwrite("jobs", &SweepOptions::jobs)
      .def_readwrite("jobs_file", &SweepOptions::jobs_file)
      .def_readwrite("collect_dir", &SweepOptions::collect_dir)
      .def_readwrite("quiet", &SweepOptions::quiet)
      .def_readwrite("program", &SweepOptions::program);
  m.def("_run", &run, py::arg("options"));
  m.def("_study", &study, py::arg("path"), py::arg("out_dir"), py::arg("repeats"), py::arg("quiet"));
  m.def("_sweep", &sweep, py::arg("options"));
}

}  // namespace periflex::pycommands
