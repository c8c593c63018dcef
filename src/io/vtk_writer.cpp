#include "io/vtk_writer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <type_traits>
#include <vector>

#include "output/atomic_file.h"
#include "scene/shape_outline.h"

namespace periflex {

namespace {

static_assert(std::endian::native == std::endian::little, "the VTK files declare LittleEndian");

template <typename T>
constexpr const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  if constexpr (std::is_same_v<T, float>) return "Float32";
  if constexpr (std::is_same_v<T, int64_t>) return "Int64";
  if constexpr (std::is_same_v<T, int32_t>) return "Int32";
  if constexpr (std::is_same_v<T, uint8_t>) return "UInt8";
}

// The arrays of one file: each <DataArray> in the XML names its offset into the appended block,
// where its bytes follow a UInt64 byte count (VTK's "raw" appended encoding, header_type UInt64).
class AppendedArrays {
 public:
  template <typename T>
  void add(std::ostringstream& xml, const char* name, int components, const std::vector<T>& values) {
    xml << "        <DataArray type=\"" << vtk_type<T>() << "\" Name=\"" << name << "\"";
    if (components > 1) xml << " NumberOfComponents=\"" << components << "\"";
    xml << " format=\"appended\" offset=\"" << block_.size() << "\"/>\n";
    const uint64_t bytes = values.size() * sizeof(T);
    append(&bytes, sizeof bytes);
    if (bytes) append(values.data(), bytes);
  }
  // The end of the document: the appended block, then the closing tags.
  void finish(std::ostringstream& xml) const {
    xml << "  <AppendedData encoding=\"raw\">\n_";
    xml.write(block_.data(), static_cast<std::streamsize>(block_.size()));
    xml << "\n  </AppendedData>\n</VTKFile>\n";
  }

 private:
  void append(const void* data, size_t size) {
    const size_t at = block_.size();
    block_.resize(at + size);
    std::memcpy(block_.data() + at, data, size);
  }
  std::vector<char> block_;
};

void open_document(std::ostringstream& xml, const char* type, double time, long step) {
  xml.precision(17);
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"" << type << "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      << "  <" << type << ">\n"
      << "    <FieldData>\n"
      << "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">" << time
      << "</DataArray>\n"
      << "      <DataArray type=\"Int64\" Name=\"STEP\" NumberOfTuples=\"1\" format=\"ascii\">" << step
      << "</DataArray>\n"
      << "    </FieldData>\n";
}

// (x, y) pairs as 3-vectors with z = 0, as VTK wants points and vectors.
std::vector<double> planar(const std::vector<double>& xy) {
  std::vector<double> out(xy.size() / 2 * 3, 0.0);
  for (size_t i = 0; 2 * i + 1 < xy.size(); ++i) {
    out[3 * i] = xy[2 * i];
    out[3 * i + 1] = xy[2 * i + 1];
  }
  return out;
}

// Pairs from two float arrays (the drawing's precision), for snapshots filled without doubles.
std::vector<double> pairs_of(const std::vector<float>& x, const std::vector<float>& y, size_t n) {
  std::vector<double> xy(2 * n, 0.0);
  for (size_t i = 0; i < n && i < x.size() && i < y.size(); ++i) {
    xy[2 * i] = x[i];
    xy[2 * i + 1] = y[i];
  }
  return xy;
}

std::vector<float> padded(const std::vector<float>& v, size_t n) {
  std::vector<float> out(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(std::min(n, v.size())));
  out.resize(n, 0.0f);
  return out;
}

}  // namespace

