// Framing the scene in the part of the window the panels leave free. No GL: the GUI smoke
// test's image checker uses the same function to find where the crack is drawn.
#pragma once

#include "render/camera.h"
#include "solve/snapshot.h"

namespace periflex {

// Width in pixels of the panel column on the left of the window.
constexpr int kPanelWidth = 360;

// A camera showing the scene (its initial bounds grown by where the particles are now) for a
// window of width x height pixels whose leftmost `left_inset` pixels are covered by panels:
// the scene is centred in the free part.
Camera fit_camera_beside_panels(const Snapshot& snapshot, int width, int height, int left_inset);

}  // namespace periflex
