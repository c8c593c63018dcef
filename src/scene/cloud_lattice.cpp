#include "scene/cloud_lattice.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace {

[[noreturn]] void fail_at(const std::string& file, long line, const std::string& message) {
  throw InputError(SourceLocation{file, static_cast<int>(line), 0, "shape.file"}, message);
}

}  // namespace

CloudLattice place_on_lattice(const ParticleCloud& cloud, double dx, double thickness, const std::string& file) {
  CloudLattice lattice;
  const long n = cloud.size();
  if (n == 0) return lattice;
  const auto line_of = [&](long k) { return k < static_cast<long>(cloud.line.size()) ? cloud.line[k] : 0L; };
  lattice.origin = Vec2(*std::min_element(cloud.x.begin(), cloud.x.end()), *std::min_element(cloud.y.begin(), cloud.y.end()));
  const double span = std::max(*std::max_element(cloud.x.begin(), cloud.x.end()) - lattice.origin.x(),
                               *std::max_element(cloud.y.begin(), cloud.y.end()) - lattice.origin.y());
  if (!(span / dx < 2e9))
    fail_at(file, 0, "the points span " + format_count(std::ceil(span / dx)) +
                         " grid spacings, more than 2000000000; raise grid_spacing");

  // each point's node, and how far from it the point lies
  const double volume = dx * dx * thickness;
  lattice.ix.resize(n);
  lattice.iy.resize(n);
  for (long k = 0; k < n; ++k) {
    const double fx = (cloud.x[k] - lattice.origin.x()) / dx, fy = (cloud.y[k] - lattice.origin.y()) / dx;
    const double rx = std::round(fx), ry = std::round(fy);
    const double off = std::max(std::abs(fx - rx), std::abs(fy - ry));
    if (!(off <= kLatticeTolerance))
      fail_at(file, line_of(k), "the point (" + format_number(cloud.x[k]) + ", " + format_number(cloud.y[k]) +
                                    ") lies " + format_number(off) + " grid spacings off the square grid of spacing " +
                                    format_number(dx) + " through the lowest point; a flexible body's points must lie "
                                    "on its grid (check grid_spacing and the file's unit)");
    if (!(std::abs(cloud.volume[k] - volume) <= kVolumeTolerance * volume))
      fail_at(file, line_of(k), "volume " + format_number(cloud.volume[k]) + " m^3 differs from grid_spacing^2 x "
                                    "thickness = " + format_number(volume) + " m^3; every particle of a body has that "
                                    "volume (check grid_spacing, thickness and the file's unit)");
    lattice.ix[k] = static_cast<int32_t>(rx);
    lattice.iy[k] = static_cast<int32_t>(ry);
  }

  // two points on one node would be one particle counted twice
  std::vector<long> order(n);
  std::iota(order.begin(), order.end(), 0L);
  std::sort(order.begin(), order.end(), [&](long a, long b) {
    return lattice.iy[a] != lattice.iy[b] ? lattice.iy[a] < lattice.iy[b]
           : lattice.ix[a] != lattice.ix[b] ? lattice.ix[a] < lattice.ix[b] : a < b;
  });
  for (long k = 1; k < n; ++k) {
    const long a = order[k - 1], b = order[k];
    if (lattice.ix[a] == lattice.ix[b] && lattice.iy[a] == lattice.iy[b])
      fail_at(file, line_of(b), "the point (" + format_number(cloud.x[b]) + ", " + format_number(cloud.y[b]) +
                                    ") coincides with the point of line " + std::to_string(line_of(a)) +
                                    " (the same grid node at spacing " + format_number(dx) + ")");
  }
  return lattice;
}

}  // namespace periflex
