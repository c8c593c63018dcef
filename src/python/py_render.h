// sim.render(): a picture of a simulation's state now, drawn by the program's off-screen
// renderer (EGL, no display) in the interpreter's own process, as `periflex run --snapshot-at`
// draws its screenshot: the same camera (fitted to the scene), the same colours, the same
// overlay, the same multisampling, so the same pixels for the same state and size.
#pragma once

#include <pybind11/numpy.h>

#include <optional>
#include <string>
#include <vector>

namespace periflex {

class PySimulation;

// What a picture shows; the defaults are `periflex run --snapshot-at`'s.
struct PyRenderRequest {
  int width = 1280, height = 720;
  std::string field = "damage";        // damage | displacement | speed | strain
  std::string deform = "auto";         // "auto" or a magnification K in [0, 1e6], as --deform
  std::string colormap;                // empty: the renderer's default
  int samples = 0;                     // multisamples per pixel; 0: as the program chooses
  bool overlay = true;                 // time, scene name, legend, scale bar
  std::vector<double> camera;          // empty: fitted to the scene; else x, y, view height [m]
  std::string resource_root;           // shaders and colour maps; empty: find_resource_root()
};

namespace pyrender {

// An array of shape (height, width, 3), uint8, rows top to bottom. Throws InputError naming
// the argument for a bad field, deform, size or camera; std::runtime_error when the build has
// no off-screen renderer or EGL cannot make a context.
pybind11::array render(PySimulation& sim, const PyRenderRequest& request);

// True when this build draws pictures (EGL).
bool available();

}  // namespace pyrender
}  // namespace periflex
