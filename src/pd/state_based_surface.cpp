#include "pd/state_based_surface.h"

#include <algorithm>
#include <cmath>

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
  // bonds see half of that through the mean with their other ends, hence the iteration. Full
  // families have r = 1 (to round-off, taken as exact) and keep their factors of 1.
  constexpr int kMaxIterations = 200;
  constexpr double kTolerance = 1e-9;
  for (int it = 0; it < kMaxIterations; ++it) {
    for (int i = 0; i < n; ++i)
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b)
        out.bond[b] = bond_factor(gx, gy, i, bonds.neighbor[b], nx[b], ny[b]);
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
      double kxx = 0.0, kyy = 0.0;
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
        const double l2 = 1.0 / (bonds.inv_length(b) * bonds.inv_length(b));
        kxx += weight[b] * out.bond[b] * l2 * nx[b] * nx[b];
        kyy += weight[b] * out.bond[b] * l2 * ny[b] * ny[b];
      }
      // a family without bonds across one axis (a single row) cannot be made isotropic
      if (!(kxx > 0.0) || !(kyy > 0.0)) continue;
      const double r = kxx / kyy;
      if (std::abs(r - 1.0) < 1e-12) continue;
      worst = std::max(worst, std::abs(r - 1.0));
      // at most a factor 2 a step, so that a nearly one-sided family cannot swing the iteration
      const double step = std::sqrt(std::clamp(r, 0.25, 4.0));
      gx[i] /= step;
      gy[i] *= step;
    }
    if (worst < kTolerance) break;
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
