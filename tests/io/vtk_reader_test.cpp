// Reading back the VTK files periflex writes (src/io/vtk_reader): every array of a written
// .vtu and .vtp file comes back with every digit, TIME and STEP included; a collection lists its
// data sets; a file cut short, a foreign file and a collection pointing outside its folder are
// refused naming the file.
#include "io/vtk_reader.h"

#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "output/checkpoint_file.h"
#include "io/vtk_series.h"
#include "io/vtk_writer.h"

namespace periflex {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("periflex_vtk_reader_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// two particles of one body and a box on body 1, at step 42
Snapshot small_scene() {
  auto geometry = std::make_shared<SceneGeometry>();
  geometry->reference_x = {0.0f, 1.0f};
  geometry->reference_y = {0.0f, 0.0f};
  geometry->reference_xy = {0.0, 0.0, 1.0, 0.0};
  geometry->particle_volume = {1e-9, 2e-9};
  geometry->flex_bodies = {{"plate", 0, 2, 1.0}};
  ShapeDef box;
  box.kind = ShapeDef::Kind::kBox;
  box.width = 0.2;
  box.height = 0.1;
  geometry->bodies = {{"ground", true, false, {}}, {"block", false, false, {box}}};
  Snapshot s;
  s.geometry = geometry;
  s.time = 1.0 / 3.0;
  s.step = 42;
  s.bodies = {Snapshot::Pose{}, Snapshot::Pose{0.1, -0.2, 0.7}};
  s.px = {0.0f, 1.0f};
  s.py = {0.0f, 0.5f};
  s.damage = {0.25f, 1.0f};
  s.strain = {1e-3f, 0.0f};
  s.full_precision = true;
  s.particle_q = {1e-13, 0.0, 1.0 + 1e-12, 0.5};
  s.particle_qd = {3.0, -1.0 / 7.0, 0.0, 2.0};
  return s;
}

TEST(VtkReader, ReadsBackEveryArrayWithEveryDigit) {
  const fs::path dir = fresh("round_trip");
  const Snapshot s = small_scene();
  write_vtu((dir / "p.vtu").string(), s);
  write_vtp_bodies((dir / "b.vtp").string(), s);

  const VtkArrays p = read_vtk_arrays((dir / "p.vtu").string());
  EXPECT_EQ(p.get("TIME", 1)[0], 1.0 / 3.0);
  EXPECT_EQ(p.get("STEP", 1)[0], 42.0);
  const std::vector<double>& position = p.get("position", 6);
  EXPECT_EQ(position[0], 1e-13);
  EXPECT_EQ(position[3], 1.0 + 1e-12);
  EXPECT_EQ(position[4], 0.5);
  EXPECT_EQ(p.get("velocity", 6)[1], -1.0 / 7.0);
  EXPECT_EQ(p.get("damage", 2)[0], 0.25);
  EXPECT_EQ(p.get("strain", 2)[0], static_cast<double>(1e-3f));
  EXPECT_THROW(p.get("damage", 3), CheckpointError);
  EXPECT_THROW(p.get("no_such_array", 1), CheckpointError);

  const VtkArrays b = read_vtk_arrays((dir / "b.vtp").string());
  EXPECT_EQ(b.get("body", 1)[0], 1.0);
  EXPECT_EQ(b.get("angle", 1)[0], 0.7);
  EXPECT_EQ(b.get("position", 3)[1], -0.2);
  fs::remove_all(dir);
}

TEST(VtkReader, CollectionListsEachSnapshotsParts) {
  const fs::path dir = fresh("collection");
  VtkSeries series(dir.string());
  Snapshot s = small_scene();
  series.write(s);
  s.time = 0.5;
  series.write(s);
  const std::vector<VtkDataSet> sets = read_vtk_collection((dir / "snapshots.pvd").string());
  ASSERT_EQ(sets.size(), 4u);
  EXPECT_EQ(sets[0].part, 0);
  EXPECT_EQ(sets[1].part, 1);
  EXPECT_EQ(sets[1].time, 1.0 / 3.0);  // 17 digits in the collection: the same double
  EXPECT_EQ(sets[2].time, 0.5);
  EXPECT_EQ(sets[3].file, "bodies_000001.vtp");
  fs::remove_all(dir);
}

TEST(VtkReader, DamagedOrForeignFilesAreRefusedNamingThem) {
  const fs::path dir = fresh("damaged");
  write_vtu((dir / "p.vtu").string(), small_scene());
  // cut inside the appended block
  std::string text;
  {
    std::ifstream in(dir / "p.vtu", std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::ofstream(dir / "cut.vtu", std::ios::binary) << text.substr(0, text.size() - 120);
  std::ofstream(dir / "foreign.vtu") << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"></VTKFile>\n";
  std::ofstream(dir / "outside.pvd") << "<VTKFile type=\"Collection\"><Collection>\n"
                                        "<DataSet timestep=\"0\" part=\"0\" file=\"../../etc/passwd\"/>\n"
                                        "</Collection></VTKFile>\n";
  for (const char* name : {"cut.vtu", "foreign.vtu", "missing.vtu"}) {
    try {
      read_vtk_arrays((dir / name).string());
      ADD_FAILURE() << name << " was read";
    } catch (const CheckpointError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_vtk_collection((dir / "outside.pvd").string()), CheckpointError);
  EXPECT_THROW(read_vtk_collection((dir / "p.vtu").string()), CheckpointError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace periflex
