// Combined shapes measured against Clipper (Angus Johnson's polygon clipper, Debian's
// libpolyclipping-dev). The project may use Clipper for `union`, `difference` and `intersection`,
// or its own code where the result is the same; these tests show it is: on every combined shape
// of a shipped scene, on the example of docs/scenes.md and on harder shapes, the particles the
// grid fill places (and the cells the inside test accepts) are the grid cells whose centres lie
// in Clipper's result, but for cells whose centre is within kBoundaryTolerance of an outline.
//
// The Clipper side: boxes, polygons and bars' straight sides exactly, circles (and bars' ends) as
// regular polygons whose chord error is at most half of kBoundaryTolerance, all in integer units
// of 1e-7 grid spacings (kUnitsPerSpacing; rounding at most 5e-8 spacings); the operation by
// Clipper (non-zero fill of its own clean operands); then every cell centre of the grid frame
// tested by Clipper's PointInPolygon against each path of the result, even-odd over the paths
// (outers and holes; a centre outside a path's bounding box is outside that path).
// The fill scans runs of cells (scene/grid_scan.cpp) and never calls the combined inside test
// (scene/shape_boolean.cpp), so both are compared. Each shape's counts and the times of both
// routes are printed and recorded (RecordProperty: --gtest_output=xml keeps them).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <clipper.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "pd/particle_grid.h"
#include "scene/grid_scan.h"
#include "scene/scene_loader.h"
#include "test_shapes.h"

namespace periflex {
namespace clipper_check {

// A centre this close to an operand's outline (in grid spacings) may fall either way: the
// polygonised circles and the integer rounding move the outline by less than this.
constexpr double kBoundaryTolerance = 1e-6;
// Clipper's integer unit: 1e-7 grid spacings (coordinates within 107 spacings of the origin keep
// Clipper to 64-bit products; beyond, it switches to 128-bit ones by itself).
constexpr double kUnitsPerSpacing = 1e7;
// At most this share of a shape's particles may be exceptions.
constexpr double kMostExceptions = 1e-3;

using test::box;
using test::circle;
using test::combined;
using Clock = std::chrono::steady_clock;

ShapeDef polygon(std::vector<Vec2> vertices) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kPolygon;
  s.vertices = std::move(vertices);
  return s;
}

// ---------------------------------------------------------------------------
// Shapes as Clipper paths.

struct Polygoniser {
  double scale = 0.0;  // integer units per metre
  double dx = 0.0;

  ClipperLib::IntPoint point(const Vec2& p) const {
    return {static_cast<ClipperLib::cInt>(std::llround(p.x() * scale)),
            static_cast<ClipperLib::cInt>(std::llround(p.y() * scale))};
  }

  // Vertices of a full circle (or, with a given sweep, an arc) such that the chord error
  // r (1 - cos(pi / n)) stays within half the tolerance.
  int arc_vertices(double r, double sweep) const {
    const double half_step = std::acos(1.0 - 0.5 * kBoundaryTolerance * dx / r);
    return std::max(8, static_cast<int>(std::ceil(sweep / (2.0 * half_step))));
  }
  void arc(ClipperLib::Path& path, const Vec2& c, double r, double from, double sweep) const {
    const int n = arc_vertices(r, sweep);
    const bool closed = sweep >= 2.0 * kPi;
    for (int k = 0; k < (closed ? n : n + 1); ++k) {
      const double t = from + sweep * k / n;
      path.push_back(point(c + r * Vec2(std::cos(t), std::sin(t))));
    }
  }

