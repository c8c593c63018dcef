// Peridynamic body checks that need no time integration: bond family, material constants,
// corrections, pre-cracks, determinism, the stable step and input refusal.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "core/error.h"
#include "pd/pd_body.h"
#include "pd/bond_kernel.h"
#include "pd/pd_material.h"
#include "pd_test_support.h"

namespace periflex {
namespace {

using test::affine_positions;
using test::box;
using test::glass_plate;

// Index of the particle nearest the centre of a body (an interior particle).
int centre_particle(const PdBody& body) { return body.nearest_particle(Vec2(1e-9, 1e-9)); }

long row_length(const PdBody& body, int i) { return body.bonds().row[i + 1] - body.bonds().row[i]; }

TEST(PdBonds, InteriorParticleHas28BondsAtHorizonRatio3) {
  // grid points (a, b) != 0 with a^2 + b^2 <= 9: 28 of them
  FlexBodyDef def = glass_plate(0.02, 0.02, 1e-3);
  def.partial_volume_correction = false;
  auto body = PdBody::build(def, 0);
  EXPECT_EQ(row_length(*body, centre_particle(*body)), 28);
}

TEST(PdBonds, PartialVolumeBandAddsTheRingAtSqrt10) {
  // with the band delta + dx/2 = 3.5 dx the 8 points with a^2 + b^2 = 10 join as partial neighbours
  FlexBodyDef def = glass_plate(0.02, 0.02, 1e-3);
  auto body = PdBody::build(def, 0);
  EXPECT_EQ(row_length(*body, centre_particle(*body)), 36);
}

TEST(PdBonds, EveryBondIsStoredInBothDirectionsWithIdenticalData) {
  auto body = PdBody::build(glass_plate(0.012, 0.008, 1e-3), 0);
  const BondStore& b = body->bonds();
  for (int i = 0; i < b.particle_count(); ++i) {
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int j = b.neighbor[k];
      const auto begin = b.neighbor.begin() + b.row[j], end = b.neighbor.begin() + b.row[j + 1];
      const auto it = std::find(begin, end, i);
      ASSERT_NE(it, end);
      const int64_t back = it - b.neighbor.begin();
      EXPECT_EQ(b.length_class[k], b.length_class[back]);
      EXPECT_EQ(b.stiffness[k], b.stiffness[back]);
    }
  }
}

TEST(PdMaterial, MicromodulusReproducesContinuumEnergyOfIsotropicExpansion) {
  // midpoint quadrature of W = 1/4 int_H c s^2 |xi| dV (dV = t r dr dtheta, s = eps) against the
  // classical plane-stress (nu = 1/3) and plane-strain (nu = 1/4) energies; 1e-6: quadrature error
  const double e = 72e9, t = 2e-3, delta = 3e-3, eps = 1e-3;
  for (bool plane_strain : {false, true}) {
    const double c = micromodulus(e, t, delta, plane_strain);
    const int nr = 20000;
    double w = 0.0;
    for (int k = 0; k < nr; ++k) {
      const double r = (k + 0.5) * delta / nr;
      w += 0.25 * c * eps * eps * r * t * r * 2.0 * kPi * (delta / nr);
    }
    const double nu = implied_poisson_ratio(plane_strain);
    const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu)), mu = e / (2 * (1 + nu));
    // plane strain: 2 (lambda + mu) eps^2; plane stress: E eps^2 / (1 - nu)
    const double classical = plane_strain ? 2 * (lambda + mu) * eps * eps : e / (1 - nu) * eps * eps;
    EXPECT_NEAR(w / classical, 1.0, 1e-6) << (plane_strain ? "strain" : "stress");
  }
}

