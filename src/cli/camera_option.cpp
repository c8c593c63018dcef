#include "cli/camera_option.h"

#include <cmath>
#include <cstdio>

namespace periflex {

std::optional<CameraOption> parse_camera_option(const std::string& text) {
  CameraOption out;
  if (text.empty() || text == "grow") return out;
  if (text == "fit") {
    out.mode = CameraOption::Mode::kFit;
    return out;
  }
  double x = 0, y = 0, h = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &x, &y, &h, &tail) != 3 || !std::isfinite(x) ||
      !std::isfinite(y) || !std::isfinite(h) || !(h > 0.0))
    return std::nullopt;
  out.mode = CameraOption::Mode::kFixed;
  out.center_x = x;
  out.center_y = y;
  out.view_height = h;
  return out;
}

std::string camera_option_expected(const std::string& text) {
  return "expected grow, fit, or X,Y,HEIGHT (the view's centre and height in metres, height > 0), not '" + text +
         "'";
}

}  // namespace periflex
