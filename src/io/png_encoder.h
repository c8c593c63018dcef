// PNG files for rendered frames, compressed by libdeflate. No shared state: any number of threads
// may encode at once.
#pragma once

#include <cstdint>
#include <vector>

namespace periflex {

// Encodes width x height 8-bit RGBA pixels (rows top to bottom, 4 * width bytes each, no padding)
// as a PNG file in memory. Pictures whose alpha is 255 everywhere are stored as RGB (they decode
// to the same RGBA), others as RGBA. Throws std::invalid_argument for an empty picture (width or
// height below 1).
std::vector<uint8_t> encode_png_rgba(const uint8_t* pixels, int width, int height);

}  // namespace periflex