TEST(PdMaterial, CriticalStretchReleasesFractureEnergyAcrossACrackLine) {
  // energy of all bonds crossing a straight crack per unit length and thickness, by quadrature
  // over the lower point's depth z, bond length r and angle: must equal G0. 1e-4: quadrature error
  const double e = 72e9, t = 1e-3, delta = 1e-3, g0 = 3.8;
  for (auto influence_kind : {FlexBodyDef::Influence::kConstant, FlexBodyDef::Influence::kConical}) {
    for (bool plane_strain : {false, true}) {
      const double c = micromodulus(e, t, delta, plane_strain);
      const double s0 = critical_stretch_from_energy(g0, e, delta, plane_strain, influence_kind);
      const int nz = 400, nr = 400;
      double per_length = 0.0;
      for (int a = 0; a < nz; ++a) {
        const double z = (a + 0.5) * delta / nz;
        for (int b = 0; b < nr; ++b) {
          const double r = z + (b + 0.5) * (delta - z) / nr;
          const double w = influence(influence_kind, r, delta);
          const double bond = 0.5 * c * w * s0 * s0 * r;           // energy per unit volume^2
          per_length += bond * (2.0 * std::acos(z / r)) * t * r * ((delta - z) / nr) * t * (delta / nz);
        }
      }
      EXPECT_NEAR(per_length / t / g0, 1.0, 1e-3) << plane_strain << " " << static_cast<int>(influence_kind);
    }
  }
}

// Uniaxial stress along x in plane stress with nu = 1/3: eps_yy = -eps / 3, W = E eps^2 / 2.
Eigen::Matrix2d uniaxial(double eps) {
  Eigen::Matrix2d h;
  h << eps, 0.0, 0.0, -eps / 3.0;
  return h;
}

TEST(PdElasticity, InteriorEnergyDensityRecoversYoungsModulus) {
  // affine uniaxial stress; E from W = E eps^2 / 2 at the centre. 2%: the square lattice's
  // anisotropy and the discrete horizon (the corrections calibrate isotropic expansion only)
  const double eps = 1e-4, e = 72e9;
  for (bool surface : {true, false}) {
    FlexBodyDef def = glass_plate(0.04, 0.04, 1e-3);
    def.surface_correction = surface;
    auto body = PdBody::build(def, 0);
    std::vector<double> w;
    body->strain_energy_density(affine_positions(*body, uniaxial(eps)), w);
    const double e_recovered = 2.0 * w[centre_particle(*body)] / (eps * eps);
    RecordProperty(surface ? "E_ratio_corrected" : "E_ratio_uncorrected", std::to_string(e_recovered / e));
    std::printf("interior E / E_input (surface correction %s): %.5f\n", surface ? "on" : "off", e_recovered / e);
    if (surface) {
      EXPECT_NEAR(e_recovered / e, 1.0, 0.02);
    }
  }
}

TEST(PdElasticity, PartialVolumesBringTheUncorrectedInteriorCloserToE) {
  // without the surface correction the interior stiffness is the raw lattice sum: counting
  // whole cells out to delta overshoots the horizon's area, the exact cell fractions much less
  const double eps = 1e-4, e = 72e9;
  double error[2];
  for (int partial = 0; partial < 2; ++partial) {
    FlexBodyDef def = glass_plate(0.04, 0.04, 1e-3);
    def.surface_correction = false;
    def.partial_volume_correction = partial == 1;
    auto body = PdBody::build(def, 0);
    std::vector<double> w;
    body->strain_energy_density(affine_positions(*body, uniaxial(eps)), w);
    error[partial] = std::abs(2.0 * w[centre_particle(*body)] / (eps * eps) / e - 1.0);
    std::printf("interior |E/E_input - 1| without surface correction, partial volumes %s: %.4f\n",
                partial ? "on" : "off", error[partial]);
  }
  EXPECT_LT(error[1], 0.5 * error[0]);
}

TEST(PdElasticity, BondForcesAcrossACutRecoverYoungsModulus) {
  // force balance: the x-force that the particles right of the plane x = 0 exert on those left
  // of it, over an interior band of height hb, is sigma_xx * hb * t = E eps hb t.
  // 2%: as above, plus the band edges
  const double eps = 1e-4, e = 72e9, dx = 1e-3, t = 1e-3;
  FlexBodyDef def = glass_plate(0.04, 0.04, dx, t);
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd q = affine_positions(*body, uniaxial(eps));
  const BondStore& b = body->bonds();
  const std::vector<double>& x = body->reference_positions();
  const double half_band = 0.01;
  double fx = 0.0;
  int rows = 0;
  for (int i = 0; i < body->particle_count(); ++i) {
    if (x[2 * i] > 0.0 || std::abs(x[2 * i + 1]) > half_band) continue;
    if (x[2 * i] > -0.5 * dx - 1e-12) ++rows;
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int j = b.neighbor[k];
      if (x[2 * j] < 0.0) continue;
      const double dxq = q[2 * j] - q[2 * i], dyq = q[2 * j + 1] - q[2 * i + 1];
      const double len = std::hypot(dxq, dyq);
      fx += double(b.stiffness[k]) * (len * b.inv_length(k) - 1.0) * dxq / len;
    }
  }
  const double sigma = fx / (rows * dx * t);
  std::printf("E from the cut: %.5f of input\n", sigma / (e * eps));
  EXPECT_NEAR(sigma / (e * eps), 1.0, 0.02);
}

