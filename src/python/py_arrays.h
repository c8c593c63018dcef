// NumPy arrays and dictionaries of a PySimulation's state. Positions, velocities and body poses
// are read-only views of the simulation's own coordinate vectors (no copy: they show the values
// of the moment they are read, and later steps change them); the fields the solver computes
// on demand (displacement, damage, broken bonds) are copies.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace periflex {

class PySimulation;

namespace pyarrays {

// `self` is the Python object of a PySimulation; views keep it alive.
pybind11::array positions(pybind11::object self);        // (particles, 2) float64, view
pybind11::array velocities(pybind11::object self);       // (particles, 2) float64, view
pybind11::array body_poses(pybind11::object self);       // (bodies, 3) x, y, angle, view
pybind11::array body_velocities(pybind11::object self);  // (bodies, 3) vx, vy, omega, view
pybind11::array reference_positions(PySimulation& sim);  // (particles, 2) float64, copy
pybind11::array displacement(PySimulation& sim);         // (particles, 2) x - X, float64, copy
pybind11::array damage(PySimulation& sim);               // (particles,) float32, copy
pybind11::array broken_bonds(PySimulation& sim);         // (particles,) int32, copy
pybind11::list flex_bodies(PySimulation& sim);           // [{name, first, count, grid_spacing}]
pybind11::list body_names(PySimulation& sim);            // rigid bodies in pose order
pybind11::dict series_row(PySimulation& sim);            // the row series.csv would hold now
pybind11::dict series_units(PySimulation& sim);          // each column's unit
pybind11::dict check_report(PySimulation& sim);          // what `periflex check` prints

}  // namespace pyarrays
}  // namespace periflex
