#include "pd/state_based_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace periflex {

namespace {

// G of bond b from row i to j: the ends' mean factors per axis, combined along the bond
inline double bond_factor(const std::vector<double>& gx, const std::vector<double>& gy, int i, int j, double nx,
                          double ny) {
  const double mx = 0.5 * (gx[i] + gx[j]), my = 0.5 * (gy[i] + gy[j]);
  return 1.0 / std::sqrt(nx * nx / (mx * mx) + ny * ny / (my * my));
}

// Deviatoric energy per unit shear modulus, (4 / m) sum w (e - theta |xi| / 2)^2 V with the volume
// cancelled, of row i under the affine strain [[hxx, hxy], [hxy, hyy]] of unit size.
double deviatoric_energy(const BondStore& bonds, const std::vector<double>& w, const std::vector<double>& nx,
                         const std::vector<double>& ny, int i, double hxx, double hyy, double hxy) {
  double moment = 0.0, sum = 0.0;
  for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
    const double l = 1.0 / bonds.inv_length(b);
    const double e = l * (hxx * nx[b] * nx[b] + hyy * ny[b] * ny[b] + 2.0 * hxy * nx[b] * ny[b]);
    moment += w[b] * l * l;
    sum += w[b] * l * e;
  }
  if (!(moment > 0.0)) return 0.0;
  const double theta = 2.0 * sum / moment;
  double dev = 0.0;
  for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
    const double l = 1.0 / bonds.inv_length(b);
    const double ed = l * (hxx * nx[b] * nx[b] + hyy * ny[b] * ny[b] + 2.0 * hxy * nx[b] * ny[b]) - 0.5 * theta * l;
    dev += w[b] * ed * ed;
  }
  return 4.0 * dev / moment;
}

}  // namespace

LpsSurfaceFactors lps_surface_factors(const BondStore& bonds, const std::vector<double>& weight,
                                      const std::vector<double>& nx, const std::vector<double>& ny) {
  const int n = bonds.particle_count();
  std::vector<double> gx(n, 1.0), gy(n, 1.0);
  LpsSurfaceFactors out;
  out.bond.assign(weight.size(), 1.0);
  // fixed point for isotropic second moments: a particle whose x-moment exceeds its y-moment by r
  // divides its x factor by sqrt(r) and multiplies its y factor by it (the product stays 1); its
  // bonds see half of that through the mean with their other ends, hence the iteration. Only the
  // particles with a truncated family (anisotropic moments at the start: within a horizon of a free
  // edge, a hole or a notch) take factors; full families keep 1, and their moments, touched only
  // through bonds to the surface layer, stay isotropic to a fraction of a percent. Letting them
  // adjust too spread the correction through the whole body over a hundred sweeps, and made the
  // strip of the tests 0.6 % stiffer rather than 0.1 % softer than the lattice's interior. A sweep
  // visits only the rows whose own or neighbours' factors changed in the sweep before.
  constexpr int kMaxSweeps = 200;
  constexpr double kTolerance = 1e-6;
  std::vector<uint8_t> dirty(n, 1), truncated(n, 0);
  std::vector<double> step(n, 1.0);
  std::vector<int> changed;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    changed.clear();
    for (int i = 0; i < n; ++i) {
      if (!dirty[i]) continue;
      double kxx = 0.0, kyy = 0.0;
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const double l2 = 1.0 / (bonds.inv_length(b) * bonds.inv_length(b));
        const double g = bond_factor(gx, gy, i, bonds.neighbor[b], nx[b], ny[b]);
        kxx += weight[b] * g * l2 * nx[b] * nx[b];
        kyy += weight[b] * g * l2 * ny[b] * ny[b];
      }
      // a family without bonds across one axis (a single row) cannot be made isotropic
      if (!(kxx > 0.0) || !(kyy > 0.0)) continue;
      const double r = kxx / kyy;
      if (sweep == 0) truncated[i] = std::abs(r - 1.0) > 1e-12;
      if (!truncated[i] || std::abs(r - 1.0) <= kTolerance) continue;
      // at most a factor 2 a sweep, so that a nearly one-sided family cannot swing the iteration
      step[i] = std::sqrt(std::clamp(r, 0.25, 4.0));
      changed.push_back(i);
    }
    if (changed.empty()) break;
    // apply the sweep's steps together, then mark the rows that hold a changed particle
    std::fill(dirty.begin(), dirty.end(), 0);
    for (int i : changed) {
      gx[i] /= step[i];
      gy[i] *= step[i];
      dirty[i] = 1;
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) dirty[bonds.neighbor[b]] = 1;
    }
  }
  for (int i = 0; i < n; ++i)
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b)
      out.bond[b] = bond_factor(gx, gy, i, bonds.neighbor[b], nx[b], ny[b]);

  // shear factors with the corrected weights: the continuum holds 2 mu under each unit shear
  std::vector<double> w(weight.size());
  for (size_t b = 0; b < w.size(); ++b) w[b] = weight[b] * out.bond[b];
  out.shear.assign(n, 1.0);
  for (int i = 0; i < n; ++i) {
    const double axes = deviatoric_energy(bonds, w, nx, ny, i, 1.0, -1.0, 0.0);
    const double diagonal = deviatoric_energy(bonds, w, nx, ny, i, 0.0, 0.0, 1.0);
    const double s = 4.0 / (axes + diagonal);
    if (axes + diagonal > 0.0 && std::abs(s - 1.0) > 1e-12) out.shear[i] = s;
  }
  return out;
}

}  // namespace periflex