TEST(PdElasticity, AffineFieldLeavesInteriorParticlesInEquilibrium) {
  // a uniform strain produces no net force away from the boundary; 1e-9 of one bond's force
  // magnitude is round-off
  const double eps = 1e-4;
  auto body = PdBody::build(glass_plate(0.04, 0.04, 1e-3), 0);
  const Eigen::VectorXd q = affine_positions(*body, uniaxial(eps));
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  body->add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  const int c = centre_particle(*body);
  const double bond_force = body->bonds().stiffness[body->bonds().row[c]] * eps;
  EXPECT_LT(std::hypot(g[2 * c], g[2 * c + 1]), 1e-9 * bond_force * 36);
}

TEST(PdElasticity, SurfaceCorrectionStiffensEdgeParticles) {
  // at the middle of the top edge, under uniaxial stress along the edge (sigma_yy = 0 there,
  // so the classical W = E eps^2 / 2 holds), the corrected particle is much closer to the bulk
  const double eps = 1e-4, e = 72e9;
  double error[2];
  for (int surface = 0; surface < 2; ++surface) {
    FlexBodyDef def = glass_plate(0.04, 0.04, 1e-3);
    def.surface_correction = surface == 1;
    auto body = PdBody::build(def, 0);
    std::vector<double> w;
    body->strain_energy_density(affine_positions(*body, uniaxial(eps)), w);
    const int edge = body->nearest_particle(Vec2(0.0, 0.02));
    error[surface] = std::abs(2.0 * w[edge] / (eps * eps) / e - 1.0);
    std::printf("edge particle |E/E_input - 1| with surface correction %s: %.4f\n", surface ? "on" : "off",
                error[surface]);
  }
  EXPECT_GT(error[0], 0.2);             // uncorrected edge particles lose about a third of the stiffness
  EXPECT_LT(error[1], 0.5 * error[0]);  // the correction at least halves the error
}

TEST(PdNotch, RemovesExactlyTheBondsCrossingTheNotch) {
  // notch along y = 0 from the left edge to x = 0.0032 (off the bond crossing points); particles sit at y = +-dx/2, +-3dx/2, ...
  // a bond crosses it when its ends lie on opposite sides and it meets y = 0 at x < 0.003
  const double dx = 1e-3, tip = 0.0032;
  FlexBodyDef def = glass_plate(0.02, 0.012, dx);
  auto intact = PdBody::build(def, 0);
  NotchDef notch;
  notch.p1 = Vec2(-0.011, 0.0);
  notch.p2 = Vec2(tip, 0.0);
  def.notches.push_back(notch);
  auto cut = PdBody::build(def, 0);

  std::vector<std::pair<int, int>> before, after;
  intact->bond_pairs(before, 1u << 30);
  cut->bond_pairs(after, 1u << 30);
  const std::vector<double>& x = intact->reference_positions();
  long expected_removed = 0;
  std::set<std::pair<int, int>> kept(after.begin(), after.end());
  for (const auto& [i, j] : before) {
    const double yi = x[2 * i + 1], yj = x[2 * j + 1];
    bool crosses = false;
    if (yi * yj < 0.0) {
      const double xc = x[2 * i] + (x[2 * j] - x[2 * i]) * (0.0 - yi) / (yj - yi);
      crosses = xc < tip;
    }
    expected_removed += crosses ? 1 : 0;
    EXPECT_EQ(kept.count({i, j}), crosses ? 0u : 1u) << i << " " << j;
  }
  EXPECT_GT(expected_removed, 0);
  EXPECT_EQ(intact->bond_count() - cut->bond_count(), expected_removed);
}

