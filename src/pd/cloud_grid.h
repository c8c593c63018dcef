// The particles of a flexible body given one by one (a point file, an image): one particle at
// each point, in the cloud's order, with the grid indices of its node (scene/cloud_lattice.h)
// so that bonds keep whole grid offsets as on a filled shape.
#pragma once

#include <cstdint>

#include "pd/particle_grid.h"
#include "scene/particle_cloud.h"
#include "scene/scene_def.h"

namespace periflex {

// Throws InputError (naming the file's line) for two coincident points or a volume far from
// dx^2 thickness (scene/cloud_lattice.h). Points off the grid of spacing dx make a grid with
// on_grid false; volumes other than dx^2 thickness are kept per particle.
ParticleGrid grid_from_cloud(const ParticleCloud& cloud, double dx, double thickness);

// Moves each particle by up to jitter spacings in x and in y (uniform, from the seed and the
// particle's index alone); any jitter > 0 leaves the grid off the grid.
void jitter_particles(ParticleGrid& grid, double jitter, uint64_t seed);

// The particles of a flexible body as PdBody::build places them: its cloud, or its shape filled,
// then jittered when the body asks for it.
ParticleGrid body_particles(const FlexBodyDef& def);

// 1 for each particle of `grid` whose bonds never break: inside a no-fail region of the body,
// or marked by its point file or image.
std::vector<uint8_t> body_no_fail(const FlexBodyDef& def, const ParticleGrid& grid);

}  // namespace periflex
