#include "output/vtk_series.h"

#include <cstdio>
#include <sstream>

#include "output/atomic_file.h"
#include "output/vtk_writer.h"

namespace periflex {

VtkSeries::VtkSeries(std::string directory) : directory_(std::move(directory)) { ensure_directory(directory_); }

void VtkSeries::write(const Snapshot& snapshot) {
  char name[64];
  std::snprintf(name, sizeof name, "particles_%06zu.vtu", entries_.size());
  write_vtu(directory_ + "/" + name, snapshot);
  entries_.push_back({snapshot.time, name});

  std::ostringstream pvd;
  pvd.precision(12);
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const Entry& e : entries_)
    pvd << "    <DataSet timestep=\"" << e.time << "\" file=\"" << e.file << "\"/>\n";
  pvd << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(directory_ + "/particles.pvd", pvd.str());
}

}  // namespace periflex
