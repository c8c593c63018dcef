// Specimens from files, run by the program as typed: a body written out as a point file and
// read back runs bit for bit; the plate with a hole rebuilt from a point file, a picture and a
// DXF outline places the same particles (but at the hole's rim) and breaks the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "../cli/run_program.h"
#include "scene/point_file_reader.h"

namespace periflex {
namespace {

using testing::read_text;
using testing::run_periflex;

const std::string kData = std::string(PERIFLEX_TEST_DATA) + "/specimens/";

// series.csv as columns by name.
std::map<std::string, std::vector<double>> series(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream h(header);
  for (std::string name; std::getline(h, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (size_t k = 0; k < names.size() && std::getline(row, cell, ','); ++k) columns[names[k]].push_back(std::stod(cell));
  }
  return columns;
}

// The glass plate's 36 000 particles (no-fail strips and notch included) written out, read
// back as a points shape, and run for 20 us, where the crack has started: series.csv the same
// bytes.
TEST(SpecimenFiles, GlassPlateWrittenAndReadBackRunsBitForBit) {
  const auto dir = testing::fresh_directory("specimen_glass");
  const std::string points = (dir / "glass.csv").string();
  const std::string common = testing::scene("glass_branching.toml") + " --until 2e-5 --quiet";
  const auto original = run_periflex("run " + common + " --out " + (dir / "a").string() + " --points-out " + points);
  ASSERT_EQ(original.exit_code, 0) << original.output;
  const auto back = run_periflex("run " + common + " --out " + (dir / "b").string() +
                                 " --set 'flex_body.plate.shape={type=\"points\",file=\"" + points + "\"}'");
  ASSERT_EQ(back.exit_code, 0) << back.output;
  const std::string a = read_text(dir / "a" / "series.csv"), b = read_text(dir / "b" / "series.csv");
  EXPECT_EQ(a, b);
  // the comparison covers fracture: bonds have broken by the end
  EXPECT_GT(series(dir / "a" / "series.csv").at("broken_bonds").back(), 0.0);
}

// One run of the plate with a hole whose shape is `shape` (and no holes of its own, when given).
struct PlateRun {
  std::map<std::string, std::vector<double>> columns;
  ParticleCloud particles;
};

// The shipped plate with a hole, its shape and holes lines replaced by `shape` (empty: as
// shipped), written into `dir`.
std::string plate_scene(const std::filesystem::path& dir, const std::string& shape) {
  std::string scene = read_text(testing::scene("plate_with_hole.toml"));
  if (!shape.empty()) {
    const size_t at = scene.find("\nshape = "), holes = scene.find("\nholes = ");
    EXPECT_NE(at, std::string::npos);
    EXPECT_EQ(holes, scene.find('\n', at + 1));  // the holes line follows the shape line
    scene.replace(at + 1, scene.find('\n', holes + 1) - at - 1, "shape = " + shape);
  }
  std::ofstream(dir / "plate.toml") << scene;
  return (dir / "plate.toml").string();
}

PlateRun run_plate(const std::string& name, const std::string& shape) {
  const auto dir = testing::fresh_directory("specimen_plate_" + name);
  plate_scene(dir, shape);
  const auto result = run_periflex("run " + (dir / "plate.toml").string() + " --until 4e-4 --quiet --out " +
                                   (dir / "out").string() + " --points-out " + (dir / "points.csv").string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return {series(dir / "out" / "series.csv"), read_point_file((dir / "points.csv").string(), {})};
}

// A body off the grid through a file: the plate with a hole jittered by a quarter spacing,
// written out and read back as a points shape (whose points now lie off any grid), runs to its
// end as the same bytes of series.csv, cracking included.
TEST(SpecimenFiles, JitteredPlateWrittenAndReadBackRunsBitForBit) {
  const auto dir = testing::fresh_directory("specimen_jittered");
  const std::string points = (dir / "jittered.csv").string();
  const std::string common = testing::scene("plate_with_hole.toml") + " --until 4e-4 --quiet";
  const auto original = run_periflex("run " + common + " --set flex_body.plate.jitter=0.25 --out " +
                                     (dir / "a").string() + " --points-out " + points);
  ASSERT_EQ(original.exit_code, 0) << original.output;
  // the scene with the points for its shape and no holes (a jittered particle may sit inside the
  // hole's circle)
  const std::string back_scene = plate_scene(dir, "{ type = \"points\", file = \"" + points + "\" }");
  const auto back = run_periflex("run " + back_scene + " --until 4e-4 --quiet --out " + (dir / "b").string());
  ASSERT_EQ(back.exit_code, 0) << back.output;
  const std::string a = read_text(dir / "a" / "series.csv"), b = read_text(dir / "b" / "series.csv");
  EXPECT_EQ(a, b);
  EXPECT_GT(series(dir / "a" / "series.csv").at("broken_bonds").back(), 0.0);
}

// A body of two materials from one point file (tests/data/scenes/run/bimaterial_points.toml: PMMA
// bonded to aluminium, block by block): it runs to its end and cracks; written out with
// --points-out (which keeps its blocks) and read back with the same block materials, it runs as
// the same bytes of series.csv; without its block material (all PMMA) the run differs. `check`
// names each block's material, and the GPU path refuses the body before anything runs.
TEST(SpecimenFiles, MaterialsByBlockWrittenAndReadBackRunBitForBit) {
  const auto dir = testing::fresh_directory("specimen_blocks");
  const std::string scene_file = std::string(PERIFLEX_TEST_DATA) + "/scenes/run/bimaterial_points.toml";
  const std::string points = (dir / "blocks.csv").string();
  const auto original = run_periflex("run " + scene_file + " --quiet --out " + (dir / "a").string() + " --points-out " + points);
  ASSERT_EQ(original.exit_code, 0) << original.output;
  std::string text = read_text(scene_file);
  const std::string from = "file = \"bimaterial_points.csv\", unit = \"mm\"";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "file = \"" + points + "\"");
  std::ofstream(dir / "back.toml") << text;
  const auto back = run_periflex("run " + (dir / "back.toml").string() + " --quiet --out " + (dir / "b").string());
  ASSERT_EQ(back.exit_code, 0) << back.output;
  EXPECT_EQ(read_text(dir / "a" / "series.csv"), read_text(dir / "b" / "series.csv"));
  EXPECT_GT(series(dir / "a" / "series.csv").at("broken_bonds").back(), 0.0);
  // the same strip all PMMA: another run
  std::ofstream(dir / "one.toml") << text.substr(0, text.find("\n[[flex_body.block_material]]")) + "\n" +
                                         text.substr(text.find("\n[[flex_body.load]]"));
  const auto one = run_periflex("run " + (dir / "one.toml").string() + " --quiet --out " + (dir / "c").string());
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_NE(read_text(dir / "a" / "series.csv"), read_text(dir / "c" / "series.csv"));
  const auto check = run_periflex("check " + scene_file);
  EXPECT_NE(check.output.find("'strip': block 1, youngs_modulus = 7e+10 Pa, density = 2700 kg/m^3"), std::string::npos)
      << check.output;
  const auto gpu = run_periflex("run " + scene_file + " --quiet --device gpu --out " + (dir / "d").string());
  EXPECT_EQ(gpu.exit_code, 2) << gpu.output;
  EXPECT_NE(gpu.output.find("'strip' has materials by block"), std::string::npos) << gpu.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "d" / "series.csv"));
}

// Particles of `a` that `b` lacks, all within one grid spacing of the hole's rim (radius 6 mm).
void expect_same_but_at_rim(const ParticleCloud& a, const ParticleCloud& b, const std::string& what) {
  std::set<std::pair<long, long>> in_b;
  for (long k = 0; k < b.size(); ++k) in_b.insert({std::lround(b.x[k] * 2e3), std::lround(b.y[k] * 2e3)});
  long differ = 0;
  for (long k = 0; k < a.size(); ++k) {
    if (in_b.count({std::lround(a.x[k] * 2e3), std::lround(a.y[k] * 2e3)})) continue;
    ++differ;
    EXPECT_LE(std::abs(std::hypot(a.x[k], a.y[k]) - 0.006), 1e-3) << what << ": (" << a.x[k] << ", " << a.y[k] << ")";
  }
  std::cout << what << ": " << differ << " particles differ, all at the rim\n";
}

// Energies within 1% of the column's largest magnitude, row by row (1%: the bound; a
// particle or two at the rim changes the stiffness near the hole by about that much), and the
// bonds broken at the end within 1%.
void expect_same_run(const PlateRun& reference, const PlateRun& other, const std::string& what) {
  for (const char* column : {"kinetic", "potential_elastic", "fracture", "external_work", "driver_work"}) {
    const auto& r = reference.columns.at(column);
    const auto& o = other.columns.at(column);
    ASSERT_EQ(r.size(), o.size()) << what;
    double scale = 0.0, worst = 0.0;
    for (double v : r) scale = std::max(scale, std::abs(v));
    for (size_t k = 0; k < r.size(); ++k) worst = std::max(worst, std::abs(o[k] - r[k]));
    EXPECT_LE(worst, 0.01 * scale) << what << " " << column;
    std::cout << what << " " << column << ": largest difference " << (scale > 0 ? worst / scale : 0.0) << " of its scale\n";
  }
  const double broken_r = reference.columns.at("broken_bonds").back(), broken_o = other.columns.at("broken_bonds").back();
  EXPECT_GT(broken_r, 0.0);
  EXPECT_LE(std::abs(broken_o - broken_r), 0.01 * broken_r) << what << ": " << broken_o << " against " << broken_r;
  std::cout << what << " broken bonds: " << broken_o << " against " << broken_r << "\n";
}

TEST(SpecimenFiles, PlateWithHoleFromPointsImageAndDxfMatchesTheTypedShapes) {
  const PlateRun typed = run_plate("typed", "");
  const PlateRun points = run_plate("points", "{ type = \"points\", file = \"" + kData + "plate_with_hole_points.csv\" }");
  const PlateRun image = run_plate("image", "{ type = \"image\", file = \"" + kData + "plate_with_hole.png\", width = 0.08 }");
  const PlateRun dxf = run_plate("dxf", "{ type = \"dxf\", file = \"" + kData + "plate_with_hole.dxf\", scale = 1e-3, layer = \"outline\" }");
  for (const auto* run : {&points, &image, &dxf}) {
    const std::string what = run == &points ? "points" : run == &image ? "image" : "dxf";
    expect_same_but_at_rim(typed.particles, run->particles, what);
    expect_same_but_at_rim(run->particles, typed.particles, what);
    expect_same_run(typed, *run, what);
  }
  // the point file is the typed body itself
  EXPECT_EQ(points.columns, typed.columns);
}

// `check` says where each body's geometry came from and the box its particles fill.
TEST(SpecimenFiles, CheckNamesWhereTheGeometryCameFrom) {
  const auto dir = testing::fresh_directory("specimen_check");
  const auto typed = run_periflex("check " + testing::scene("plate_with_hole.toml"));
  EXPECT_EQ(typed.exit_code, 0) << typed.output;
  EXPECT_NE(typed.output.find("'plate': shape of the scene, x in [-0.04, 0.04] m, y in [-0.02, 0.02] m"),
            std::string::npos) << typed.output;
  const std::string dxf = kData + "plate_with_hole.dxf";
  const auto drawn = run_periflex("check " + plate_scene(dir, "{ type = \"dxf\", file = \"" + dxf + "\", scale = 1e-3 }"));
  EXPECT_EQ(drawn.exit_code, 0) << drawn.output;
  EXPECT_NE(drawn.output.find("'plate': dxf " + dxf + ", x in [-0.04, 0.04] m, y in [-0.02, 0.02] m"),
            std::string::npos) << drawn.output;
}

}  // namespace
}  // namespace periflex
