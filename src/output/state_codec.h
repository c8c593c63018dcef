// A SimState as bytes and back, for checkpoint files (output/checkpoint_file.h). Little-endian
// fixed-width fields in the order of docs/state.md; the long arrays of doubles (coordinates,
// velocities, caches) are stored as integer differences of their bit patterns from a prediction
// (the same coordinate of the previous particle, plus the change one grid row before where the
// particles form a grid), zigzag-coded and byte-planed (every value's first byte, then every
// second byte, ...): an evenly spaced grid and a smooth field become runs of zero bytes in the
// high planes, which deflate packs.
#pragma once

#include <cstdint>
#include <vector>

#include "solve/sim_state.h"

namespace periflex {

// The bytes of `state`.
std::vector<uint8_t> encode_state(const SimState& state);

// The state in `bytes`. Throws std::runtime_error saying what is malformed (a size that runs
// past the end, bytes left over) for bytes encode_state did not write.
SimState decode_state(const uint8_t* bytes, size_t size);

}  // namespace periflex
