#include "python/py_render.h"

#include <cmath>
#include <stdexcept>

#include "cli/gui_command.h"
#include "core/error.h"
#include "python/py_simulation.h"

#ifdef PERIFLEX_WITH_HEADLESS
#include "headless/offscreen_renderer.h"
#include "render/view.h"
#endif

namespace py = pybind11;

namespace periflex::pyrender {

bool available() {
#ifdef PERIFLEX_WITH_HEADLESS
  return true;
#else
  return false;
#endif
}

#ifndef PERIFLEX_WITH_HEADLESS

py::array render(PySimulation&, const PyRenderRequest&) {
  throw std::runtime_error("render: this build has no off-screen renderer (configured with -DPERIFLEX_HEADLESS=OFF)");
}

#else

namespace {

InputError bad_argument(const std::string& name, const std::string& what) {
  return InputError({"", 0, 0, name}, what);
}

// The request's settings, checked as `periflex run` checks --field, --deform and --size.
RenderSettings render_settings(const PyRenderRequest& request) {
  if (request.width < 16 || request.height < 16 || request.width > 8192 || request.height > 8192)
    throw bad_argument("width, height", "expected 16 <= width, height <= 8192, not " + std::to_string(request.width) +
                                            " x " + std::to_string(request.height));
  RenderSettings settings;
  if (!parse_field_name(request.field, settings.field))
    throw bad_argument("field", "unknown field '" + request.field + "'; expected damage, displacement, speed or strain");
  double deform = -1.0;
  if (!parse_deform(request.deform, deform)) throw bad_argument("deform", parse_deform_check(request.deform));
  settings.deform = static_cast<float>(deform);
  if (!request.colormap.empty()) settings.colormap = request.colormap;
  settings.show_overlay = request.overlay;
  return settings;
}

// The screenshot's camera (headless/recorder.cpp): fitted to the scene, then widened to what is
// drawn now when it has left that view; or the one asked for.
Camera picture_camera(const Snapshot& snapshot, const PyRenderRequest& request) {
  if (!request.camera.empty()) {
    const auto& c = request.camera;
    if (c.size() != 3 || !std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]) || c[2] <= 0.0)
      throw bad_argument("camera", "expected (x, y, view height) in metres, the height > 0");
    Camera camera;
    camera.center = Vec2(c[0], c[1]);
    camera.view_height = c[2];
    return camera;
  }
  Camera camera = fit_camera(snapshot, request.width, request.height);
  widen_to_show(camera, snapshot, request.width, request.height);
  return camera;
}

}  // namespace

py::array render(PySimulation& sim, const PyRenderRequest& request) {
  const RenderSettings settings = render_settings(request);
  // a copy: the drawing runs without the interpreter, while another thread may read the fields
  const Snapshot snapshot = sim.picture_snapshot();
  const Camera camera = picture_camera(snapshot, request);
  const long particles = static_cast<long>(snapshot.px.size());
  const int samples = request.samples > 0 ? request.samples : default_samples(particles);
  const std::string root = request.resource_root.empty() ? find_resource_root() : request.resource_root;

  RgbaImage image;
  {
    // a context of its own for each picture, made and dropped on this thread: the renderer's
    // automatic magnification and range are then this picture's alone, as in a screenshot
    py::gil_scoped_release release;
    OffscreenRenderer offscreen(request.width, request.height, samples, root);
    offscreen.render(snapshot, camera, settings, image);
  }
  py::array_t<uint8_t> out({static_cast<long>(image.height), static_cast<long>(image.width), 3L});
  uint8_t* rgb = out.mutable_data();
  const size_t pixels = static_cast<size_t>(image.width) * image.height;
  for (size_t k = 0; k < pixels; ++k)
    for (int c = 0; c < 3; ++c) rgb[3 * k + c] = image.pixels[4 * k + c];
  return out;
}

#endif

}  // namespace periflex::pyrender
