#include "io/vtk_series.h"

#include <cstdio>
#include <sstream>

#include "output/atomic_file.h"
#include "io/vtk_writer.h"

namespace periflex {

VtkSeries::VtkSeries(std::string directory) : directory_(std::move(directory)) { ensure_directory(directory_); }

void VtkSeries::write(const Snapshot& snapshot) {
  // particles when there are any, bodies when any has a shape: a scene writes what it has
  const SceneGeometry* geo = snapshot.geometry.get();
  bool has_shapes = false;
  if (geo)
    for (const auto& body : geo->bodies) has_shapes = has_shapes || !body.shapes.empty();
  char name[64];
  if (!snapshot.px.empty() || !has_shapes) {
    std::snprintf(name, sizeof name, "particles_%06ld.vtu", snapshots_);
    write_vtu(directory_ + "/" + name, snapshot);
    entries_.push_back({snapshot.time, 0, name});
  }
  if (has_shapes) {
    std::snprintf(name, sizeof name, "bodies_%06ld.vtp", snapshots_);
    write_vtp_bodies(directory_ + "/" + name, snapshot);
    entries_.push_back({snapshot.time, 1, name});
  }
  ++snapshots_;

  std::ostringstream pvd;
  pvd.precision(17);
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const Entry& e : entries_)
    pvd << "    <DataSet timestep=\"" << e.time << "\" part=\"" << e.part << "\" file=\"" << e.file << "\"/>\n";
  pvd << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(directory_ + "/snapshots.pvd", pvd.str());
}

}  // namespace periflex
