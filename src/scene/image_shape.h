// A specimen drawn in any paint program: the picture, stretched over a rectangle of the scene,
// is sampled at the body's grid spacing; a grid cell whose centre is darker than a threshold (the
// luminance interpolated between the four nearest pixels) is material. Red pixels (material too)
// mark particles whose bonds never break. PNG, BMP, JPEG and the other formats stb_image reads.
#pragma once

#include <string>

#include "core/vec2.h"
#include "scene/particle_cloud.h"

namespace periflex {

struct ImageShapeOptions {
  Vec2 center = Vec2::Zero();   // of the rectangle the picture covers [m]
  double width = 0.0;           // [m]
  double height = 0.0;          // [m]; 0: from the picture's aspect ratio
  double threshold = 0.5;       // relative luminance below which a pixel is material
  double dx = 0.0;              // grid spacing
  double thickness = 1.0;       // particle volume = dx^2 thickness
  double max_particles = 2e7;   // refused, before any particle is stored, above this
};

// Samples the picture at `path`. Throws InputError naming the file: unreadable, larger than
// kMaxImagePixels, no material pixel at this grid spacing, or more particles than allowed.
ParticleCloud read_image_shape(const std::string& path, const ImageShapeOptions& options);

// Largest picture accepted (pixels), checked from its header before it is decoded.
constexpr double kMaxImagePixels = 1e8;

}  // namespace periflex
