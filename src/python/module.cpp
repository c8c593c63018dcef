// The compiled part of the Python module periflex (periflex._periflex): the Simulation class and
// the two errors. python/periflex/__init__.py builds the public Simulation on top of it (scenes
// from paths, TOML text or dicts; overrides as a dict).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "core/error.h"
#include "core/resources.h"
#include "python/py_arrays.h"
#include "python/py_commands.h"
#include "python/py_render.h"
#include "python/py_simulation.h"
#include "python/py_step_method.h"
#include "solve/simulation.h"

namespace py = pybind11;
using namespace periflex;

namespace {

// The Python classes of the errors, made once when the module is imported (kept for the
// interpreter's life, as the translator may run at any time after).
PyObject* input_error_type = nullptr;
PyObject* numerical_error_type = nullptr;

// Raises `type` with the program's message and the fields a script may want apart.
void raise_with(PyObject* type, const char* message, py::dict fields) {
  py::object error = py::reinterpret_borrow<py::object>(type)(message);
  for (auto item : fields) error.attr(item.first) = item.second;
  PyErr_SetObject(type, error.ptr());
}

void translate_errors(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const InputError& e) {
    const SourceLocation& at = e.where();
    py::dict fields;
    fields["file"] = at.file;
    fields["line"] = at.line;
    fields["column"] = at.column;
    fields["key"] = at.key;
    fields["detail"] = e.detail();
    raise_with(input_error_type, e.what(), fields);
  } catch (const NumericalError& e) {
    const NumericalDiagnostic& d = e.diagnostic();
    py::dict fields;
    fields["quantity"] = d.quantity;
    fields["step"] = d.step;
    fields["time"] = d.time;
    fields["cause"] = d.cause;
    fields["remedy"] = d.remedy;
    raise_with(numerical_error_type, e.what(), fields);
  }
}

SceneSource make_source(const std::string& path, const std::string& text, const std::string& display_name) {
  SceneSource s;
  s.path = path;
  s.text = text;
  s.display_name = display_name.empty() ? "<string>" : display_name;
  return s;
}

py::dict live_settings(const PySimulation& sim) {
  const LiveSettings s = sim.sim().settings();
  static const char* methods[] = {"none", "baumgarte", "projection"};
  py::dict d;
  d["integrator"] = s.integrator;
  d["dt"] = s.dt;
  d["correction"] = methods[static_cast<int>(s.correction.method)];
  d["alpha"] = s.correction.alpha;
  d["beta"] = s.correction.beta;
  d["tolerance"] = s.correction.tolerance;
  d["max_iterations"] = s.correction.max_iterations;
  d["bond_damping"] = s.bond_damping;
  d["global_damping"] = s.global_damping;
  d["fracture"] = s.fracture;
  return d;
}

}  // namespace