  // Clean (non-overlapping, counter-clockwise outers) paths of a shape.
  ClipperLib::Paths paths(const ShapeDef& s) const {
    ClipperLib::Path path;
    switch (s.kind) {
      case ShapeDef::Kind::kNone:
        return {};
      case ShapeDef::Kind::kBoolean:
        return combine(s);
      case ShapeDef::Kind::kBox: {
        const Mat2 r = rotation(s.angle);
        const double hw = 0.5 * s.width, hh = 0.5 * s.height;
        for (const Vec2& corner : {Vec2(-hw, -hh), Vec2(hw, -hh), Vec2(hw, hh), Vec2(-hw, hh)})
          path.push_back(point(s.center + r * corner));
        break;
      }
      case ShapeDef::Kind::kCircle:
        arc(path, s.center, s.radius, 0.0, 2.0 * kPi);
        break;
      case ShapeDef::Kind::kBar: {
        // a stadium: the half circle about p2, then the one about p1
        const double a = std::atan2(s.p2.y() - s.p1.y(), s.p2.x() - s.p1.x());
        arc(path, s.p2, s.radius, a - 0.5 * kPi, kPi);
        arc(path, s.p1, s.radius, a + 0.5 * kPi, kPi);
        break;
      }
      case ShapeDef::Kind::kPolygon:
        for (const Vec2& v : s.vertices) path.push_back(point(v));
        break;
    }
    // the inside test of a polygon is even-odd: Clipper's union of the path alone under that rule
    // gives paths the non-zero rule reads alike (SimplifyPolygon would too, but makes them
    // strictly simple, which took 73 ms for a circle of 8000 vertices against 3 ms)
    ClipperLib::Clipper clipper;
    clipper.AddPath(path, ClipperLib::ptSubject, true);
    ClipperLib::Paths clean;
    EXPECT_TRUE(clipper.Execute(ClipperLib::ctUnion, clean, ClipperLib::pftEvenOdd, ClipperLib::pftEvenOdd));
    return clean;
  }

