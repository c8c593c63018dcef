#include "headless/offscreen_renderer.h"

#include <algorithm>
#include <stdexcept>

#include "headless/egl_context.h"
#include "render/gl.h"
#include "render/view.h"

namespace periflex {

struct OffscreenRenderer::Impl {
  int width = 0, height = 0, samples = 1;
  EglContext egl;  // first member: created first, destroyed last
  GLuint draw_fbo = 0, draw_color = 0, draw_depth = 0;   // what the scene is drawn into
  GLuint read_fbo = 0, read_color = 0;                   // single-sample copy for glReadPixels
  std::unique_ptr<Renderer> renderer;

  void make_framebuffers();
  void draw(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings,
            const OverlayPlot* plot = nullptr);
};

void OffscreenRenderer::Impl::make_framebuffers() {
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples = std::clamp(samples, 1, std::max(1, static_cast<int>(max_samples)));

  // colour (+ depth) renderbuffers of the requested size; multisampled when asked
  auto make = [&](GLuint& fbo, GLuint& color, GLuint* depth, int n) {
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    if (n > 1)
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_RGBA8, width, height);
    else
      glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    if (depth) {
      glGenRenderbuffers(1, depth);
      glBindRenderbuffer(GL_RENDERBUFFER, *depth);
      if (n > 1)
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_DEPTH24_STENCIL8, width, height);
      else
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, *depth);
    }
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("off-screen framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                               " (" + std::to_string(n) + " samples) is incomplete: status " + std::to_string(status));
  };
  make(draw_fbo, draw_color, &draw_depth, samples);
  if (samples > 1) make(read_fbo, read_color, nullptr, 1);
  check_gl("off-screen framebuffer set-up");
}

void OffscreenRenderer::Impl::draw(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings,
                                   const OverlayPlot* plot) {
  glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo);
  renderer->draw(snapshot, camera, settings, width, height);
  renderer->draw_overlay(snapshot, settings, width, height, 0, plot);
}

OffscreenRenderer::OffscreenRenderer(int width, int height, int samples, const std::string& resource_root)
    : impl_(std::make_unique<Impl>()) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    throw std::runtime_error("off-screen size " + std::to_string(width) + "x" + std::to_string(height) +
                             " is out of range");
  Impl& m = *impl_;
  m.width = width;
  m.height = height;
  m.samples = samples;
  m.make_framebuffers();
  m.renderer = std::make_unique<Renderer>(resource_root);
}

OffscreenRenderer::~OffscreenRenderer() {
  Impl& m = *impl_;
  m.egl.make_current();
  m.renderer.reset();
  for (GLuint f : {m.draw_fbo, m.read_fbo})
    if (f) glDeleteFramebuffers(1, &f);
  for (GLuint r : {m.draw_color, m.draw_depth, m.read_color})
    if (r) glDeleteRenderbuffers(1, &r);
}

void OffscreenRenderer::render(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings,
                               RgbaImage& out, const OverlayPlot* plot) {
  Impl& m = *impl_;
  m.draw(snapshot, camera, settings, plot);
  // resolve the samples into the single-sample buffer, then read it
  GLuint source = m.draw_fbo;
  if (m.samples > 1) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m.draw_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m.read_fbo);
    glBlitFramebuffer(0, 0, m.width, m.height, 0, 0, m.width, m.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    source = m.read_fbo;
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, source);
  if (out.width != m.width || out.height != m.height) out.resize(m.width, m.height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, m.width, m.height, GL_RGBA, GL_UNSIGNED_BYTE, out.pixels.data());
  check_gl("off-screen read-back");
  // GL's first row is the bottom one
  flip_rows(out);
  // the picture is opaque whatever alpha blending left in the buffer
  for (size_t i = 3; i < out.pixels.size(); i += 4) out.pixels[i] = 255;
}

RgbaImage OffscreenRenderer::render(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings) {
  RgbaImage out;
  render(snapshot, camera, settings, out);
  return out;
}

void OffscreenRenderer::draw_only(const Snapshot& snapshot, const Camera& camera, const RenderSettings& settings) {
  impl_->draw(snapshot, camera, settings);
  glFinish();
}

Renderer& OffscreenRenderer::renderer() { return *impl_->renderer; }
int OffscreenRenderer::width() const { return impl_->width; }
int OffscreenRenderer::height() const { return impl_->height; }
int OffscreenRenderer::samples() const { return impl_->samples; }
const std::string& OffscreenRenderer::description() const { return impl_->egl.description(); }

RgbaImage render_snapshot_image(const Snapshot& snapshot, const RenderSettings& settings, int width, int height,
                                const Camera* camera) {
  OffscreenRenderer offscreen(width, height);
  const Camera cam = camera ? *camera : fit_camera(snapshot, width, height);
  return offscreen.render(snapshot, cam, settings);
}

}  // namespace periflex
