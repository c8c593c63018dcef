// VTK XML unstructured-grid files (.vtu, ASCII) of the particles of a snapshot, for ParaView.
// Each particle is a VTK_VERTEX cell carrying point data: displacement (vector, from the
// reference grid), speed, damage and strain (largest bond stretch). Files are written under a
// temporary name and renamed, so a run killed part-way leaves only complete files.
#pragma once

#include <string>

#include "solve/snapshot.h"

namespace periflex {

// The .vtu document of the particles of `snapshot` (empty grid when it has none).
std::string vtu_document(const Snapshot& snapshot);

// Writes vtu_document(snapshot) to `path` atomically. Throws std::runtime_error on failure.
void write_vtu(const std::string& path, const Snapshot& snapshot);

}  // namespace periflex
