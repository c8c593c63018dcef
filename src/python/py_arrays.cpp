#include "python/py_arrays.h"

#include <stdexcept>

#include "output/series_row.h"
#include "python/py_simulation.h"
#include "scene/scene_budget.h"

namespace py = pybind11;

namespace periflex::pyarrays {

namespace {

PySimulation& unwrap(py::object self) { return py::cast<PySimulation&>(self); }

// A read-only array over memory the simulation owns; the view keeps that simulation alive (also
// after set() has built the model again and the Python object holds another).
py::array readonly_view(const double* data, long rows, long cols, py::object self) {
  using Shared = std::shared_ptr<Simulation>;
  py::capsule keeper(new Shared(unwrap(self).shared_sim()), [](void* p) { delete static_cast<Shared*>(p); });
  py::array out(py::dtype::of<double>(), {rows, cols},
                {static_cast<long>(cols * sizeof(double)), static_cast<long>(sizeof(double))}, data, keeper);
  out.attr("setflags")(py::arg("write") = false);
  return out;
}

template <class T>
py::array readonly_copy(py::array_t<T> a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

long rigid_body_count(const Simulation& sim) { return sim.info().bodies; }

// Where the particles' coordinates start in q: after x, y, angle of each rigid body. Checked
// against the size of q, so a change of layout is an error, not a wrong view.
long particle_offset(const Simulation& sim) {
  const long offset = 3 * rigid_body_count(sim);
  if (offset + 2 * sim.info().particles != sim.coordinates().size())
    throw std::logic_error("the coordinates are not rigid bodies' then particles' (size " +
                           std::to_string(sim.coordinates().size()) + ")");
  return offset;
}

}  // namespace

py::array positions(py::object self) {
  const Simulation& sim = unwrap(self).sim();
  return readonly_view(sim.coordinates().data() + particle_offset(sim), sim.info().particles, 2, self);
}

py::array velocities(py::object self) {
  const Simulation& sim = unwrap(self).sim();
  return readonly_view(sim.velocities().data() + particle_offset(sim), sim.info().particles, 2, self);
}

py::array body_poses(py::object self) {
  const Simulation& sim = unwrap(self).sim();
  particle_offset(sim);
  return readonly_view(sim.coordinates().data(), rigid_body_count(sim), 3, self);
}

py::array body_velocities(py::object self) {
  const Simulation& sim = unwrap(self).sim();
  particle_offset(sim);
  return readonly_view(sim.velocities().data(), rigid_body_count(sim), 3, self);
}

py::array reference_positions(PySimulation& sim) {
  const std::vector<double>& xy = sim.snapshot().geometry->reference_xy;
  py::array_t<double> out({static_cast<long>(xy.size() / 2), 2L});
  std::copy(xy.begin(), xy.end(), out.mutable_data());
  return readonly_copy(out);
}

py::array displacement(PySimulation& sim) {
  const std::vector<double>& xy = sim.snapshot().geometry->reference_xy;
  const Simulation& s = sim.sim();
  const double* q = s.coordinates().data() + particle_offset(s);
  py::array_t<double> out({static_cast<long>(xy.size() / 2), 2L});
  double* d = out.mutable_data();
  for (size_t k = 0; k < xy.size(); ++k) d[k] = q[k] - xy[k];
  return readonly_copy(out);
}

py::array damage(PySimulation& sim) {
  const std::vector<float>& v = sim.snapshot().damage;
  py::array_t<float> out(static_cast<long>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return readonly_copy(out);
}

py::array broken_bonds(PySimulation& sim) {
  const Snapshot& snap = sim.snapshot();
  const std::vector<uint16_t>& initial = snap.geometry->bonds_initial;
  py::array_t<int32_t> out(static_cast<long>(initial.size()));
  int32_t* o = out.mutable_data();
  for (size_t k = 0; k < initial.size(); ++k)
    o[k] = static_cast<int32_t>(initial[k]) - (k < snap.bonds_intact.size() ? snap.bonds_intact[k] : initial[k]);
  return readonly_copy(out);
}

py::list flex_bodies(PySimulation& sim) {
  py::list out;
  for (const auto& f : sim.snapshot().geometry->flex_bodies) {
    py::dict d;
    d["name"] = f.name;
    d["first_particle"] = f.first_particle;
    d["particle_count"] = f.particle_count;
    d["grid_spacing"] = f.grid_spacing;
    out.append(d);
  }
  return out;
}

py::list body_names(PySimulation& sim) {
  py::list out;
  const auto& bodies = sim.snapshot().geometry->bodies;
  for (size_t k = 1; k < bodies.size(); ++k) out.append(bodies[k].name);  // ground first, left out
  return out;
}

py::dict series_row(PySimulation& sim) {
  const Simulation& s = sim.sim();
  const bool with_damage = s.info().particles > 0, with_contact = !s.scene().contacts.empty();
  const std::vector<std::string> columns = series_columns(s);
  std::vector<double> values;
  series_values(s.sample(), with_damage, with_contact, values);
  py::dict out;
  for (size_t k = 0; k < columns.size() && k < values.size(); ++k) out[py::str(columns[k])] = values[k];
  return out;
}

py::dict series_units(PySimulation& sim) {
  py::dict out;
  for (const std::string& c : series_columns(sim.sim())) out[py::str(c)] = series_unit(c);
  return out;
}

py::dict check_report(PySimulation& py_sim) {
  Simulation& sim = py_sim.sim();
  // as `periflex check`: initial conditions made consistent first (this finds redundant
  // constraints); a failure there is raised as the program reports it. Once: a simulation that
  // has stepped keeps its state (the figures are the first initialisation's)
  py_sim.initialize_once();
  const ModelInfo& m = sim.info();
  const SceneDef& scene = sim.scene();
  py::dict d;
  d["scene"] = scene.name;
  d["path"] = scene.path;
  d["description"] = scene.description;
  d["rigid_bodies"] = m.bodies;
  d["virtual_bodies"] = m.virtual_bodies;
  d["joints"] = m.joints;
  d["drivers"] = m.drivers;
  d["force_elements"] = m.force_elements;
  d["probes"] = m.probes;
  d["flexible_bodies"] = m.flex_bodies;
  d["particles"] = m.particles;
  d["bonds"] = m.bonds;
  py::list models;
  for (const FlexBodyDef& flex : scene.flex_bodies) {
    const PdMaterialDef& mat = flex.material;
    py::dict e;
    e["body"] = flex.name;
    const bool state_based = mat.model == PdMaterialDef::Model::kStateBased;
    e["model"] = state_based ? "state-based (LPS)" : "bond-based";
    e["plane"] = mat.plane_strain ? "plane strain" : "plane stress";
    e["poisson_ratio"] = state_based ? mat.poisson_ratio : (mat.plane_strain ? 0.25 : 1.0 / 3.0);
    models.append(e);
  }
  d["peridynamic_models"] = models;
  d["coordinates"] = m.coordinates;
  d["constraint_equations"] = m.constraint_equations;
  d["redundant_equations"] = m.redundant_equations;
  d["redundant_constraints"] = m.redundant_constraints;
  d["degrees_of_freedom"] = m.degrees_of_freedom;
  d["active_modules"] = m.active_modules;
  d["integrator"] = scene.solver.integrator;
  d["dt"] = scene.solver.dt;
  d["end_time"] = scene.solver.end_time;
  d["critical_time_step"] = m.critical_time_step > 0 ? py::cast(m.critical_time_step) : py::none();
  if (m.flex_bodies > 0) {
    const SceneBudget budget = check_scene_budget(scene);
    d["memory_estimate"] = budget.memory;
    d["memory_limit"] = memory_cap(scene.limits);
  } else {
    d["memory_estimate"] = py::none();
    d["memory_limit"] = py::none();
  }
  d["initial_position_correction"] = m.initial_position_correction;
  d["initial_velocity_correction"] = m.initial_velocity_correction;
  std::vector<std::string> warnings = py_sim.scene_warnings();
  warnings.insert(warnings.end(), m.warnings.begin(), m.warnings.end());
  d["warnings"] = warnings;
  return d;
}

}  // namespace periflex::pyarrays
