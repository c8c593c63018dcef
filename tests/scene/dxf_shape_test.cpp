// CAD outlines: entities of every kind joined into loops, outer loops material and inner ones
// holes, layers and scale honoured, and an outline that does not close refused naming the
// entity and where the gap is.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scene/dxf_shape.h"

namespace periflex {
namespace {

// A DXF file of the given entities (each a list of "code\nvalue" pairs).
std::string dxf(const std::string& name, const std::string& entities) {
  const auto path = std::filesystem::temp_directory_path() / ("periflex_" + name + ".dxf");
  std::ofstream(path) << "0\nSECTION\n2\nENTITIES\n" << entities << "0\nENDSEC\n0\nEOF\n";
  return path.string();
}

std::string line(double x1, double y1, double x2, double y2, const std::string& layer = "0") {
  std::ostringstream s;
  s << "0\nLINE\n8\n" << layer << "\n10\n" << x1 << "\n20\n" << y1 << "\n11\n" << x2 << "\n21\n" << y2 << "\n";
  return s.str();
}

double area(const std::vector<Vec2>& loop) {
  double twice = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) twice += cross(loop[i], loop[(i + 1) % loop.size()]);
  return 0.5 * twice;
}

// A 4 x 2 rectangle of lines drawn in any order and direction, minus a rounded slot of an arc,
// a line and a polyline with a bulge: one material loop, one hole, in metres.
TEST(DxfShape, PiecesJoinIntoLoopsAndInnerLoopsAreHoles) {
  const std::string entities =
      line(4, 0, 4, 2) + line(0, 0, 4, 0) + line(0, 2, 0, 0) + line(0, 2, 4, 2) +
      // the slot: from (1,1) right to (3,1), a half circle up to (3,1.5)... drawn as an arc and a bulged polyline
      "0\nARC\n8\n0\n10\n3\n20\n1.25\n40\n0.25\n50\n-90\n51\n90\n" + line(3, 1.5, 1, 1.5) +
      "0\nLWPOLYLINE\n8\n0\n90\n2\n70\n0\n10\n1\n20\n1.5\n42\n1\n10\n1\n20\n1\n" + line(1, 1, 3, 1);
  DxfShapeOptions options;
  options.scale = 1e-3;
  const DxfOutline outline = read_dxf_shape(dxf("pieces", entities), options);
  ASSERT_EQ(outline.material.size(), 1u);
  ASSERT_EQ(outline.holes.size(), 1u);
  EXPECT_NEAR(area(outline.material[0]), 8e-6, 1e-15);
  // the slot: a 2 x 0.5 rectangle and two half discs of radius 0.25 (the polygons' chords lose
  // under 1e-4 of the discs' area)
  const double slot = (1.0 + kPi * 0.0625) * 1e-6;
  EXPECT_NEAR(area(outline.holes[0]), slot, 1e-4 * slot);
  EXPECT_GT(area(outline.holes[0]), 0.0);  // counter-clockwise whatever the drawing's direction
}

TEST(DxfShape, CircleAndClosedPolylineOnTheirLayer) {
  const std::string entities =
      "0\nLWPOLYLINE\n8\nplate\n90\n4\n70\n1\n10\n-4\n20\n-2\n10\n4\n20\n-2\n10\n4\n20\n2\n10\n-4\n20\n2\n"
      "0\nCIRCLE\n8\nplate\n10\n0\n20\n0\n40\n1\n" + line(-9, -9, 9, 9, "notes");
  DxfShapeOptions options;
  options.layer = "plate";
  const DxfOutline outline = read_dxf_shape(dxf("layer", entities), options);
  ASSERT_EQ(outline.material.size(), 1u);
  ASSERT_EQ(outline.holes.size(), 1u);
  EXPECT_EQ(outline.holes[0].size(), static_cast<size_t>(kDxfSegmentsPerTurn));
  for (const Vec2& v : outline.holes[0]) EXPECT_NEAR(v.norm(), 1.0, 1e-12);
  // on every layer, the stray line leaves the outline open
  EXPECT_THROW(read_dxf_shape(dxf("layer", entities), {}), InputError);
}

TEST(DxfShape, OpenOutlineNamesTheEntityAndTheGap) {
  const std::string entities = line(0, 0, 4, 0) + line(4, 0, 4, 2) + line(4, 2, 0, 2) + line(0, 2, 0, 0.5);
  std::string message;
  try {
    read_dxf_shape(dxf("open", entities), {});
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("not closed"), std::string::npos) << message;
  EXPECT_NE(message.find("LINE at line"), std::string::npos) << message;
  EXPECT_NE(message.find("(0, 0.5)"), std::string::npos) << message;
}

TEST(DxfShape, NoLoopAndNotADxfRefused) {
  EXPECT_THROW(read_dxf_shape(dxf("empty", ""), {}), InputError);
  const auto path = std::filesystem::temp_directory_path() / "periflex_not.dxf";
  std::ofstream(path) << "hello\nworld\n";
  std::string message;
  try {
    read_dxf_shape(path.string(), {});
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("group code"), std::string::npos) << message;
}

}  // namespace
}  // namespace periflex