// A notch is a closed segment: one that ends exactly where bonds cross its line (here at x = 0,
// between the particle columns at x = -dx/2 and +dx/2) cuts them, as one reaching a tenth of a
// cell further does; one stopping a tenth of a cell short does not. Before, an exact
// floating-point zero left the bonds through the end point intact.
TEST(PdNotch, ANotchEndingOnABondCutsIt) {
  const double dx = 1e-3;
  const FlexBodyDef def = glass_plate(0.02, 0.012, dx);
  auto bonds_with_tip_at = [&](double tip) {
    FlexBodyDef notched = def;
    NotchDef notch;
    notch.p1 = Vec2(-0.011, 0.0);
    notch.p2 = Vec2(tip, 0.0);
    notched.notches.push_back(notch);
    return PdBody::build(notched, 0)->bond_count();
  };
  // the bonds of the un-notched plate that cross y = 0 exactly at x = 0
  auto intact = PdBody::build(def, 0);
  std::vector<std::pair<int, int>> pairs;
  intact->bond_pairs(pairs, 1u << 30);
  const std::vector<double>& x = intact->reference_positions();
  long through_end = 0;
  for (const auto& [i, j] : pairs) {
    const double yi = x[2 * i + 1], yj = x[2 * j + 1];
    if (yi * yj >= 0.0) continue;
    const double xc = x[2 * i] + (x[2 * j] - x[2 * i]) * (0.0 - yi) / (yj - yi);
    through_end += std::abs(xc) < 1e-9 * dx;
  }
  ASSERT_GT(through_end, 0);
  const long on_end = bonds_with_tip_at(0.0);
  EXPECT_EQ(on_end, bonds_with_tip_at(0.1 * dx));
  EXPECT_EQ(bonds_with_tip_at(-0.1 * dx) - on_end, through_end);
}

// damage = "include_notch": bonds cut by a notch count as broken, so the particles along it start
// damaged (half their weight gone at most: the notch cuts one side); "exclude_notch" (the
// default) leaves them out of the initial weight, and nothing starts damaged.
TEST(PdNotch, DamageCountsNotchBondsOnlyWhenAsked) {
  const double dx = 1e-3;
  FlexBodyDef def = glass_plate(0.02, 0.012, dx);
  NotchDef notch;
  notch.p1 = Vec2(-0.011, 0.0);
  notch.p2 = Vec2(0.0032, 0.0);
  def.notches.push_back(notch);
  std::vector<float> damage;
  PdBody::build(def, 0)->damage(damage);
  EXPECT_EQ(*std::max_element(damage.begin(), damage.end()), 0.0f);

  def.damage = FlexBodyDef::Damage::kIncludeNotch;
  auto body = PdBody::build(def, 0);
  body->damage(damage);
  const std::vector<double>& x = body->reference_positions();
  for (size_t i = 0; i < damage.size(); ++i) {
    const double px = x[2 * i], py = x[2 * i + 1];
    // beside the notch, within the horizon: bonds across it are gone; elsewhere nothing is
    const bool beside = std::abs(py) < 3 * dx && px < 0.0032 + 3 * dx;
    if (std::abs(py) < dx && px < 0.0) {
      EXPECT_GT(damage[i], 0.2f) << px << ", " << py;
      EXPECT_LT(damage[i], 0.5f) << px << ", " << py;
    }
    if (!beside) {
      EXPECT_EQ(damage[i], 0.0f) << px << ", " << py;
    }
  }
}

TEST(PdDeterminism, ForcesAreBitIdenticalAcrossThreadCounts) {
  // each particle gathers its own bonds in a fixed order, so the thread count cannot change a bit;
  // the energy is summed in fixed ranges added in order: the same bits too
  FlexBodyDef def = glass_plate(0.05, 0.03, 5e-4);
  def.bond_damping = 1e3;
  auto body = PdBody::build(def, 0);
  // the same state is evaluated three times: nothing may break in between
  body->set_break_timing(PdBody::BreakTiming::kAfterStep);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1e-6);
  Eigen::VectorXd q = affine_positions(*body, uniaxial(1e-4)), qd(q.size());
  for (int k = 0; k < q.size(); ++k) {
    q[k] += noise(rng);
    qd[k] = noise(rng) * 1e3;
  }
  const int saved = omp_get_max_threads();
  std::vector<Eigen::VectorXd> forces;
  std::vector<double> energies;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
    body->add_forces(q, qd, 0.0, g);
    forces.push_back(g);
    energies.push_back(body->potential_energy(q));
  }
  omp_set_num_threads(saved);
  for (size_t k = 1; k < forces.size(); ++k) {
    EXPECT_EQ(forces[k], forces[0]);
    EXPECT_EQ(energies[k], energies[0]) << "thread counts 1 and " << k + 1;
  }
}