PYBIND11_MODULE(_periflex, m) {
  m.doc() = "The compiled core of periflex: use the package periflex, not this module.";
  m.attr("__version__") = PERIFLEX_VERSION;

  input_error_type = PyErr_NewExceptionWithDoc(
      "periflex.InputError",
      "Bad scene input or a refused value, with the program's message (file:line:column: key "
      "'...': what is wrong). Attributes: file, line, column, key, detail.",
      PyExc_ValueError, nullptr);
  numerical_error_type = PyErr_NewExceptionWithDoc(
      "periflex.NumericalError",
      "A numerical failure, with the program's diagnostic. Attributes: quantity, step, time, "
      "cause, remedy.",
      PyExc_RuntimeError, nullptr);
  m.attr("InputError") = py::handle(input_error_type);
  m.attr("NumericalError") = py::handle(numerical_error_type);
  py::register_exception_translator(translate_errors);

  pycommands::bind(m);
  m.def("_recorded_scene", &recorded_scene, py::arg("checkpoint_path"));
  m.def("_program_resource_root", [] { return find_resource_root(); },
        "Where the program finds shaders/, assets/ and scenes/ ($PERIFLEX_ROOT, then the source tree).");
  m.def("render_available", &pyrender::available, "True when this build draws pictures (Simulation.render).");
  m.def("integrator_names", &integrator_names, "The integrators this build offers (solver.integrator).");

  py::class_<PySimulation> simulation(m, "_Simulation", "The compiled simulation; periflex.Simulation wraps it.");
  pystep::bind(simulation);
  simulation
      .def(py::init([](const std::string& path, const std::string& text, const std::string& display_name,
                       const std::vector<std::string>& overrides) {
             return new PySimulation(make_source(path, text, display_name), overrides);
           }),
           py::arg("path"), py::arg("text"), py::arg("display_name"), py::arg("overrides"))
      .def("advance_to", &PySimulation::advance_to, py::arg("t"),
           "Step up to exactly time t [s], the last step shortened to land on it (as the program's "
           "output instants). Interruptible like step().")
      .def_property_readonly("time", [](const PySimulation& s) { return s.sim().time(); }, "Simulated time [s].")
      .def_property_readonly("steps", [](const PySimulation& s) { return s.sim().step_count(); },
                             "Steps taken so far.")
      .def_property_readonly("end_time", [](const PySimulation& s) { return s.sim().end_time(); },
                             "The scene's solver.end_time [s].")
      .def_property_readonly("scene_name", [](const PySimulation& s) { return s.sim().scene().name; })
      .def_property_readonly("scene_warnings", &PySimulation::scene_warnings,
                             "Warnings the program prints when it loads the scene.")
      .def("check", &pyarrays::check_report,
           "What `periflex check` prints, as a dict: the model's counts (bodies, joints, particles, "
           "bonds, coordinates, constraint equations, degrees of freedom), the peridynamic models, "
           "the integrator, dt, the critical time step, the memory estimate, the initial "
           "corrections and the warnings. Makes the initial conditions consistent first; raises "
           "InputError or NumericalError where `periflex check` exits with 2 or 3.")
      .def_property_readonly("positions", &pyarrays::positions,
                             "Particle positions [m], shape (particles, 2): a read-only view of the "
                             "simulation's coordinates (no copy; it follows later steps).")
      .def_property_readonly("velocities", &pyarrays::velocities,
                             "Particle velocities [m/s], shape (particles, 2): a read-only view.")
      .def_property_readonly("body_poses", &pyarrays::body_poses,
                             "Rigid bodies' x [m], y [m], angle [rad], shape (bodies, 3), ground "
                             "excluded, in the order of body_names: a read-only view.")
      .def_property_readonly("body_velocities", &pyarrays::body_velocities,
                             "Rigid bodies' vx, vy [m/s], omega [rad/s], shape (bodies, 3): a read-only view.")
      .def_property_readonly("body_names", &pyarrays::body_names, "Rigid bodies' names, in pose order.")
      .def_property_readonly("reference_positions", &pyarrays::reference_positions,
                             "Particle positions at the start [m], shape (particles, 2) (a copy).")
      .def_property_readonly("displacement", &pyarrays::displacement,
                             "positions - reference_positions [m], shape (particles, 2) (a copy).")
      .def_property_readonly("damage", &pyarrays::damage,
                             "Damage of each particle in [0, 1] (float32, a copy): 1 - intact / "
                             "initial bond weight.")
      .def_property_readonly("broken_bonds", &pyarrays::broken_bonds,
                             "Bonds of each particle broken so far (int32, a copy).")
      .def_property_readonly("flex_bodies", &pyarrays::flex_bodies,
                             "The flexible bodies: name, first_particle, particle_count, grid_spacing.")
      .def("series_row", &pyarrays::series_row,
           "The row series.csv would hold now, as {column: value} (units: series_units()).")
      .def("series_units", &pyarrays::series_units, "The unit of each series_row() column.")
      .def_property_readonly("settings", &live_settings, "The live settings (what set() changes).")
      .def("_set", &PySimulation::set, py::arg("key"), py::arg("value"))
      .def(
          "save_state",
          [](const PySimulation& s) {
            const std::vector<uint8_t> bytes = s.save_state();
            return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
          },
          "The whole state as bytes. restore_state() of them makes the following steps repeat "
          "the ones after the save bit for bit (same settings, same thread count).")
      .def(
          "restore_state",
          [](PySimulation& s, py::bytes state) {
            const std::string_view view = state;
            s.restore_state(reinterpret_cast<const uint8_t*>(view.data()), view.size());
          },
          py::arg("state"), "Put back a state save_state() returned (ValueError for another model's).")
      .def("write_checkpoint", &PySimulation::write_checkpoint, py::arg("path"),
           "Write the state to a checkpoint file (the format of `periflex run --checkpoint-every`).")
      .def("restore_checkpoint", &PySimulation::restore_checkpoint, py::arg("path"),
           "Put back the state of a checkpoint file written for this scene and overrides "
           "(InputError naming the file otherwise).")
      .def(
          "_render",
          [](PySimulation& s, int width, int height, const std::string& field, const std::string& deform,
             const std::string& colormap, int samples, bool overlay, const std::vector<double>& camera,
             const std::string& resource_root) {
            PyRenderRequest r;
            r.width = width;
            r.height = height;
            r.field = field;
            r.deform = deform;
            r.colormap = colormap;
            r.samples = samples;
            r.overlay = overlay;
            r.camera = camera;
            r.resource_root = resource_root;
            return pyrender::render(s, r);
          },
          py::arg("width"), py::arg("height"), py::arg("field"), py::arg("deform"), py::arg("colormap"),
          py::arg("samples"), py::arg("overlay"), py::arg("camera"), py::arg("resource_root"));
}