std::string vtu_document(const Snapshot& s) {
  const size_t n = s.px.size();
  const SceneGeometry* geo = s.geometry.get();
  const std::vector<double> q = s.particle_q.size() == 2 * n ? s.particle_q : pairs_of(s.px, s.py, n);
  const std::vector<double> qd = s.particle_qd.size() == 2 * n ? s.particle_qd : pairs_of(s.vx, s.vy, n);
  std::vector<double> reference = q;  // without a reference grid the displacement is zero
  if (geo && geo->reference_xy.size() == 2 * n)
    reference = geo->reference_xy;
  else if (geo && geo->reference_x.size() == n)
    reference = pairs_of(geo->reference_x, geo->reference_y, n);

  std::vector<double> displacement(2 * n), magnitude(n), speed(n), volume(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    displacement[2 * i] = q[2 * i] - reference[2 * i];
    displacement[2 * i + 1] = q[2 * i + 1] - reference[2 * i + 1];
    magnitude[i] = std::hypot(displacement[2 * i], displacement[2 * i + 1]);
    speed[i] = std::hypot(qd[2 * i], qd[2 * i + 1]);
  }
  if (geo && geo->particle_volume.size() == n) volume = geo->particle_volume;
  std::vector<int32_t> body(n, 0);
  if (geo) {
    for (size_t f = 0; f < geo->flex_bodies.size(); ++f) {
      const auto& flex = geo->flex_bodies[f];
      for (int p = flex.first_particle; p < flex.first_particle + flex.particle_count && p < static_cast<int>(n); ++p)
        body[p] = static_cast<int32_t>(f);
    }
  }
  std::vector<int64_t> connectivity(n), offsets(n);
  for (size_t i = 0; i < n; ++i) {
    connectivity[i] = static_cast<int64_t>(i);
    offsets[i] = static_cast<int64_t>(i + 1);
  }
  const std::vector<uint8_t> types(n, 1);  // VTK_VERTEX

  std::ostringstream xml;
  AppendedArrays data;
  open_document(xml, "UnstructuredGrid", s.time, s.step);
  xml << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n";
  // point data: what ParaView colours by, warps by (displacement) and scales glyphs by (volume)
  xml << "      <PointData Scalars=\"damage\" Vectors=\"displacement\">\n";
  data.add(xml, "displacement", 3, planar(displacement));
  data.add(xml, "displacement_magnitude", 1, magnitude);
  data.add(xml, "velocity", 3, planar(qd));
  data.add(xml, "speed", 1, speed);
  data.add(xml, "damage", 1, padded(s.damage, n));
  data.add(xml, "strain", 1, padded(s.strain, n));
  data.add(xml, "volume", 1, volume);
  data.add(xml, "body", 1, body);
  xml << "      </PointData>\n";
  xml << "      <Points>\n";
  data.add(xml, "position", 3, planar(q));
  xml << "      </Points>\n";
  xml << "      <Cells>\n";
  data.add(xml, "connectivity", 1, connectivity);
  data.add(xml, "offsets", 1, offsets);
  data.add(xml, "types", 1, types);
  xml << "      </Cells>\n"
      << "    </Piece>\n"
      << "  </UnstructuredGrid>\n";
  data.finish(xml);
  return xml.str();
}

std::string vtp_bodies_document(const Snapshot& s) {
  std::vector<double> points;
  std::vector<int64_t> connectivity, offsets;
  std::vector<int32_t> body;
  std::vector<uint8_t> is_virtual;
  std::vector<double> position, angle;
  if (s.geometry) {
    const auto& bodies = s.geometry->bodies;
    for (size_t k = 0; k < bodies.size() && k < s.bodies.size(); ++k) {
      const Snapshot::Pose& pose = s.bodies[k];
      for (const ShapeDef& shape : bodies[k].shapes) {
        const std::vector<Vec2> outline = shape_outline(shape, Vec2(pose.x, pose.y), pose.angle);
        if (outline.size() < 3) continue;
        for (const Vec2& p : outline) {
          connectivity.push_back(static_cast<int64_t>(points.size() / 3));
          points.insert(points.end(), {p.x(), p.y(), 0.0});
        }
        offsets.push_back(static_cast<int64_t>(connectivity.size()));
        body.push_back(static_cast<int32_t>(k));
        is_virtual.push_back(bodies[k].is_virtual ? 1 : 0);
        position.insert(position.end(), {pose.x, pose.y, 0.0});
        angle.push_back(pose.angle);
      }
    }
  }
  std::ostringstream xml;
  AppendedArrays data;
  open_document(xml, "PolyData", s.time, s.step);
  xml << "    <Piece NumberOfPoints=\"" << points.size() / 3 << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\""
      << " NumberOfStrips=\"0\" NumberOfPolys=\"" << offsets.size() << "\">\n";
  xml << "      <CellData Scalars=\"body\">\n";
  data.add(xml, "body", 1, body);
  data.add(xml, "virtual", 1, is_virtual);
  data.add(xml, "position", 3, position);
  data.add(xml, "angle", 1, angle);
  xml << "      </CellData>\n";
  xml << "      <Points>\n";
  data.add(xml, "points", 3, points);
  xml << "      </Points>\n";
  xml << "      <Polys>\n";
  data.add(xml, "connectivity", 1, connectivity);
  data.add(xml, "offsets", 1, offsets);
  xml << "      </Polys>\n"
      << "    </Piece>\n"
      << "  </PolyData>\n";
  data.finish(xml);
  return xml.str();
}

void write_vtu(const std::string& path, const Snapshot& snapshot) {
  write_file_atomically(path, vtu_document(snapshot));
}

void write_vtp_bodies(const std::string& path, const Snapshot& snapshot) {
  write_file_atomically(path, vtp_bodies_document(snapshot));
}

}  // namespace periflex
