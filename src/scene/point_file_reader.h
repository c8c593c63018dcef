// Point files: a discretisation given particle by particle, as peridynamic codes exchange them
// (PDMATLAB2D inputs, PeriLab's and Peridigm's text meshes). One point a line:
//
//   x, y, volume[, block[, no_fail]]        (commas, or blanks in a .txt file)
//
// '#' starts a comment; blank lines are skipped; a first line of words (x,y,volume,...) is a
// header. Lengths are in the file's unit (PointFileOptions::scale converts them to metres, the
// volume by its cube). block selects points (several bodies from one file); no_fail = 1 marks a
// particle whose bonds never break. Every error names the file and the line.
#pragma once

#include <string>

#include "scene/particle_cloud.h"

namespace periflex {

struct PointFileOptions {
  double scale = 1.0;            // metres per unit of the file
  long block = -1;               // keep only the points of this block; -1: every point
  double max_points = 2e7;       // refused (before any point is stored) above this many lines
};

// Reads the file. Throws InputError naming the file and line: a row that is not 3 to 5 numbers,
// a volume that is not positive, a block or no_fail that is not a whole number, more data lines
// than max_points (counted before anything is stored), no point at all (in the block).
ParticleCloud read_point_file(const std::string& path, const PointFileOptions& options);

}  // namespace periflex
