// Writing files so that a reader (or a run killed half-way) never sees a partial file:
// the content goes to "<path>.tmp" and is renamed over <path> once complete.
#pragma once

#include <string>
#include <string_view>

namespace periflex {

// Writes `content` to `path` atomically. Throws std::runtime_error naming the path on failure.
void write_file_atomically(const std::string& path, std::string_view content);

// Overwrites the file at `path` with `content` where it stands, without a second file: for a
// full disk, where write_file_atomically finds no room for its temporary. Only when the file's
// blocks already hold room for all of `content`, so that the overwrite needs no new space
// (true); false otherwise, the file untouched when it lacks the room. A reader may see it
// half-written.
bool overwrite_in_place(const std::string& path, std::string_view content);

// Creates `dir` and its parents. Throws std::runtime_error naming the directory on failure.
void ensure_directory(const std::string& dir);

}  // namespace periflex
