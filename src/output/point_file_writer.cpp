#include "output/point_file_writer.h"

#include <charconv>

#include "output/atomic_file.h"
#include "pd/cloud_grid.h"

namespace periflex {

namespace {

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

}  // namespace

std::string point_file_text(const SceneDef& scene) {
  std::string out = "# periflex points of scene '" + scene.name + "': reference x, y [m], volume [m^3] " +
                    "(grid_spacing^2 x thickness unless a graded file gave its own), block (the flexible body), " +
                    "no_fail (1: bonds never break)\n";
  for (size_t b = 0; b < scene.flex_bodies.size(); ++b) {
    const FlexBodyDef& def = scene.flex_bodies[b];
    out += "# block " + std::to_string(b + 1) + ": flexible body '" + def.name + "', grid_spacing ";
    append_number(out, def.grid_spacing);
    out += " m, thickness ";
    append_number(out, def.thickness);
    out += " m\n";
  }
  out += "x,y,volume,block,no_fail\n";
  for (size_t b = 0; b < scene.flex_bodies.size(); ++b) {
    const FlexBodyDef& def = scene.flex_bodies[b];
    const ParticleGrid grid = body_particles(def);
    const std::vector<uint8_t> no_fail = body_no_fail(def, grid);
    const double volume = def.grid_spacing * def.grid_spacing * def.thickness;
    std::string tail(1, ',');
    tail += std::to_string(b + 1);
    tail += ',';
    for (int i = 0; i < grid.size(); ++i) {
      append_number(out, grid.x[i]);
      out += ',';
      append_number(out, grid.y[i]);
      out += ',';
      append_number(out, grid.volume.empty() ? volume : grid.volume[i]);
      out += tail;
      out += no_fail[i] ? "1\n" : "0\n";
    }
  }
  return out;
}

void write_point_file(const std::string& path, const SceneDef& scene) {
  write_file_atomically(path, point_file_text(scene));
}

}  // namespace periflex
