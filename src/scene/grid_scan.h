// The square grid a flexible body's particles sit on, and a scan of it that visits only the
// cells inside a shape: row by row, each row as runs of consecutive cells. The same scan counts
// the particles before anything is allocated (the budget) and fills them (pd/particle_grid.h),
// so the count is exact; its work grows with the rows and the particles, never with the
// shape's bounding box.
//
//   const GridFrame frame = grid_frame(shape, dx);
//   scan_grid(shape, holes, frame, {}, [&](long j, long begin, long end) { ... cells [begin, end) of row j });
#pragma once

#include <functional>
#include <vector>

#include "scene/scene_def.h"

namespace periflex {

// Cell centres origin + dx (i, j), 0 <= i < nx, 0 <= j < ny, centred on the shape's bounds.
struct GridFrame {
  Vec2 origin = Vec2::Zero();
  double dx = 0.0;
  long nx = 0, ny = 0;
  // Position of cell (i, j), computed the one way every inside test uses.
  Vec2 cell(long i, long j) const {
    return origin + dx * Vec2(static_cast<double>(i), static_cast<double>(j));
  }
};

// Axis-aligned bounds of a shape.
void shape_bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi);

// Cells across x and y the frame of `shape` at `dx` would have (a double: it may be huge).
Vec2 grid_extent_cells(const ShapeDef& shape, double dx);

// The frame of `shape` at spacing dx. The extent must fit in a long (check grid_extent_cells).
GridFrame grid_frame(const ShapeDef& shape, double dx);

// Rows times shapes visited, plus the rows each polygon edge spans: the work of one scan, known
// before scanning.
double grid_scan_work(const ShapeDef& shape, const std::vector<ShapeDef>& holes, const GridFrame& frame,
                      const std::vector<ShapeDef>& inside = {});

// Called with each run [begin, end) of consecutive cells of row j; rows in increasing j.
using CellRunVisitor = std::function<void(long j, long begin, long end)>;

// Visits the cells of `frame` inside `shape`, outside every hole and inside every shape of
// `inside`. A cell is inside a shape exactly when ShapeDef::contains says so.
void scan_grid(const ShapeDef& shape, const std::vector<ShapeDef>& holes, const GridFrame& frame,
               const std::vector<ShapeDef>& inside, const CellRunVisitor& visit);

// Number of cells scan_grid visits.
long count_grid_cells(const ShapeDef& shape, const std::vector<ShapeDef>& holes, const GridFrame& frame,
                      const std::vector<ShapeDef>& inside = {});

}  // namespace periflex