  // A combined shape by Clipper: the operands' clean paths, one operation.
  ClipperLib::Paths combine(const ShapeDef& s) const {
    const auto nz = ClipperLib::pftNonZero;
    ClipperLib::Paths result = paths(s.operands.front());
    for (size_t k = 1; k < s.operands.size(); ++k) {
      ClipperLib::Clipper clipper;
      clipper.AddPaths(result, ClipperLib::ptSubject, true);
      clipper.AddPaths(paths(s.operands[k]), ClipperLib::ptClip, true);
      const ClipperLib::ClipType type = s.combine == ShapeDef::Combine::kUnion          ? ClipperLib::ctUnion
                                        : s.combine == ShapeDef::Combine::kIntersection ? ClipperLib::ctIntersection
                                                                                        : ClipperLib::ctDifference;
      ClipperLib::Paths next;
      EXPECT_TRUE(clipper.Execute(type, next, nz, nz));
      result = std::move(next);
    }
    return result;
  }
};

// ---------------------------------------------------------------------------
// Exact distances to the outlines (what an exception is measured by).

double segment_gap(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Distance from p to the nearest outline of the shape or of any of its operands: where the
// combined shape's outline can be.
double outline_distance(const ShapeDef& s, const Vec2& p) {
  switch (s.kind) {
    case ShapeDef::Kind::kNone:
      return std::numeric_limits<double>::infinity();
    case ShapeDef::Kind::kBoolean: {
      double d = std::numeric_limits<double>::infinity();
      for (const ShapeDef& o : s.operands) d = std::min(d, outline_distance(o, p));
      return d;
    }
    case ShapeDef::Kind::kBox: {
      const Vec2 local = rotation(-s.angle) * (p - s.center);
      const Vec2 q = local.cwiseAbs() - 0.5 * Vec2(s.width, s.height);
      return q.maxCoeff() > 0.0 ? q.cwiseMax(0.0).norm() : -q.maxCoeff();
    }
    case ShapeDef::Kind::kCircle:
      return std::abs((p - s.center).norm() - s.radius);
    case ShapeDef::Kind::kBar:
      return std::abs(segment_gap(p, s.p1, s.p2) - s.radius);
    case ShapeDef::Kind::kPolygon: {
      double d = std::numeric_limits<double>::infinity();
      const size_t n = s.vertices.size();
      for (size_t i = 0, j = n - 1; i < n; j = i++) d = std::min(d, segment_gap(p, s.vertices[j], s.vertices[i]));
      return d;
    }
  }
  return 0.0;
}

// ---------------------------------------------------------------------------
// One shape compared at one spacing.

struct Case {
  std::string name;
  ShapeDef shape;
  std::vector<ShapeDef> holes;
  double dx = 0.0;
};

struct Outcome {
  long in_house = 0, clipper = 0;          // particles
  long fill_exceptions = 0;                // cells where the fill and Clipper differ
  long inside_test_exceptions = 0;         // cells where ShapeDef::contains and Clipper differ
  long far_exceptions = 0;                 // of those, cells beyond the tolerance of any outline
  double fill_us = 0, clipper_op_us = 0, clipper_points_us = 0;
  size_t clipper_vertices = 0;
};

double microseconds(Clock::duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

// Cells of `frame` inside Clipper's result (row-major, j * nx + i).
std::vector<char> clipper_cells(const ClipperLib::Paths& result, const GridFrame& frame, const Polygoniser& poly) {
  // bounding boxes first: a point outside one is outside that path
  struct Bounds {
    ClipperLib::cInt x0, y0, x1, y1;
  };
  std::vector<Bounds> bounds;
  for (const ClipperLib::Path& path : result) {
    Bounds b{path[0].X, path[0].Y, path[0].X, path[0].Y};
    for (const ClipperLib::IntPoint& q : path)
      b = {std::min(b.x0, q.X), std::min(b.y0, q.Y), std::max(b.x1, q.X), std::max(b.y1, q.Y)};
    bounds.push_back(b);
  }
  std::vector<char> inside(static_cast<size_t>(frame.nx * frame.ny), 0);
  for (long j = 0; j < frame.ny; ++j) {
    for (long i = 0; i < frame.nx; ++i) {
      const ClipperLib::IntPoint c = poly.point(frame.cell(i, j));
      // even-odd over the result's paths; a centre on an outline counts as inside that path
      bool in = false;
      for (size_t k = 0; k < result.size(); ++k) {
        const Bounds& b = bounds[k];
        if (c.X < b.x0 || c.X > b.x1 || c.Y < b.y0 || c.Y > b.y1) continue;
        if (ClipperLib::PointInPolygon(c, result[k]) != 0) in = !in;
      }
      inside[static_cast<size_t>(j * frame.nx + i)] = in;
    }
  }
  return inside;
}

Outcome compare(const Case& c) {
  Outcome out;
  const double dx = c.dx;
  const GridFrame frame = grid_frame(c.shape, dx);
  const size_t cells = static_cast<size_t>(frame.nx * frame.ny);

  // the in-house fill, best of three
  ParticleGrid grid;
  out.fill_us = std::numeric_limits<double>::infinity();
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = Clock::now();
    grid = fill_grid(c.shape, c.holes, dx);
    out.fill_us = std::min(out.fill_us, microseconds(Clock::now() - t0));
  }
  EXPECT_EQ(grid.origin, frame.origin) << c.name;
  std::vector<char> filled(cells, 0);
  for (int k = 0; k < grid.size(); ++k) filled[static_cast<size_t>(grid.iy[k] * frame.nx + grid.ix[k])] = 1;
  out.in_house = grid.size();

  // Clipper: the shape minus its holes, then every cell centre; best of two (milliseconds each)
  Polygoniser poly{kUnitsPerSpacing / dx, dx};
  const ShapeDef whole = c.holes.empty() ? c.shape : [&] {
    std::vector<ShapeDef> operands = {c.shape};
    operands.insert(operands.end(), c.holes.begin(), c.holes.end());
    return combined(ShapeDef::Combine::kDifference, operands);
  }();
  ClipperLib::Paths result;
  std::vector<char> clipped;
  out.clipper_op_us = out.clipper_points_us = std::numeric_limits<double>::infinity();
  for (int rep = 0; rep < 2; ++rep) {
    const auto t0 = Clock::now();
    result = poly.paths(whole);
    const auto t1 = Clock::now();
    clipped = clipper_cells(result, frame, poly);
    out.clipper_op_us = std::min(out.clipper_op_us, microseconds(t1 - t0));
    out.clipper_points_us = std::min(out.clipper_points_us, microseconds(Clock::now() - t1));
  }
  for (const ClipperLib::Path& path : result) out.clipper_vertices += path.size();

  // the cells where either in-house answer differs from Clipper's
  int reported = 0;
  for (long j = 0; j < frame.ny; ++j) {
    for (long i = 0; i < frame.nx; ++i) {
      const size_t at = static_cast<size_t>(j * frame.nx + i);
      const Vec2 p = frame.cell(i, j);
      bool tested = c.shape.contains(p);
      for (const ShapeDef& h : c.holes) tested = tested && !h.contains(p);
      out.clipper += clipped[at];
      if (filled[at] == clipped[at] && tested == static_cast<bool>(clipped[at])) continue;
      out.fill_exceptions += filled[at] != clipped[at];
      out.inside_test_exceptions += tested != static_cast<bool>(clipped[at]);
      double gap = outline_distance(c.shape, p);
      for (const ShapeDef& h : c.holes) gap = std::min(gap, outline_distance(h, p));
      if (gap <= kBoundaryTolerance * dx) continue;
      ++out.far_exceptions;
      if (reported++ < 5)
        ADD_FAILURE() << c.name << " dx " << dx << ": cell (" << i << ", " << j << ") at (" << p.x() << ", " << p.y()
                      << ") is " << gap / dx << " spacings from every outline; fill " << int(filled[at])
                      << ", inside test " << tested << ", Clipper " << int(clipped[at]);
    }
  }
  return out;
}

// Compares every case, prints one line each and records the figures.
void compare_all(const std::vector<Case>& cases) {
  if (cases.empty()) return;
  std::cout << std::left << std::setw(34) << "shape" << std::right << std::setw(8) << "dx" << std::setw(10)
            << "in-house" << std::setw(10) << "Clipper" << std::setw(8) << "except" << std::setw(11) << "fill us"
            << std::setw(14) << "Clipper op us" << std::setw(15) << "PointInPoly us" << std::setw(10) << "vertices"
            << "\n";
  for (const Case& c : cases) {
    const Outcome o = compare(c);
    const long exceptions = std::max(o.fill_exceptions, o.inside_test_exceptions);
    std::ostringstream dx;
    dx << c.dx;
    std::cout << std::left << std::setw(34) << c.name << std::right << std::setw(8) << dx.str() << std::setw(10)
              << o.in_house << std::setw(10) << o.clipper << std::setw(8) << exceptions << std::setw(11)
              << std::lround(o.fill_us) << std::setw(14) << std::lround(o.clipper_op_us) << std::setw(15)
              << std::lround(o.clipper_points_us) << std::setw(10) << o.clipper_vertices << "\n";
    const std::string key = c.name + "_dx" + dx.str();
    ::testing::Test::RecordProperty(key + "_particles_in_house", static_cast<int>(o.in_house));
    ::testing::Test::RecordProperty(key + "_particles_clipper", static_cast<int>(o.clipper));
    ::testing::Test::RecordProperty(key + "_exceptions", static_cast<int>(exceptions));
    ::testing::Test::RecordProperty(key + "_fill_us", static_cast<int>(std::lround(o.fill_us)));
    ::testing::Test::RecordProperty(key + "_clipper_op_us", static_cast<int>(std::lround(o.clipper_op_us)));
    ::testing::Test::RecordProperty(key + "_clipper_points_us", static_cast<int>(std::lround(o.clipper_points_us)));

    EXPECT_GT(o.in_house, 0) << c.name;
    EXPECT_EQ(o.far_exceptions, 0) << c.name << " dx " << c.dx << ": cells placed differently, away from the outlines";
    EXPECT_LE(static_cast<double>(exceptions), kMostExceptions * static_cast<double>(o.clipper))
        << c.name << " dx " << c.dx << ": " << o.fill_exceptions << " fill and " << o.inside_test_exceptions
        << " inside-test exceptions of " << o.clipper << " particles";
  }
}

// ---------------------------------------------------------------------------
// The shapes.

// Every combined shape in a scene under scenes/ (bodies' shapes with their holes, holes, no-fail
// zones, load and attachment regions), at the body's grid spacing and at half of it. Found by
// reading the folder at test time, so scenes added later are covered too; files that do not
// load as scenes (sweeps, cases of failure suites) are skipped.
std::vector<Case> shipped_cases(int& scenes_read) {
  std::vector<Case> cases;
  const std::filesystem::path root = std::filesystem::path(PERIFLEX_SOURCE_ROOT) / "scenes";
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    if (s.find("\"difference\"") == std::string::npos && s.find("\"union\"") == std::string::npos &&
        s.find("\"intersection\"") == std::string::npos)
      continue;
    SceneDef scene;
    try {
      scene = load_scene(file.string());
    } catch (const std::exception& e) {
      std::cout << "skipped " << file.string() << ": " << e.what() << "\n";
      continue;
    }
    ++scenes_read;
    const std::string stem = file.stem().string();
    auto add = [&](const std::string& what, const ShapeDef& shape, const std::vector<ShapeDef>& holes, double dx) {
      for (double spacing : {dx, 0.5 * dx}) cases.push_back({stem + "_" + what, shape, holes, spacing});
    };
    auto is_combined = [](const ShapeDef& shape) { return shape.kind == ShapeDef::Kind::kBoolean; };
    for (const FlexBodyDef& b : scene.flex_bodies) {
      if (b.particles) continue;  // a point file or a picture: no grid fill
      const bool combined_hole = std::any_of(b.holes.begin(), b.holes.end(), is_combined);
      if (is_combined(b.shape) || combined_hole) add(b.name, b.shape, b.holes, b.grid_spacing);
      for (const ShapeDef& z : b.no_fail_regions)
        if (is_combined(z)) add(b.name + "_no_fail", z, {}, b.grid_spacing);
      for (const RegionLoadDef& l : b.loads)
        if (is_combined(l.region)) add(b.name + "_" + l.name, l.region, {}, b.grid_spacing);
      for (const AttachmentDef& a : scene.attachments)
        if (a.flex_body == b.name && is_combined(a.region)) add(a.name, a.region, {}, b.grid_spacing);
    }
  }
  return cases;
}

// The documented example (docs/scenes.md, "Combined shapes"): a plate minus a hole minus a slot,
// and the union of the two grip boxes as a no-fail zone; at 1 mm (the notched plate's spacing)
// and 0.5 mm.
std::vector<Case> documented_cases() {
  const ShapeDef plate = combined(ShapeDef::Combine::kDifference,
                                  {box({0, 0}, 0.08, 0.04), circle({0, 0}, 0.006), box({-0.03, 0}, 0.02, 0.002)});
  const ShapeDef grips =
      combined(ShapeDef::Combine::kUnion, {box({-0.0365, 0}, 0.007, 0.042), box({0.0365, 0}, 0.007, 0.042)});
  std::vector<Case> cases;
  for (double dx : {1e-3, 5e-4}) {
    cases.push_back({"docs_plate_hole_slot", plate, {}, dx});
    cases.push_back({"docs_no_fail_grips", grips, {}, dx});
  }
  return cases;
}

// Harder shapes: thin features below a grid spacing, overlaps, rotation, tangency, nesting.
std::vector<Case> extra_cases() {
  // a plate minus two holes minus a thin notch polygon whose tip is narrower than a spacing
  const ShapeDef notched = combined(
      ShapeDef::Combine::kDifference,
      {box({0, 0}, 0.1, 0.05), circle({-0.025, 0.008}, 0.0075), circle({0.025, -0.006}, 0.005),
       polygon({{-0.0012, -0.026}, {0.0012, -0.026}, {0.0001, -0.005}})});
  // two overlapping circles and a rotated box
  const ShapeDef blob = combined(ShapeDef::Combine::kUnion, {circle({-0.01, 0}, 0.015), circle({0.012, 0.004}, 0.013),
                                                             box({0, -0.012}, 0.05, 0.01, 0.3)});
  // a circle cut by an irregular hexagon turned by 0.4 rad about (0.002, -0.001)
  std::vector<Vec2> hexagon = {{0.022, 0.0}, {0.012, 0.016}, {-0.009, 0.019},
                               {-0.021, 0.002}, {-0.011, -0.017}, {0.013, -0.015}};
  for (Vec2& v : hexagon) v = Vec2(0.002, -0.001) + rotation(0.4) * v;
  const ShapeDef cut = combined(ShapeDef::Combine::kIntersection, {circle({0.003, 0.002}, 0.02), polygon(hexagon)});
  // holes touching the outer edge: a bite centred on the top edge, a disc tangent to the right edge
  const ShapeDef bitten =
      combined(ShapeDef::Combine::kDifference,
               {box({0, 0}, 0.06, 0.03), circle({0.01, 0.015}, 0.006), circle({0.025, -0.005}, 0.005)});
  // nested: a plate minus a disc, united with a ring (a circle minus a circle)
  const ShapeDef nested = combined(
      ShapeDef::Combine::kUnion,
      {combined(ShapeDef::Combine::kDifference, {box({0, 0}, 0.05, 0.03, 0.2), circle({0.004, 0.002}, 0.008)}),
       combined(ShapeDef::Combine::kDifference, {circle({0.035, 0}, 0.015), circle({0.035, 0}, 0.009)})});
  // a combined shape with holes given apart, as a flexible body may have
  const ShapeDef lens = combined(ShapeDef::Combine::kIntersection, {circle({-0.01, 0}, 0.03), circle({0.01, 0}, 0.03)});
  const std::vector<ShapeDef> lens_holes = {circle({0, 0.008}, 0.004), box({0, -0.01}, 0.012, 0.0015, -0.5)};
  std::vector<Case> cases;
  for (double dx : {1e-3, 5e-4}) {
    cases.push_back({"plate_two_holes_thin_notch", notched, {}, dx});
    cases.push_back({"two_circles_and_box", blob, {}, dx});
    cases.push_back({"circle_and_rotated_polygon", cut, {}, dx});
    cases.push_back({"holes_touching_the_edge", bitten, {}, dx});
    cases.push_back({"plate_minus_disc_and_ring", nested, {}, dx});
    cases.push_back({"lens_with_holes", lens, lens_holes, dx});
  }
  return cases;
}

TEST(ShapeBooleanClipper, ShippedScenesShapesFillTheCellsInsideClippersResult) {
  int scenes_read = 0;
  const std::vector<Case> cases = shipped_cases(scenes_read);
  std::cout << scenes_read << " shipped scene(s) with combined shapes, " << cases.size() / 2 << " combined shape(s)\n";
  RecordProperty("shipped_scenes_with_combined_shapes", scenes_read);
  compare_all(cases);
}

TEST(ShapeBooleanClipper, DocumentedExampleFillsTheCellsInsideClippersResult) { compare_all(documented_cases()); }

TEST(ShapeBooleanClipper, HarderShapesFillTheCellsInsideClippersResult) { compare_all(extra_cases()); }

}  // namespace clipper_check
}  // namespace periflex
