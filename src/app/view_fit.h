// Framing the scene in the part of the window the panels leave free. No GL: the GUI smoke
// test's image checker uses the same functions to find where the crack is drawn.
#pragma once

#include "render/camera.h"
#include "render/view.h"
#include "solve/snapshot.h"

namespace periflex {

// Width in pixels of the panel column on the left of the window.
constexpr int kPanelWidth = 360;

// What a fit frames: the scene's initial bounds grown by everything drawn now.
Bounds framing_bounds(const Snapshot& snapshot);

// A camera showing `box` in a window of width x height pixels whose leftmost `left_inset`
// pixels are covered by panels: the box is centred in the free part.
Camera fit_camera_beside_panels(const Bounds& box, int width, int height, int left_inset);
// The same for framing_bounds(snapshot): the camera the GUI starts with.
Camera fit_camera_beside_panels(const Snapshot& snapshot, int width, int height, int left_inset);

// The camera of a picture without the panels (a screenshot, a recorded frame) of `height`
// pixels: the window's camera moved so what it shows beside the panels is centred.
Camera picture_camera(const Camera& window_camera, int height, int left_inset = kPanelWidth);

// A view that grows to keep a moving scene in sight: everything seen so far, and the box shown
// (what was seen, with a margin once it has grown, so it is not re-framed every frame).
struct Framing {
  Bounds seen, shown;
};
// The framing at a fit: framing_bounds(snapshot), shown as it is.
Framing start_framing(const Snapshot& snapshot);
// Adds what `snapshot` draws; when that leaves the shown box, the shown box becomes the seen one
// grown by `margin` of its size on each side. Returns true when the shown box changed.
bool grow_framing(Framing& framing, const Snapshot& snapshot, double margin = 0.1);

}  // namespace periflex