TEST(PdStableStep, CriticalStepMatchesSillingAskariForAnInteriorParticle) {
  // without corrections every bond has C = c: dt = sqrt(2 rho / (c V sum_j 1/|xi_j|)) over the
  // 28 lattice neighbours of an interior particle (which has the most bonds, hence the minimum)
  FlexBodyDef def = glass_plate(0.02, 0.02, 1e-3);
  def.partial_volume_correction = false;
  def.surface_correction = false;
  auto body = PdBody::build(def, 0);
  double sum_inv = 0.0;
  for (int a = -3; a <= 3; ++a)
    for (int b = -3; b <= 3; ++b)
      if ((a || b) && a * a + b * b <= 9) sum_inv += 1.0 / (1e-3 * std::sqrt(a * a + b * b));
  const double c = micromodulus(72e9, 1e-3, 3e-3, false), v = 1e-6 * 1e-3;
  const double expected = std::sqrt(2.0 * 2440.0 / (c * v * sum_inv));
  // 1e-7: bond stiffnesses are stored in single precision (relative rounding up to 6e-8 each)
  EXPECT_NEAR(body->critical_time_step() / expected, 1.0, 1e-7);
}

TEST(PdInput, RefusesHugeGridsWithTheEstimatedCount) {
  FlexBodyDef def = glass_plate(1.0, 1.0, 1e-4);  // 1e8 particles
  def.where.file = "big.toml";
  def.where.line = 12;
  try {
    PdBody::build(def, 0);
    FAIL() << "no refusal";
  } catch (const InputError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("100000000"), std::string::npos) << what;
    EXPECT_NE(what.find("big.toml:12"), std::string::npos) << what;
    EXPECT_NE(what.find("grid_spacing"), std::string::npos) << what;
  }
}

TEST(PdInput, WarnsAboutAPoissonRatioBondBasedPdCannotRepresent) {
  FlexBodyDef def = glass_plate(0.01, 0.01, 1e-3);
  def.material.poisson_ratio = 0.22;
  EXPECT_EQ(PdBody::build(def, 0)->warnings().size(), 1u);
  def.material.poisson_ratio = 1.0 / 3.0;
  EXPECT_TRUE(PdBody::build(def, 0)->warnings().empty());
  def.material.plane_strain = true;
  EXPECT_EQ(PdBody::build(def, 0)->warnings().size(), 1u);
}

TEST(PdGrid, BoxWithHoleHasTheExpectedParticleCount) {
  // 20 x 10 cells, a circular hole of radius 2.5 dx at the centre removes the 4 x 4 block minus
  // its corners (12 particles at distance sqrt(0.5^2 + 0.5^2) and sqrt(0.5^2 + 1.5^2) dx)
  FlexBodyDef def = glass_plate(0.02, 0.01, 1e-3);
  ShapeDef hole;
  hole.kind = ShapeDef::Kind::kCircle;
  hole.radius = 1.7e-3;
  def.holes.push_back(hole);
  auto body = PdBody::build(def, 0);
  EXPECT_EQ(body->particle_count(), 200 - 12);
  EXPECT_NEAR(body->volumes()[0], 1e-9, 1e-21);
  EXPECT_NEAR(body->masses()[0], 2440.0 * 1e-9, 1e-18);
}

