// VTK XML files of a snapshot, for ParaView and VTK readers:
//   particles (.vtu, unstructured grid): one VTK_VERTEX cell per particle; Float64 positions and
//     point data: displacement and velocity (3-vectors, z = 0), displacement_magnitude, speed,
//     damage, strain (largest bond stretch), volume [m^3] and body (index of the flexible body);
//   rigid bodies (.vtp, polydata): each shape of each body as a polygon at the body's pose, with
//     cell data body (index, 0 = ground), virtual (1 for virtual bodies), position (the body's
//     reference point, a 3-vector) and angle [rad].
// Values are stored as raw little-endian binary in an appended block (UInt64 sizes), so files
// are compact and keep every digit. Both carry the time and the step as field data TIME and STEP. Files are written
// under a temporary name and renamed, so a run killed part-way leaves only complete files.
// docs/running.md lists the arrays.
#pragma once

#include <string>

#include "solve/snapshot.h"

namespace periflex {

// The .vtu document of the particles of `snapshot` (an empty grid when it has none). Positions
// and velocities come from snapshot.particle_q / particle_qd when filled (full precision), else
// from the float arrays.
std::string vtu_document(const Snapshot& snapshot);

// The .vtp document of the rigid bodies' shapes (ground included) at their poses.
std::string vtp_bodies_document(const Snapshot& snapshot);

// Write the documents above to `path` atomically. Throw std::runtime_error on failure.
void write_vtu(const std::string& path, const Snapshot& snapshot);
void write_vtp_bodies(const std::string& path, const Snapshot& snapshot);

}  // namespace periflex
