// The view of a headless run's frames, as `--camera` gives it: grow (fit the first frame, widen
// when the scene leaves it; the default), fit (fit the first frame and keep it), or a fixed view
// "X,Y,HEIGHT" in metres. Read without the renderer, so the flag is refused before the scene is
// built.
#pragma once

#include <optional>
#include <string>

namespace periflex {

struct CameraOption {
  enum class Mode { kGrow, kFit, kFixed } mode = Mode::kGrow;
  double center_x = 0.0, center_y = 0.0, view_height = 0.0;  // kFixed: finite, height > 0
};

// The view `text` names; nothing when it names none ("" is grow).
std::optional<CameraOption> parse_camera_option(const std::string& text);

// What --camera takes, for its error message.
std::string camera_option_expected(const std::string& text);

}  // namespace periflex