TEST(PdLoads, TractionOnAnEdgeRowSumsToTractionTimesEdgeLengthTimesThickness) {
  FlexBodyDef def = glass_plate(0.02, 0.01, 1e-3, 2e-3);
  RegionLoadDef load;
  load.kind = RegionLoadDef::Kind::kTraction;
  load.region = box(0.02, 0.001, Vec2(0.0, 0.0045));
  load.fy = TimeFunction::constant(2e6);
  def.loads.push_back(load);
  load.region = box(0.02, 0.002, Vec2(0.0, -0.004));  // two rows: same total force
  load.fy = TimeFunction::constant(-2e6);
  def.loads.push_back(load);
  def.surface_correction = false;
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(body->reference_positions().data(), 2 * body->particle_count());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  body->add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  double top = 0.0, bottom = 0.0;
  for (int i = 0; i < body->particle_count(); ++i) (q[2 * i + 1] > 0 ? top : bottom) += g[2 * i + 1];
  EXPECT_NEAR(top, 2e6 * 0.02 * 2e-3, 1e-6);
  EXPECT_NEAR(bottom, -2e6 * 0.02 * 2e-3, 1e-6);
}

TEST(PdLoads, PrescribedVelocityBecomesItsDisplacement) {
  FlexBodyDef def = glass_plate(0.02, 0.01, 1e-3);
  RegionLoadDef load;
  load.kind = RegionLoadDef::Kind::kPrescribedVelocity;
  load.region = box(0.001, 0.01, Vec2(0.0095, 0.0));
  load.fx = TimeFunction::constant(0.5);
  def.loads.push_back(load);
  auto body = PdBody::build(def, 7);
  const std::vector<PrescribedCoordinate> pcs = body->prescribed_coordinates();
  ASSERT_EQ(pcs.size(), 10u);  // one column of 10 particles, x only
  for (const PrescribedCoordinate& pc : pcs) {
    EXPECT_EQ((pc.coordinate - 7) % 2, 0);
    EXPECT_DOUBLE_EQ(pc.displacement(2.0), 1.0);
    EXPECT_DOUBLE_EQ(pc.reference, body->reference_positions()[pc.coordinate - 7]);
    EXPECT_DOUBLE_EQ(body->initial_velocities()[pc.coordinate - 7], 0.5);
  }
}

TEST(PdDamage, BrokenBondsRaiseDamageAndReleaseTheirEnergy) {
  // stretch a strip uniformly past s0: every breakable bond goes, damage -> 1, and the released
  // energy equals the strain energy held just before (1e-12 relative: same sums)
  FlexBodyDef def = glass_plate(0.02, 0.004, 1e-3);
  def.material.critical_stretch = 1e-3;
  auto body = PdBody::build(def, 0);
  Eigen::Matrix2d h = Eigen::Matrix2d::Identity() * 2e-3;
  const Eigen::VectorXd q = affine_positions(*body, h);
  const double stored = body->potential_energy(q);
  const FractureUpdate up = body->update_fracture(q);
  EXPECT_EQ(up.bonds_broken, body->bond_count());
  EXPECT_NEAR(up.energy_released / stored, 1.0, 1e-12);
  std::vector<float> d;
  body->damage(d);
  for (float v : d) EXPECT_FLOAT_EQ(v, 1.0f);
  EXPECT_EQ(body->potential_energy(q), 0.0);
}

TEST(PdDamage, NoFailRegionKeepsItsBonds) {
  FlexBodyDef def = glass_plate(0.02, 0.004, 1e-3);
  def.material.critical_stretch = 1e-3;
  def.no_fail_regions.push_back(box(0.004, 0.004, Vec2(0.008, 0.0)));
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd q = affine_positions(*body, Eigen::Matrix2d::Identity() * 2e-3);
  body->update_fracture(q);
  std::vector<float> d;
  body->damage(d);
  const int inside = body->nearest_particle(Vec2(0.0085, 0.0005));
  const int outside = body->nearest_particle(Vec2(-0.008, 0.0));
  EXPECT_EQ(d[inside], 0.0f);
  EXPECT_EQ(d[outside], 1.0f);
}

TEST(PdDamage, FractureOffNeverBreaks) {
  FlexBodyDef def = glass_plate(0.02, 0.004, 1e-3);
  def.material.critical_stretch = 1e-3;
  def.fracture = false;
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd q = affine_positions(*body, Eigen::Matrix2d::Identity() * 2e-3);
  EXPECT_EQ(body->update_fracture(q).bonds_broken, 0);
  EXPECT_EQ(body->broken_bond_count(), 0);
}

}  // namespace
}  // namespace periflex

