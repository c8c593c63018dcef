// Surface correction of the 2D ordinary state-based model (LPS), computed once from the reference
// configuration. Near a free edge a particle's family is truncated: a disc less a cap, which holds
// more bonds along the edge than across it, so its dilatation over-counts strains along the edge
// and its deviatoric energy differs from the continuum's. Two factors set that right (an energy
// method in the spirit of Le & Bobaru 2018, docs/peridynamics.md section 12):
//  * bond weights: per particle an x and a y factor, a bond taking the mean of its two ends' and
//    combining them along its direction n as G = ((n_x / G_x)^2 + (n_y / G_y)^2)^(-1/2), found by a
//    fixed-point iteration that makes the weighted second moments sum_j w |xi|^2 n n^T of every
//    particle with a truncated family isotropic (to 1e-6): the dilatation is then exact for any
//    strain with axes along the grid, at an edge too;
//  * a per-particle shear modulus mu_i = mu s_i that gives the deviatoric energy of the continuum,
//    2 mu g^2, as the mean over pure shear along the axes and along the diagonals.
// Both are exactly 1 for a full family (its moments are isotropic, and the mean of the two shears
// is exact on the square lattice), so the interior is unchanged.
#pragma once

#include <vector>

#include "pd/bond_store.h"

namespace periflex {

struct LpsSurfaceFactors {
  std::vector<double> bond;   // G per stored bond direction (the same for both copies of a bond)
  std::vector<double> shear;  // s_i per particle
};

// weight: w beta per stored bond direction; nx, ny: the reference unit vector of each direction
// (from the grid offsets). Uses bonds.row, neighbor and the length table.
LpsSurfaceFactors lps_surface_factors(const BondStore& bonds, const std::vector<double>& weight,
                                      const std::vector<double>& nx, const std::vector<double>& ny);

}  // namespace periflex
