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

// What a pixel stands for.
enum class PixelKind { kVoid, kMaterial, kNoFail };

PixelKind classify(const unsigned char* rgba, double threshold) {
  const int r = rgba[0], g = rgba[1], b = rgba[2], a = rgba[3];
  if (a < 128) return PixelKind::kVoid;  // transparent: no material
  // a clear red (the no-fail colour) before the darkness test
  if (r >= 150 && g < 100 && b < 100) return PixelKind::kNoFail;
  const double luminance = (0.2126 * r + 0.7152 * g + 0.0722 * b) / 255.0;
  return luminance < threshold ? PixelKind::kMaterial : PixelKind::kVoid;
}

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

  // the pixel under each cell of the box (nearest), visited row by row from the bottom
  auto kind_at = [&](const Vec2& p) {
    const long u = std::clamp(static_cast<long>(std::floor((p.x() - left) / box.width * w)), 0L, static_cast<long>(w) - 1);
    const long v = std::clamp(static_cast<long>(std::floor((top - p.y()) / box.height * h)), 0L, static_cast<long>(h) - 1);
    return classify(pixels.get() + 4 * (v * static_cast<long>(w) + u), options.threshold);
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
    cloud.line.push_back(0);
  });
  return cloud;
}

}  // namespace periflex