namespace periflex {
namespace {

// A plate in a random state near the reference, for kernel comparisons.
struct Perturbed {
  std::unique_ptr<PdBody> body;
  Eigen::VectorXd q, qd;
};

Perturbed perturbed_plate(double bond_damping, double global_damping) {
  FlexBodyDef def = test::glass_plate(0.03, 0.02, 5e-4);
  def.bond_damping = bond_damping;
  def.global_damping = global_damping;
  Perturbed p;
  p.body = PdBody::build(def, 0);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1e-6);
  p.q = test::affine_positions(*p.body, Eigen::Matrix2d::Identity() * 1e-4);
  p.qd.resize(p.q.size());
  for (int k = 0; k < p.q.size(); ++k) {
    p.q[k] += noise(rng);
    p.qd[k] = noise(rng) * 1e3;
  }
  return p;
}

TEST(PdKernel, VectorAndPortableLoopsAgreeToRoundOff) {
  // same formula, different summation order (and, in the AVX-512 loops, 1/|y| refined from an
  // estimate): 1e-12 of the largest force component. Each width the CPU lacks runs the next
  // narrower loop, so the comparison then holds trivially.
  for (VectorKernels width : {VectorKernels::kAvx2, VectorKernels::kAvx512}) {
    for (double eta : {0.0, 50.0}) {
      Perturbed p = perturbed_plate(eta, 0.0);
      Eigen::VectorXd g_vec = Eigen::VectorXd::Zero(p.q.size()), g_port = g_vec;
      set_vector_kernels(width);
      p.body->add_forces(p.q, p.qd, 0.0, g_vec);
      set_vector_kernels(VectorKernels::kPortable);
      p.body->add_forces(p.q, p.qd, 0.0, g_port);
      set_vector_kernels(VectorKernels::kAvx512);
      EXPECT_LT((g_vec - g_port).cwiseAbs().maxCoeff(), 1e-12 * g_port.cwiseAbs().maxCoeff())
          << "width " << static_cast<int>(width) << ", eta " << eta;
    }
  }
}

TEST(PdKernel, RowMaximaOfTheForceLoopsMatchTheExactStretch) {
  // the force loops' by-product row maxima let the fracture pass skip rows; they must agree
  // with the exact stretch (max_bond_stretch at the same positions) to far below any s0
  for (VectorKernels width : {VectorKernels::kPortable, VectorKernels::kAvx2, VectorKernels::kAvx512}) {
    Perturbed p = perturbed_plate(0.0, 0.0);
    set_vector_kernels(width);
    std::vector<double> most(p.body->particle_count());
    Eigen::VectorXd g = Eigen::VectorXd::Zero(p.q.size());
    add_bond_forces(p.body->bonds(), p.q.data(), g.data(), most.data());
    set_vector_kernels(VectorKernels::kAvx512);
    const BondStore& b = p.body->bonds();
    double worst = 0.0;
    for (int i = 0; i < b.particle_count(); ++i) {
      double exact = -1.0;
      for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
        const int j = b.neighbor[k];
        const double dx = p.q[2 * j] - p.q[2 * i], dy = p.q[2 * j + 1] - p.q[2 * i + 1];
        if (b.stiffness[k] > 0.0f) exact = std::max(exact, std::sqrt(dx * dx + dy * dy) * b.inv_length(k) - 1.0);
      }
      worst = std::max(worst, std::abs(most[i] - exact));
    }
    // a few units in the last place of a stretch near 1e-4; far below the fracture pass's slack
    EXPECT_LT(worst, 1e-13) << static_cast<int>(width);
  }
}

TEST(PdDamping, DissipationPowerIsMinusTheDampingForcesPower) {
  // the power the damping forces do on the particles (forces with damping minus forces
  // without, dotted with qd) must be the negative of the reported dissipation; 1e-9 relative:
  // round-off in the difference of two large force vectors
  Perturbed p = perturbed_plate(50.0, 300.0);
  Eigen::VectorXd g_damped = Eigen::VectorXd::Zero(p.q.size()), g_plain = g_damped;
  p.body->add_forces(p.q, p.qd, 0.0, g_damped);
  const double dissipated = p.body->dissipation_power(p.q, p.qd);
  p.body->set_bond_damping(0.0);
  p.body->set_global_damping(0.0);
  p.body->add_forces(p.q, p.qd, 0.0, g_plain);
  EXPECT_EQ(p.body->dissipation_power(p.q, p.qd), 0.0);
  const double power = (g_damped - g_plain).dot(p.qd);
  EXPECT_GT(dissipated, 0.0);
  EXPECT_NEAR(-power / dissipated, 1.0, 1e-9);
}

