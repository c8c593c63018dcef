#include "output/vtk_writer.h"

#include <sstream>

#include "output/atomic_file.h"

namespace periflex {

namespace {

// One <DataArray> of n scalars of VTK type `type`, eight to a line.
template <typename Get>
void scalar_array(std::ostringstream& out, const char* type, const char* name, size_t n, Get get) {
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" format=\"ascii\">\n";
  for (size_t i = 0; i < n; ++i) out << (i % 8 == 0 ? "          " : " ") << get(i) << (i % 8 == 7 ? "\n" : "");
  if (n % 8 != 0) out << "\n";
  out << "        </DataArray>\n";
}

// One <DataArray> of n 3-vectors (x, y, 0).
template <typename GetX, typename GetY>
void vector_array(std::ostringstream& out, const char* name, size_t n, GetX gx, GetY gy) {
  out << "        <DataArray type=\"Float32\" Name=\"" << name
      << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (size_t i = 0; i < n; ++i) out << "          " << gx(i) << ' ' << gy(i) << " 0\n";
  out << "        </DataArray>\n";
}

}  // namespace

std::string vtu_document(const Snapshot& s) {
  const size_t n = s.px.size();
  const SceneGeometry* geo = s.geometry.get();
  const bool has_reference = geo && geo->reference_x.size() == n && geo->reference_y.size() == n;
  auto at = [](const std::vector<float>& v, size_t i) { return i < v.size() ? v[i] : 0.0f; };

  std::ostringstream out;
  out.precision(9);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <FieldData>\n"
      << "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">" << s.time
      << "</DataArray>\n"
      << "    </FieldData>\n"
      << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n";

  // point data: what ParaView colours by
  out << "      <PointData Scalars=\"damage\" Vectors=\"displacement\">\n";
  vector_array(
      out, "displacement", n, [&](size_t i) { return has_reference ? s.px[i] - geo->reference_x[i] : 0.0f; },
      [&](size_t i) { return has_reference ? s.py[i] - geo->reference_y[i] : 0.0f; });
  scalar_array(out, "Float32", "displacement_magnitude", n, [&](size_t i) { return at(s.displacement, i); });
  vector_array(out, "velocity", n, [&](size_t i) { return at(s.vx, i); }, [&](size_t i) { return at(s.vy, i); });
  scalar_array(out, "Float32", "speed", n, [&](size_t i) { return at(s.speed, i); });
  scalar_array(out, "Float32", "damage", n, [&](size_t i) { return at(s.damage, i); });
  scalar_array(out, "Float32", "strain", n, [&](size_t i) { return at(s.strain, i); });
  out << "      </PointData>\n";

  // positions
  out << "      <Points>\n";
  vector_array(out, "position", n, [&](size_t i) { return s.px[i]; }, [&](size_t i) { return s.py[i]; });
  out << "      </Points>\n";

  // one vertex cell per particle
  out << "      <Cells>\n";
  scalar_array(out, "Int64", "connectivity", n, [](size_t i) { return i; });
  scalar_array(out, "Int64", "offsets", n, [](size_t i) { return i + 1; });
  scalar_array(out, "UInt8", "types", n, [](size_t) { return 1; });  // VTK_VERTEX
  out << "      </Cells>\n"
      << "    </Piece>\n"
      << "  </UnstructuredGrid>\n"
      << "</VTKFile>\n";
  return out.str();
}

void write_vtu(const std::string& path, const Snapshot& snapshot) {
  write_file_atomically(path, vtu_document(snapshot));
}

}  // namespace periflex
