// Renders Snapshots to RGBA images without a window: an EGL context, a framebuffer object of the
// requested size (multisampled, resolved before reading) and the ordinary Renderer, which draws
// the overlay too. Use it on the thread that created it.
#pragma once

#include <memory>
#include <string>

#include "core/resources.h"
#include "io/image.h"
#include "render/renderer.h"

namespace periflex {

class OffscreenRenderer {
 public:
  // width x height pixels; samples = 1 turns multisampling off. Throws std::runtime_error when EGL,
  // the framebuffer, the shaders or the colour maps are not available.
  OffscreenRenderer(int width, int height, int samples = 4,
                    const std::string& resource_root = find_resource_root());
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  // Draws the snapshot (and the overlay when settings.show_overlay, with the plot when one is
  // given) and reads the picture back into out, rows top to bottom.
  void render(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings, RgbaImage& out,
              const OverlayPlot* plot = nullptr);
  RgbaImage render(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings);
  // Draws without reading back (glFinish waits for the picture): for measuring drawing alone.
  void draw_only(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings);

  Renderer& renderer();
  int width() const;
  int height() const;
  int samples() const;
  // EGL platform, GL version and renderer string.
  const std::string& description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One picture of one snapshot at width x height (a temporary off-screen context). The camera is
// fitted to the scene's initial bounds when none is given.
RgbaImage render_snapshot_image(const Snapshot& snapshot, const RenderSettings& settings, int width, int height,
                                const Camera* camera = nullptr);

}  // namespace periflex
