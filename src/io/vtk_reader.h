// Reading back the VTK files periflex writes (io/vtk_writer.h): the named arrays of one .vtu
// or .vtp file, from the raw appended block (UInt64 sizes, little-endian) or as ASCII text, and
// the .pvd collection of a series. Only what the writer produces is understood; any other file
// is refused by name, so a folder of foreign VTK files cannot be mistaken for a run's.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace periflex {

// The arrays of one file, each converted to double, components interleaved as stored.
struct VtkArrays {
  std::map<std::string, std::vector<double>> arrays;
  // the array of that name; throws CheckpointError naming the file when it is missing or does
  // not hold `count` values
  const std::vector<double>& get(const std::string& name, size_t count) const;
  std::string path;
};

// Reads every <DataArray> of a file periflex wrote. Throws CheckpointError
// (output/checkpoint_file.h) naming the file when it cannot be read or is not such a file.
VtkArrays read_vtk_arrays(const std::string& path);

// One <DataSet> of a .pvd collection: its time, part (0 particles, 1 bodies) and file name.
struct VtkDataSet {
  double time = 0.0;
  int part = 0;
  std::string file;
};

// The data sets of a .pvd collection in file order. Throws CheckpointError naming the file.
std::vector<VtkDataSet> read_vtk_collection(const std::string& path);

}  // namespace periflex
