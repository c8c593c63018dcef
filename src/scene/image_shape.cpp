#include "scene/image_shape.h"

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "scene/grid_scan.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw InputError(SourceLocation{path, 0, 0, "shape.file"}, message);
}

// What a grid cell stands for.
enum class PixelKind { kVoid, kMaterial, kNoFail, kGrip };

// Relative luminance of a pixel; a transparent pixel counts as white (no material).
double luminance(const unsigned char* rgba) {
  if (rgba[3] < 128) return 1.0;
  return (0.2126 * rgba[0] + 0.7152 * rgba[1] + 0.0722 * rgba[2]) / 255.0;
}

// A clear red pixel: the no-fail colour.
bool is_red(const unsigned char* rgba) { return rgba[3] >= 128 && rgba[0] >= 150 && rgba[1] < 100 && rgba[2] < 100; }
// A clear blue pixel: the grip colour (an [[attachment]] with pixels = "blue" holds these).
bool is_blue(const unsigned char* rgba) { return rgba[3] >= 128 && rgba[2] >= 150 && rgba[0] < 100 && rgba[1] < 100; }

}  // namespace

ParticleCloud read_image_shape(const std::string& path, const ImageShapeOptions& options) {
  // the size from the header first: a huge picture is refused before it is decoded
  int w = 0, h = 0, channels = 0;
  if (!stbi_info(path.c_str(), &w, &h, &channels))
    fail(path, std::string("cannot be read as an image (") + stbi_failure_reason() + ")");
  if (static_cast<double>(w) * h > kMaxImagePixels)
    fail(path, "is " + std::to_string(w) + " x " + std::to_string(h) + " pixels, more than " +
                   format_count(kMaxImagePixels) + "; scale it down");
  const std::unique_ptr<unsigned char, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &channels, 4),
                                                                stbi_image_free);
  if (!pixels) fail(path, std::string("cannot be decoded (") + stbi_failure_reason() + ")");

  // the rectangle the picture covers, and the grid a box of that size would have
  ShapeDef box;
  box.kind = ShapeDef::Kind::kBox;
  box.center = options.center;
  box.width = options.width;
  box.height = options.height > 0.0 ? options.height : options.width * h / w;
  const GridFrame frame = grid_frame(box, options.dx);
  const double left = box.center.x() - 0.5 * box.width, top = box.center.y() + 0.5 * box.height;

  // the picture at each cell centre of the box, visited row by row from the bottom: the
  // luminance interpolated between the four nearest pixel centres (bilinear), so that a cell
  // centre on a pixel boundary weighs both sides alike and a symmetric drawing gives a symmetric
  // body; red (no-fail) or blue (grip) where the pixel under the centre is
  const auto pixel = [&](long u, long v) {
    u = std::clamp(u, 0L, static_cast<long>(w) - 1);
    v = std::clamp(v, 0L, static_cast<long>(h) - 1);
    return pixels.get() + 4 * (v * static_cast<long>(w) + u);
  };
  auto kind_at = [&](const Vec2& p) {
    const double u = (p.x() - left) / box.width * w - 0.5, v = (top - p.y()) / box.height * h - 0.5;
    const double u0 = std::floor(u), v0 = std::floor(v), fu = u - u0, fv = v - v0;
    const long iu = static_cast<long>(u0), iv = static_cast<long>(v0);
    const double lum = (1 - fv) * ((1 - fu) * luminance(pixel(iu, iv)) + fu * luminance(pixel(iu + 1, iv))) +
                       fv * ((1 - fu) * luminance(pixel(iu, iv + 1)) + fu * luminance(pixel(iu + 1, iv + 1)));
    if (!(lum < options.threshold)) return PixelKind::kVoid;
    const unsigned char* under = pixel(static_cast<long>(std::floor(u + 0.5)), static_cast<long>(std::floor(v + 0.5)));
    return is_red(under) ? PixelKind::kNoFail : is_blue(under) ? PixelKind::kGrip : PixelKind::kMaterial;
  };
  auto visit = [&](auto&& on_particle) {
    scan_grid(box, {}, frame, {}, [&](long j, long begin, long end) {
      for (long i = begin; i < end; ++i) {
        const Vec2 p = frame.cell(i, j);
        const PixelKind kind = kind_at(p);
        if (kind != PixelKind::kVoid) on_particle(p, kind);
      }
    });
  };

  // counted before anything is stored
  double count = 0.0;
  visit([&](const Vec2&, PixelKind) { count += 1.0; });
  if (count == 0.0)
    fail(path, "has no material pixel at grid spacing " + format_number(options.dx) +
                   " (material: darker than threshold = " + format_number(options.threshold) +
                   ", or red; is the picture light on dark, or the grid coarser than its strokes?)");
  if (count > options.max_particles)
    fail(path, "gives " + format_count(count) + " particles at grid spacing " + format_number(options.dx) +
                   ", more than limits.max_particles = " + format_count(options.max_particles) +
                   "; raise grid_spacing");

  ParticleCloud cloud;
  cloud.source = "image " + path;
  const double volume = options.dx * options.dx * options.thickness;
  for (auto* v : {&cloud.x, &cloud.y, &cloud.volume}) v->reserve(static_cast<size_t>(count));
  visit([&](const Vec2& p, PixelKind kind) {
    cloud.x.push_back(p.x());
    cloud.y.push_back(p.y());
    cloud.volume.push_back(volume);
    cloud.no_fail.push_back(kind == PixelKind::kNoFail ? 1 : 0);
    cloud.grip.push_back(kind == PixelKind::kGrip ? 1 : 0);
    cloud.line.push_back(0);
  });
  return cloud;
}

}  // namespace periflex
