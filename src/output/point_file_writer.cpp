#include "output/point_file_writer.h"

#include <algorithm>
#include <charconv>
#include <vector>

#include "output/atomic_file.h"
#include "pd/cloud_grid.h"

namespace periflex {

namespace {

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

// The block each body's points are written in: a body with materials by block keeps its file's
// blocks (so that its [[flex_body.block_material]] tables read the file back); every other body is
// one block, numbered from 1 in scene order, after the largest block such a body keeps.
std::vector<long> body_blocks(const SceneDef& scene) {
  long next = 1;
  for (const FlexBodyDef& def : scene.flex_bodies)
    if (!def.block_materials.empty())
      for (long block : def.particles->block) next = std::max(next, block + 1);
  std::vector<long> blocks;
  for (const FlexBodyDef& def : scene.flex_bodies) blocks.push_back(def.block_materials.empty() ? next++ : -1);
  return blocks;
}

}  // namespace

std::string point_file_text(const SceneDef& scene) {
  std::string out = "# periflex points of scene '" + scene.name + "': reference x, y [m], volume [m^3] " +
                    "(grid_spacing^2 x thickness unless a graded file gave its own), block (the flexible body, " +
                    "or a body's own blocks when they carry materials), no_fail (1: bonds never break)\n";
  const std::vector<long> blocks = body_blocks(scene);
  for (size_t b = 0; b < scene.flex_bodies.size(); ++b) {
    const FlexBodyDef& def = scene.flex_bodies[b];
    out += blocks[b] >= 0 ? "# block " + std::to_string(blocks[b]) + ": flexible body '" + def.name + "'"
                          : "# its file's blocks: flexible body '" + def.name + "' (materials by block)";
    out += ", grid_spacing ";
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
    for (int i = 0; i < grid.size(); ++i) {
      append_number(out, grid.x[i]);
      out += ',';
      append_number(out, grid.y[i]);
      out += ',';
      append_number(out, grid.volume.empty() ? volume : grid.volume[i]);
      out += ',';
      out += std::to_string(blocks[b] >= 0 ? blocks[b] : def.particles->block[i]);
      out += no_fail[i] ? ",1\n" : ",0\n";
    }
  }
  return out;
}

void write_point_file(const std::string& path, const SceneDef& scene) {
  write_file_atomically(path, point_file_text(scene));
}

}  // namespace periflex
