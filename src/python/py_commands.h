// periflex.run(), periflex.study() and periflex.sweep(): the program's commands (src/cli,
// src/study) called in the interpreter's process, as the program calls them, with the
// interpreter's Ctrl-C handed to them while they run. Their tables are read back by the Python
// side (python/periflex/_commands.py).
#pragma once

#include <pybind11/pybind11.h>

namespace periflex::pycommands {

// Adds RunOptions, SweepOptions and the functions _run, _study, _sweep to the module.
void bind(pybind11::module_& m);

}  // namespace periflex::pycommands
