#include "scene/cloud_lattice.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace {

[[noreturn]] void fail_at(const std::string& file, long line, const std::string& message) {
  throw InputError(SourceLocation{file, static_cast<int>(line), 0, "shape.file"}, message);
}

// The file line point k came from (0: not from a line).
long line_of(const ParticleCloud& cloud, long k) { return k < static_cast<long>(cloud.line.size()) ? cloud.line[k] : 0L; }

}  // namespace

CloudLattice cloud_nodes(const ParticleCloud& cloud, double dx, double thickness, const std::string& file) {
  CloudLattice lattice;
  const long n = cloud.size();
  if (n == 0) return lattice;
  lattice.origin = Vec2(*std::min_element(cloud.x.begin(), cloud.x.end()), *std::min_element(cloud.y.begin(), cloud.y.end()));
  const double span = std::max(*std::max_element(cloud.x.begin(), cloud.x.end()) - lattice.origin.x(),
                               *std::max_element(cloud.y.begin(), cloud.y.end()) - lattice.origin.y());
  if (!(span / dx < 2e9))
    fail_at(file, 0, "the points span " + format_count(std::ceil(span / dx)) +
                         " grid spacings, more than 2000000000; raise grid_spacing");

  // each point's nearest node, and whether every point lies on it
  const double volume = dx * dx * thickness;
  lattice.ix.resize(n);
  lattice.iy.resize(n);
  for (long k = 0; k < n; ++k) {
    const double fx = (cloud.x[k] - lattice.origin.x()) / dx, fy = (cloud.y[k] - lattice.origin.y()) / dx;
    const double rx = std::round(fx), ry = std::round(fy);
    const double off = std::max(std::abs(fx - rx), std::abs(fy - ry));
    if (!(off <= kLatticeTolerance)) lattice.on_grid = false;
    if (!(std::abs(cloud.volume[k] - volume) <= kVolumeTolerance * volume)) lattice.cell_volumes = false;
    if (!(cloud.volume[k] <= kVolumeRange * volume && cloud.volume[k] >= volume / kVolumeRange))
      fail_at(file, line_of(cloud, k), "volume " + format_number(cloud.volume[k]) + " m^3 is " +
                                    format_number(cloud.volume[k] / volume) + " times grid_spacing^2 x thickness = " +
                                    format_number(volume) + " m^3; a particle's volume must lie within " +
                                    format_number(1.0 / kVolumeRange) + " and " + format_number(kVolumeRange) +
                                    " times it (check grid_spacing, thickness and the file's unit)");
    lattice.ix[k] = static_cast<int32_t>(rx);
    lattice.iy[k] = static_cast<int32_t>(ry);
  }
  return lattice;
}

CloudLattice place_on_lattice(const ParticleCloud& cloud, double dx, double thickness, const std::string& file) {
  CloudLattice lattice = cloud_nodes(cloud, dx, thickness, file);
  const long n = cloud.size();
  // two points on one node (on the grid), or closer than the tolerance (off it), would be one
  // particle counted twice: the points sorted by node (nodes are >= 0, below 2^31), each compared
  // with the earlier points of its own node and, off the grid, of the eight around it
  const auto node_key = [](int64_t ix, int64_t iy) { return iy * (int64_t{1} << 32) + ix; };
  std::vector<std::pair<int64_t, long>> by_node(n);
  for (long k = 0; k < n; ++k) by_node[k] = {node_key(lattice.ix[k], lattice.iy[k]), k};
  std::sort(by_node.begin(), by_node.end());
  const double near2 = kLatticeTolerance * dx * kLatticeTolerance * dx;
  const auto coincide = [&](long a, long b) {
    if (lattice.on_grid) return true;  // on one node
    const double ddx = cloud.x[a] - cloud.x[b], ddy = cloud.y[a] - cloud.y[b];
    return ddx * ddx + ddy * ddy <= near2;
  };
  const int reach = lattice.on_grid ? 0 : 1;
  long worst_b = -1, worst_a = -1;
  for (long b = 0; b < n && worst_b < 0; ++b) {
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dxn = -reach; dxn <= reach; ++dxn) {
        const int64_t key = node_key(int64_t{lattice.ix[b]} + dxn, int64_t{lattice.iy[b]} + dy);
        for (auto it = std::lower_bound(by_node.begin(), by_node.end(), std::make_pair(key, -1L));
             it != by_node.end() && it->first == key && it->second < b; ++it)
          if (coincide(it->second, b) && (worst_a < 0 || it->second < worst_a)) {
            worst_b = b;
            worst_a = it->second;
          }
      }
    }
  }
  if (worst_b >= 0)
    fail_at(file, line_of(cloud, worst_b),
            "the point (" + format_number(cloud.x[worst_b]) + ", " + format_number(cloud.y[worst_b]) +
                ") coincides with the point of line " + std::to_string(line_of(cloud, worst_a)) +
                (lattice.on_grid ? " (the same grid node at spacing " + format_number(dx) + ")"
                                 : " (closer than " + format_number(kLatticeTolerance) + " grid spacings)"));
  return lattice;
}

}  // namespace periflex
