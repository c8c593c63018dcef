#include "pd/bond_kernel.h"

#include <algorithm>
#include <cmath>

namespace periflex {

// Below this many particles a loop runs on one thread: fork and join would cost more than the work.
constexpr int kParallelMin = 4096;

void add_bond_forces(const BondStore& bonds, const double* __restrict pos, double* __restrict force) {
  const int n = bonds.particle_count();
  const int64_t* __restrict row = bonds.row.data();
  const int32_t* __restrict nbr = bonds.neighbor.data();
  const double* __restrict inv_len0 = bonds.inv_length.data();
  const double* __restrict k = bonds.stiffness.data();

  // k (1/|xi| - 1/|y|) y = k s y/|y|: one square root and one division per bond, no branch
  // (a broken bond has k = 0)
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (int i = 0; i < n; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    double fx = 0.0, fy = 0.0;
#pragma omp simd reduction(+ : fx, fy)
    for (int64_t b = row[i]; b < row[i + 1]; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double f = k[b] * (inv_len0[b] - 1.0 / std::sqrt(dx * dx + dy * dy));
      fx += f * dx;
      fy += f * dy;
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
  }
}

void add_damped_bond_forces(const BondStore& bonds, const double* __restrict pos, const double* __restrict vel,
                            double eta_over_e, double* __restrict force) {
  const int n = bonds.particle_count();
  const int64_t* __restrict row = bonds.row.data();
  const int32_t* __restrict nbr = bonds.neighbor.data();
  const double* __restrict inv_len0 = bonds.inv_length.data();
  const double* __restrict k = bonds.stiffness.data();

  // stretch rate ds/dt = e . (v_j - v_i) / |xi|; the pair force k (s + eta/E ds/dt) acts along e
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (int i = 0; i < n; ++i) {
    const double xi = pos[2 * i], yi = pos[2 * i + 1];
    const double vxi = vel[2 * i], vyi = vel[2 * i + 1];
    double fx = 0.0, fy = 0.0;
#pragma omp simd reduction(+ : fx, fy)
    for (int64_t b = row[i]; b < row[i + 1]; ++b) {
      const int32_t j = nbr[b];
      const double dx = pos[2 * j] - xi, dy = pos[2 * j + 1] - yi;
      const double dvx = vel[2 * j] - vxi, dvy = vel[2 * j + 1] - vyi;
      const double inv_len = 1.0 / std::sqrt(dx * dx + dy * dy);
      const double rate = (dx * dvx + dy * dvy) * inv_len * inv_len0[b];
      const double f = k[b] * ((inv_len0[b] - inv_len) + eta_over_e * rate * inv_len);
      fx += f * dx;
      fy += f * dy;
    }
    force[2 * i] += fx;
    force[2 * i + 1] += fy;
  }
}

double bond_strain_energy(const BondStore& bonds, const double* pos) {
  const int n = bonds.particle_count();
  double sum = 0.0;
  // each pair is visited twice: a quarter of k |xi| s^2 per visit
#pragma omp parallel for schedule(static) reduction(+ : sum) if (n >= kParallelMin)
  for (int i = 0; i < n; ++i) {
    double local = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double s = std::sqrt(dx * dx + dy * dy) * bonds.inv_length[b] - 1.0;
      local += bonds.stiffness[b] * s * s / bonds.inv_length[b];
    }
    sum += 0.25 * local;
  }
  return sum;
}

double bond_damping_power(const BondStore& bonds, const double* pos, const double* vel, double eta_over_e) {
  const int n = bonds.particle_count();
  double sum = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : sum) if (n >= kParallelMin)
  for (int i = 0; i < n; ++i) {
    double local = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double dvx = vel[2 * j] - vel[2 * i], dvy = vel[2 * j + 1] - vel[2 * i + 1];
      const double rate = (dx * dvx + dy * dvy) / std::sqrt(dx * dx + dy * dy) * bonds.inv_length[b];
      local += bonds.stiffness[b] * eta_over_e * rate * rate / bonds.inv_length[b];
    }
    sum += 0.5 * local;
  }
  return sum;
}

long break_stretched_bonds(BondStore& bonds, const double* pos, double s0, const uint8_t* no_fail,
                           double& energy_released) {
  const int n = bonds.particle_count();
  long directed = 0;
  double energy = 0.0;
  // both copies of a bond see the same stretch bit for bit, so both break in this pass
#pragma omp parallel for schedule(static) reduction(+ : directed, energy) if (n >= kParallelMin)
  for (int i = 0; i < n; ++i) {
    if (no_fail && no_fail[i]) continue;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (bonds.broken[b]) continue;
      const int32_t j = bonds.neighbor[b];
      if (no_fail && no_fail[j]) continue;
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      const double s = std::sqrt(dx * dx + dy * dy) * bonds.inv_length[b] - 1.0;
      if (s > s0) {
        energy += 0.25 * bonds.stiffness[b] * s * s / bonds.inv_length[b];
        bonds.broken[b] = 1;
        bonds.stiffness[b] = 0.0;
        ++directed;
      }
    }
  }
  energy_released = energy;
  return directed / 2;
}

void max_bond_stretch(const BondStore& bonds, const double* pos, float* out) {
  const int n = bonds.particle_count();
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (int i = 0; i < n; ++i) {
    double most = 0.0;
    for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b) {
      if (bonds.broken[b]) continue;
      const int32_t j = bonds.neighbor[b];
      const double dx = pos[2 * j] - pos[2 * i], dy = pos[2 * j + 1] - pos[2 * i + 1];
      most = std::max(most, std::sqrt(dx * dx + dy * dy) * bonds.inv_length[b] - 1.0);
    }
    out[i] = static_cast<float>(most);
  }
}

}  // namespace periflex
