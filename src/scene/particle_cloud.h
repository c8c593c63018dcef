// Particles given one by one rather than by a shape filled with a grid: what a point file or an
// image brings. The scene layer reads them (scene/point_file_reader.h, scene/image_shape.h) and
// the flexible body places one particle at each (pd/cloud_grid.h), in this order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace periflex {

struct ParticleCloud {
  std::vector<double> x, y;         // reference positions [m]
  std::vector<double> volume;       // [m^3]
  std::vector<uint8_t> no_fail;     // 1: the particle's bonds never break
  std::vector<uint8_t> grip;        // 1: a grip particle (blue in a picture); empty: none
  std::vector<long> block;          // each point's block (a point file's fourth column); empty: none given
  std::vector<long> line;           // where each point came from in its file (0: not from a line)
  std::string source;               // what made it: "points plate.csv", "image specimen.png", ...
  long size() const { return static_cast<long>(x.size()); }
};

}  // namespace periflex