TEST(PdElasticity, BondForcesAreTheGradientOfTheStrainEnergy) {
  // central differences of potential_energy against add_forces on a few coordinates;
  // 1e-5 relative: the O(h^2) error of the difference
  Perturbed p = perturbed_plate(0.0, 0.0);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(p.q.size());
  p.body->add_forces(p.q, Eigen::VectorXd::Zero(p.q.size()), 0.0, g);
  const double h = 1e-9;
  for (int k : {0, 1, 501, 1200, static_cast<int>(p.q.size()) - 1}) {
    Eigen::VectorXd qp = p.q, qm = p.q;
    qp[k] += h;
    qm[k] -= h;
    const double numeric = -(p.body->potential_energy(qp) - p.body->potential_energy(qm)) / (2 * h);
    EXPECT_NEAR(numeric / g[k], 1.0, 1e-5) << k;
  }
}

}  // namespace
}  // namespace periflex

namespace periflex {
namespace {

TEST(PdDamage, BreaksTheSameBondsWithOrWithoutTheForcePassesStretchMaxima) {
  // update_fracture reuses the stretch maxima of a force evaluation at the same positions;
  // the bonds it breaks must be exactly those a fresh stretch pass finds
  FlexBodyDef def = test::glass_plate(0.03, 0.02, 5e-4);
  def.material.critical_stretch = 1e-4;
  auto with_forces = PdBody::build(def, 0), alone = PdBody::build(def, 0);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 4e-8);
  Eigen::VectorXd q = test::affine_positions(*alone, Eigen::Matrix2d::Identity() * 9e-5);
  for (int k = 0; k < q.size(); ++k) q[k] += noise(rng);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(q.size());
  with_forces->add_forces(q, Eigen::VectorXd::Zero(q.size()), 0.0, g);
  const FractureUpdate a = with_forces->update_fracture(q), b = alone->update_fracture(q);
  EXPECT_GT(a.bonds_broken, 0);
  EXPECT_LT(a.bonds_broken, alone->bond_count());
  EXPECT_EQ(a.bonds_broken, b.bonds_broken);
  EXPECT_EQ(a.energy_released, b.energy_released);
  EXPECT_EQ(with_forces->bonds().broken, alone->bonds().broken);
}

}  // namespace
}  // namespace periflex

namespace periflex {
namespace {

TEST(PdMaterial, ConicalInfluenceKeepsTheBulkStiffness) {
  // midpoint quadrature of int_0^delta w(r) r^2 dr against delta^3 / 3 (the constant function's
  // value), which is what the isotropic energy and hence the bulk modulus depend on; 1e-6:
  // quadrature error
  const double delta = 2e-3;
  const int steps = 100000;
  double conical = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double r = (k + 0.5) * delta / steps;
    conical += influence(FlexBodyDef::Influence::kConical, r, delta) * r * r * delta / steps;
  }
  EXPECT_NEAR(conical / (delta * delta * delta / 3.0), 1.0, 1e-6);
  EXPECT_EQ(influence(FlexBodyDef::Influence::kConical, 1.01 * delta, delta), 0.0);
}

TEST(PdGrid, ParticlesInAndNearestParticleSelectByReferencePosition) {
  // a 10 x 6 grid with dx = 1 mm: the box over the right two columns holds 12 particles, all with
  // x > 3 mm; the particle nearest (4.4, -2.4) mm sits at (4.5, -2.5) mm
  auto body = PdBody::build(test::glass_plate(0.01, 0.006, 1e-3), 0);
  const std::vector<int> right = body->particles_in(test::box(0.002, 0.006, Vec2(0.004, 0.0)));
  EXPECT_EQ(right.size(), 12u);
  for (int i : right) EXPECT_GT(body->reference_positions()[2 * i], 0.003);
  const int nearest = body->nearest_particle(Vec2(0.0044, -0.0024));
  EXPECT_NEAR(body->reference_positions()[2 * nearest], 0.0045, 1e-12);
  EXPECT_NEAR(body->reference_positions()[2 * nearest + 1], -0.0025, 1e-12);
}

}  // namespace
}  // namespace periflex
