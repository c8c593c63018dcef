// Simulation.step as a method of the C API's fast calling convention, beside pybind11's others.
#pragma once

#include <pybind11/pybind11.h>

#include "python/py_simulation.h"

namespace periflex::pystep {

// Defines `step(n=1)` on the class: the same PySimulation::step, its errors translated by the
// module's translators as pybind11's own methods translate theirs.
void bind(pybind11::class_<PySimulation>& cls);

}  // namespace periflex::pystep
