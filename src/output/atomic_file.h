// Writing files so that a reader (or a run killed half-way) never sees a partial file:
// the content goes to "<path>.tmp" and is renamed over <path> once complete.
#pragma once

#include <string>
#include <string_view>

namespace periflex {

// Writes `content` to `path` atomically. Throws std::runtime_error naming the path on failure.
void write_file_atomically(const std::string& path, std::string_view content);

// Creates `dir` and its parents. Throws std::runtime_error naming the directory on failure.
void ensure_directory(const std::string& dir);

}  // namespace periflex
