// Bodies whose particles lie off the grid (a point file of any layout, a jittered body): bonds keep
// their own reference lengths, partial volumes and influence from the positions. Checked against
// the grid body they tend to, against themselves (equal and opposite pairs, no force at rest, the
// vector loops against the portable ones, threads) and against Kirsch's stress concentration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>

#include "core/error.h"
#include "pd/bond_kernel.h"
#include "pd/cloud_grid.h"
#include "pd/pd_body.h"
#include "pd/pd_material.h"
#include "pd/state_based_material.h"
#include "pd_static_support.h"
#include "pd_test_support.h"
#include "scene/dxf_shape.h"

namespace periflex {
namespace {

FlexBodyDef jittered_glass(double jitter) {
  FlexBodyDef def = test::glass_plate(0.03, 0.02, 5e-4);
  def.jitter = jitter;
  return def;
}

// For each stored direction, the index of the same bond stored in its other row.
std::vector<int64_t> reverse_bonds(const BondStore& b) {
  std::vector<int64_t> reverse(b.neighbor.size(), -1);
  for (int i = 0; i < b.particle_count(); ++i)
    for (int64_t k = b.row[i]; k < b.row[i + 1]; ++k) {
      const int j = b.neighbor[k];
      for (int64_t r = b.row[j]; r < b.row[j + 1]; ++r)
        if (b.neighbor[r] == i) reverse[k] = r;
    }
  return reverse;
}

TEST(OffGrid, JitterMovesEveryParticleWithinItsBoundAndRepeats) {
  FlexBodyDef def = jittered_glass(0.3);
  const ParticleGrid grid = body_particles(def), again = body_particles(def);
  def.jitter = 0.0;
  const ParticleGrid plain = body_particles(def);
  ASSERT_EQ(grid.size(), plain.size());
  EXPECT_FALSE(grid.on_grid);
  EXPECT_TRUE(plain.on_grid);
  double largest = 0.0, moved = 0.0;
  for (int i = 0; i < grid.size(); ++i) {
    const double ex = std::abs(grid.x[i] - plain.x[i]), ey = std::abs(grid.y[i] - plain.y[i]);
    largest = std::max({largest, ex, ey});
    moved += ex + ey;
  }
  EXPECT_LE(largest, 0.3 * def.grid_spacing);
  EXPECT_GT(largest, 0.29 * def.grid_spacing);
  // uniform in [-0.3, 0.3] dx: a mean move of 0.15 dx per coordinate
  EXPECT_NEAR(moved / (2 * grid.size()), 0.15 * def.grid_spacing, 0.01 * def.grid_spacing);
  EXPECT_EQ(grid.x, again.x);
  EXPECT_EQ(grid.y, again.y);
}

// Particles moved by a millionth of a spacing hold the grid body's bonds: the same neighbours,
// stiffness and reference lengths to about the move, and the same forces under a strain.
TEST(OffGrid, AJitterOfAlmostNothingGivesTheGridBodysBondsAndForces) {
  auto grid = PdBody::build(jittered_glass(0.0), 0);
  auto moved = PdBody::build(jittered_glass(1e-6), 0);
  const BondStore &a = grid->bonds(), &b = moved->bonds();
  ASSERT_FALSE(a.own_lengths());
  ASSERT_TRUE(b.own_lengths());
  ASSERT_EQ(a.row, b.row);
  ASSERT_EQ(a.neighbor, b.neighbor);
  double worst_k = 0.0, worst_l = 0.0;
  for (int64_t k = 0; k < a.directed_count(); ++k) {
    worst_k = std::max(worst_k, std::abs(double(b.coefficient[k]) / a.coefficient[k] - 1.0));
    worst_l = std::max(worst_l, std::abs(b.inv_length(k) / a.inv_length(k) - 1.0));
  }
  std::printf("moved by 1e-6 dx: stiffness within %.2e, lengths within %.2e\n", worst_k, worst_l);
  EXPECT_LT(worst_k, 2e-5);
  EXPECT_LT(worst_l, 3e-6);
  const Eigen::Matrix2d strain = test::uniaxial(1e-4);
  const Eigen::VectorXd fa = test::forces_at(*grid, test::affine_positions(*grid, strain));
  const Eigen::VectorXd fb = test::forces_at(*moved, test::affine_positions(*moved, strain));
  EXPECT_LT((fa - fb).cwiseAbs().maxCoeff(), 1e-4 * fa.cwiseAbs().maxCoeff());
  std::vector<float> damage;
  moved->damage(damage);
  EXPECT_EQ(*std::max_element(damage.begin(), damage.end()), 0.0f);
}

// Both stored directions of a bond hold the same bits, so a body at rest feels no force at all,
// on every loop width, and under any deformation the forces sum to zero to round-off.
TEST(OffGrid, PairsAreEqualAndOppositeAndTheBodyAtRestFeelsNothing) {
  auto body = PdBody::build(jittered_glass(0.3), 0);
  const BondStore& b = body->bonds();
  const std::vector<int64_t> reverse = reverse_bonds(b);
  for (int64_t k = 0; k < b.directed_count(); ++k) {
    ASSERT_GE(reverse[k], 0);
    ASSERT_EQ(b.coefficient[k], b.coefficient[reverse[k]]);
    ASSERT_EQ(b.inv_length(k), b.inv_length(reverse[k]));
  }
  const Eigen::VectorXd rest = test::reference_q(*body);
  for (VectorKernels width : {VectorKernels::kPortable, VectorKernels::kAvx2, VectorKernels::kAvx512}) {
    set_vector_kernels(width);
    EXPECT_EQ(test::forces_at(*body, rest).cwiseAbs().maxCoeff(), 0.0) << static_cast<int>(width);
  }
  set_vector_kernels(VectorKernels::kAvx512);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 1e-6);
  Eigen::VectorXd q = test::affine_positions(*body, test::uniaxial(1e-4));
  for (int k = 0; k < q.size(); ++k) q[k] += noise(rng);
  const Eigen::VectorXd f = test::forces_at(*body, q);
  const double sx = f(Eigen::seq(0, f.size() - 1, 2)).sum(), sy = f(Eigen::seq(1, f.size() - 1, 2)).sum();
  EXPECT_LT(std::hypot(sx, sy), 1e-12 * f.cwiseAbs().sum());
}

// The AVX2 loops read each bond's own length; they agree with the portable loops to round-off,
// elastic and damped (AVX-512 falls back to AVX2 off the grid).
TEST(OffGrid, VectorAndPortableLoopsAgreeToRoundOff) {
  for (double eta : {0.0, 50.0}) {
    FlexBodyDef def = jittered_glass(0.25);
    def.bond_damping = eta;
    auto body = PdBody::build(def, 0);
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.0, 1e-6);
    Eigen::VectorXd q = test::affine_positions(*body, Eigen::Matrix2d::Identity() * 1e-4), qd(q.size());
    for (int k = 0; k < q.size(); ++k) {
      q[k] += noise(rng);
      qd[k] = noise(rng) * 1e3;
    }
    Eigen::VectorXd g_vec = Eigen::VectorXd::Zero(q.size()), g_port = g_vec;
    set_vector_kernels(VectorKernels::kAvx512);
    body->add_forces(q, qd, 0.0, g_vec);
    set_vector_kernels(VectorKernels::kPortable);
    body->add_forces(q, qd, 0.0, g_port);
    set_vector_kernels(VectorKernels::kAvx512);
    EXPECT_GT(g_port.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LT((g_vec - g_port).cwiseAbs().maxCoeff(), 1e-12 * g_port.cwiseAbs().maxCoeff()) << "eta " << eta;
  }
}

// A jittered plate torn apart by opposite velocities of its halves for 80 steps: both copies of
// every bond break together, and one thread and two give the same bits.
TEST(OffGrid, TearingBreaksBothCopiesAndIsBitIdenticalOnOneAndTwoThreads) {
  FlexBodyDef def = test::glass_plate(0.05, 0.03, 5e-4);
  def.jitter = 0.3;
  std::vector<Eigen::VectorXd> positions;
  std::vector<std::vector<uint8_t>> broken;
  long pairs = 0;
  for (int threads : {1, 2}) {
    const test::TornPlate torn = test::tear_plate(def, threads);
    positions.push_back(torn.q);
    broken.push_back(torn.body->bond_state().broken);
    pairs = torn.body->broken_bond_count();
    const std::vector<int64_t> reverse = reverse_bonds(torn.body->bonds());
    long directed = 0;
    for (size_t k = 0; k < reverse.size(); ++k) {
      directed += broken.back()[k] != 0;
      ASSERT_EQ(broken.back()[k], broken.back()[reverse[k]]);
    }
    EXPECT_EQ(directed, 2 * pairs);
  }
  std::printf("jittered tearing plate: %ld bonds broken\n", pairs);
  EXPECT_GT(pairs, 100);
  EXPECT_EQ(broken[0], broken[1]);
  EXPECT_EQ(positions[0], positions[1]);
}

// A point file of two spacings: dx on the left half of a 40 x 20 dx plate, dx / 2 (a quarter of
// the volume) on the right half, as a mesh refined where a crack will run. The body's spacing
// (which sets the horizon, 3 dx) is dx throughout.
std::shared_ptr<ParticleCloud> graded_cloud(double dx, double thickness) {
  auto cloud = std::make_shared<ParticleCloud>();
  const auto add = [&](double x, double y, double h) {
    cloud->x.push_back(x);
    cloud->y.push_back(y);
    cloud->volume.push_back(h * h * thickness);
    cloud->no_fail.push_back(0);
  };
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) add((i - 19.5) * dx, (j - 9.5) * dx, dx);
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) add((i + 0.5) * 0.5 * dx, (j - 19.5) * 0.5 * dx, 0.5 * dx);
  cloud->source = "points graded.csv";
  return cloud;
}

// The largest departure of the strain energy density from `continuum` under `strain` over the
// interior particles of each half (x < 0, x > 0) of the 40 x 20 mm plate of graded_cloud: those a
// horizon and a spacing from every edge and from the seam.
void interior_error(PdBody& body, const Eigen::Matrix2d& strain, double continuum, double out[2], int counted[2]) {
  std::vector<double> density;
  body.strain_energy_density(test::affine_positions(body, strain), density);
  const std::vector<double>& x = body.reference_positions();
  const double keep = body.horizon() + body.grid_spacing();
  for (int i = 0; i < body.particle_count(); ++i) {
    const double px = x[2 * i], py = x[2 * i + 1];
    if (std::abs(px) < keep || std::abs(px) > 0.02 - keep || std::abs(py) > 0.01 - keep) continue;
    const int half = px > 0.0 ? 1 : 0;
    out[half] = std::max(out[half], std::abs(density[i] / continuum - 1.0));
    ++counted[half];
  }
}

// Under a uniform strain each particle's strain energy density is the sum over its bonds of
// k0 |xi| s^2 / 4 over its own volume, where k0 = c w beta V_i V_j: on unequal volumes the sum
// weighs each neighbour by its own volume. Deep inside either half (beyond a horizon and a
// spacing from every edge and from the seam) it must come to the continuum's
// pi c t delta^3 eps^2 / 16 (uniaxial strain, no surface correction) as closely as the sum on a
// grid does: the coarse half exactly as a plate on the grid of spacing dx (measured 1.9 % off:
// three spacings to the horizon), the fine half (six) no further off. Tolerance 2.5 % for both.
TEST(OffGrid, GradedPointFileKeepsTheContinuumEnergyDensityOnBothSpacings) {
  const double dx = 1e-3, t = 1e-3, eps = 1e-4, delta = 3 * dx;
  const double continuum = uniaxial_strain_energy_density(micromodulus(72e9, t, delta, false), t, delta, eps);
  Eigen::Matrix2d strain = Eigen::Matrix2d::Zero();
  strain(0, 0) = eps;
  FlexBodyDef def = test::glass_plate(0.04, 0.02, dx, t);
  def.surface_correction = false;
  def.fracture = false;
  auto grid = PdBody::build(def, 0);
  def.particles = graded_cloud(dx, t);
  auto graded = PdBody::build(def, 0);
  ASSERT_EQ(graded->particle_count(), 400 + 1600);
  EXPECT_EQ(graded->volumes()[0], dx * dx * t);
  EXPECT_EQ(graded->volumes()[400], 0.25 * dx * dx * t);
  double on_grid[2] = {0.0, 0.0}, worst[2] = {0.0, 0.0};
  int grid_counted[2] = {0, 0}, counted[2] = {0, 0};
  interior_error(*grid, strain, continuum, on_grid, grid_counted);
  interior_error(*graded, strain, continuum, worst, counted);
  std::printf("graded plate: energy density within %.2e (coarse, %d particles) and %.2e (fine, %d) of the "
              "continuum; on the grid %.2e\n", worst[0], counted[0], worst[1], counted[1], on_grid[0]);
  EXPECT_GT(counted[0], 10);
  EXPECT_GT(counted[1], 40);
  EXPECT_NEAR(worst[0], on_grid[0], 1e-9);
  EXPECT_LE(worst[1], worst[0]);
  EXPECT_LT(worst[0], 0.025);
  EXPECT_LT(worst[1], 0.025);
}

// A body force on unequal volumes acts on each particle in proportion to its volume: the total
// is the force density times the plate's volume (0.04 x 0.02 x 1 mm), the coarse half's
// particles each take four times a fine one's.
TEST(OffGrid, BodyForceOnAGradedPointFileFollowsEachVolume) {
  const double dx = 1e-3, t = 1e-3, b = 2e6;
  FlexBodyDef def = test::glass_plate(0.04, 0.02, dx, t);
  def.particles = graded_cloud(dx, t);
  RegionLoadDef load;
  load.kind = RegionLoadDef::Kind::kBodyForce;
  load.name = "weight";
  load.region = test::box(1.0, 1.0);
  load.fy = TimeFunction::constant(-b);
  def.loads.push_back(load);
  auto body = PdBody::build(def, 0);
  const Eigen::VectorXd f = test::forces_at(*body, test::reference_q(*body));
  EXPECT_NEAR(f(Eigen::seq(1, f.size() - 1, 2)).sum(), -b * 0.04 * 0.02 * t, 1e-12 * b * 0.04 * 0.02 * t);
  EXPECT_DOUBLE_EQ(f[1], 4.0 * f[2 * 400 + 1]);
}

// The state-based law on the graded plate under a uniform uniaxial strain eps: deep inside either
// half (as in the bond-based test above) each particle's strain energy density comes to the
// continuum's kappa eps^2 / 2 + mu eps^2 / 2 (2D moduli of E = 72 GPa, nu = 0.22, plane stress;
// no surface correction): on the coarse half exactly as on the grid plate of spacing dx, on the
// fine half within the same 2.5 %. The plate's strain energy, sum V_i W_i, is the grid plate's
// within 2 % (the two differ only in the fine half's free edges); a fine particle counted with the
// cell's volume would make it 2.5 times as large.
TEST(OffGrid, StateBasedGradedPointFileKeepsTheContinuumEnergyDensityOnBothSpacings) {
  const double dx = 1e-3, t = 1e-3, eps = 1e-4, nu = 0.22;
  const double continuum = 0.5 * (lps_bulk_modulus(72e9, nu, false) + lps_shear_modulus(72e9, nu)) * eps * eps;
  Eigen::Matrix2d strain = Eigen::Matrix2d::Zero();
  strain(0, 0) = eps;
  FlexBodyDef def = test::glass_plate(0.04, 0.02, dx, t);
  def.material.model = PdMaterialDef::Model::kStateBased;
  def.material.poisson_ratio = nu;
  def.surface_correction = false;
  def.fracture = false;
  auto grid = PdBody::build(def, 0);
  def.particles = graded_cloud(dx, t);
  auto graded = PdBody::build(def, 0);
  double on_grid[2] = {0.0, 0.0}, worst[2] = {0.0, 0.0};
  int grid_counted[2] = {0, 0}, counted[2] = {0, 0};
  interior_error(*grid, strain, continuum, on_grid, grid_counted);
  interior_error(*graded, strain, continuum, worst, counted);
  std::printf("graded state-based plate: energy density within %.2e (coarse, %d particles) and %.2e (fine, %d) of "
              "the continuum; on the grid %.2e\n", worst[0], counted[0], worst[1], counted[1], on_grid[0]);
  EXPECT_GT(counted[0], 10);
  EXPECT_GT(counted[1], 40);
  EXPECT_NEAR(worst[0], on_grid[0], 1e-9);
  EXPECT_LT(worst[0], 0.025);
  EXPECT_LT(worst[1], 0.025);
  const double total = graded->potential_energy(test::affine_positions(*graded, strain));
  const double total_grid = grid->potential_energy(test::affine_positions(*grid, strain));
  std::printf("strain energy: graded %.6e J, grid %.6e J, continuum %.6e J\n", total, total_grid,
              continuum * 0.04 * 0.02 * t);
  EXPECT_NEAR(total / total_grid, 1.0, 0.02);
}

// The state-based law on a graded point file weighs each neighbour by its own volume (bond
// weights w beta V_i V_j / V^2, the pair force V_i V_j w beta (...)). Its forces are the
// derivative of its strain energy sum V_i W_i: at a deformed state (a uniaxial strain of 1e-4 and
// random moves of 1e-3 spacings), central differences of the energy (step 1e-9 m) give each
// force within 1e-6 of the largest, on the coordinates either side of the seam and far from it,
// with and without the surface correction; the forces of all particles sum to zero.
TEST(OffGrid, StateBasedForcesOnAGradedPointFileAreTheDerivativeOfItsEnergy) {
  const double dx = 1e-3, t = 1e-3;
  for (const bool surface : {false, true}) {
    FlexBodyDef def = test::glass_plate(0.04, 0.02, dx, t);
    def.particles = graded_cloud(dx, t);
    def.material.model = PdMaterialDef::Model::kStateBased;
    def.material.poisson_ratio = 0.22;
    def.surface_correction = surface;
    def.fracture = false;
    auto body = PdBody::build(def, 0);
    Eigen::Matrix2d strain = Eigen::Matrix2d::Zero();
    strain(0, 0) = 1e-4;
    Eigen::VectorXd q = test::affine_positions(*body, strain);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> move(-1e-3 * dx, 1e-3 * dx);
    for (int k = 0; k < q.size(); ++k) q[k] += move(random);
    const Eigen::VectorXd f = test::forces_at(*body, q);
    EXPECT_LT(std::abs(f(Eigen::seq(0, f.size() - 1, 2)).sum()), 1e-9 * f.cwiseAbs().maxCoeff());
    EXPECT_LT(std::abs(f(Eigen::seq(1, f.size() - 1, 2)).sum()), 1e-9 * f.cwiseAbs().maxCoeff());
    double worst = 0.0;
    int checked = 0;
    for (int i = 0; i < body->particle_count(); i += 23) {
      for (int c = 0; c < 2; ++c) {
        const double h = 1e-9;
        Eigen::VectorXd plus = q, minus = q;
        plus[2 * i + c] += h;
        minus[2 * i + c] -= h;
        const double derivative = -(body->potential_energy(plus) - body->potential_energy(minus)) / (2 * h);
        worst = std::max(worst, std::abs(derivative - f[2 * i + c]));
        ++checked;
      }
    }
    std::printf("graded state-based plate (surface correction %s): forces within %.2e of the largest from the "
                "energy's derivative (%d coordinates)\n", surface ? "on" : "off", worst / f.cwiseAbs().maxCoeff(), checked);
    EXPECT_LT(worst, 1e-6 * f.cwiseAbs().maxCoeff());
  }
}

// An 80 x 60 mm outline with a hole of radius 5 mm, as a CAD program writes it (millimetres).
std::string kirsch_dxf() {
  const auto dir = std::filesystem::temp_directory_path() / "periflex_off_grid_kirsch";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "kirsch.dxf").string();
  std::ofstream out(path);
  out << "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\noutline\n90\n4\n70\n1\n"
      << "10\n-40.0\n20\n-30.0\n10\n40.0\n20\n-30.0\n10\n40.0\n20\n30.0\n10\n-40.0\n20\n30.0\n"
      << "0\nCIRCLE\n8\noutline\n10\n0.0\n20\n0.0\n40\n5.0\n0\nENDSEC\n0\nEOF\n";
  return path;
}

// Kirsch on an irregular point set: the plate of PdStateBased.PlateWithAHoleShowsTheKirschStress-
// Concentration (steel, plane stress, nu = 0.3, state-based with the surface correction, 1 mm
// spacing, hole radius 5 spacings) drawn as a DXF outline and each particle moved by up to a
// quarter spacing. The end columns (their particles within 0.6 spacings of the outermost one)
// are pulled apart, the particle nearest the middle of each end held in y (the jittered rows give
// the end forces a small moment); the concentration E eps / sigma follows from the rim displacements. On the
// grid it measures 3.015; the tolerance is the grid case's 5 % (finite width +3 % by Heywood's
// formula, the rim taken between a and a + dx, a horizon of 3 spacings smoothing the peak).
TEST(OffGrid, KirschPlateFromADxfOutlineOnAJitteredSet) {
  test::SerialScope serial;
  DxfShapeOptions options;
  options.layer = "outline";
  options.scale = 1e-3;
  const DxfOutline outline = read_dxf_shape(kirsch_dxf(), options);
  ASSERT_EQ(outline.material.size(), 1u);
  ASSERT_EQ(outline.holes.size(), 1u);
  const double dx = 1e-3, height = 0.06, radius = 0.005, e = 200e9;
  FlexBodyDef def;
  def.name = "kirsch";
  def.shape.kind = ShapeDef::Kind::kPolygon;
  def.shape.vertices = outline.material.front();
  ShapeDef hole;
  hole.kind = ShapeDef::Kind::kPolygon;
  hole.vertices = outline.holes.front();
  def.holes.push_back(hole);
  def.grid_spacing = dx;
  def.thickness = 1e-3;
  def.fracture = false;
  def.material.youngs_modulus = e;
  def.material.density = 7850.0;
  def.material.model = PdMaterialDef::Model::kStateBased;
  def.material.poisson_ratio = 0.3;
  def.jitter = 0.25;
  auto body = PdBody::build(def, 0);
  ASSERT_TRUE(body->bonds().own_lengths());
  const std::vector<double>& x = body->reference_positions();
  const int n = body->particle_count();
  double x_max = -1.0, x_min = 1.0;
  for (int i = 0; i < n; ++i) {
    x_max = std::max(x_max, x[2 * i]);
    x_min = std::min(x_min, x[2 * i]);
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * n);
  int right = 0, left = 0;
  const double per_particle = 1e3;
  for (int i = 0; i < n; ++i) {
    if (x[2 * i] > x_max - 0.6 * dx) {
      f[2 * i] = per_particle;
      ++right;
    }
    if (x[2 * i] < x_min + 0.6 * dx) {
      f[2 * i] = -per_particle;
      ++left;
    }
  }
  ASSERT_EQ(right, 60);  // one whole column each (60 rows)
  ASSERT_EQ(left, 60);
  const double sigma = per_particle * right / (height * def.thickness);
  // the jittered columns' forces have a small net moment: the particles nearest the middle of each
  // end are held in y, whose reactions take it
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(2 * n);
  int left_middle = 0, right_middle = 0;
  for (int i = 0; i < n; ++i) {
    if (std::hypot(x[2 * i] - x_min, x[2 * i + 1]) < std::hypot(x[2 * left_middle] - x_min, x[2 * left_middle + 1]))
      left_middle = i;
    if (std::hypot(x[2 * i] - x_max, x[2 * i + 1]) < std::hypot(x[2 * right_middle] - x_max, x[2 * right_middle + 1]))
      right_middle = i;
  }
  fixed[2 * left_middle + 1] = fixed[2 * right_middle + 1] = 1.0;
  const Eigen::VectorXd u = test::static_solution(*body, f, fixed);
  std::vector<int> rim;
  for (int i = 0; i < n; ++i)
    if (std::hypot(x[2 * i], x[2 * i + 1]) < radius + dx) rim.push_back(i);
  ASSERT_GE(rim.size(), 20u);
  const double concentration = e * test::rim_hoop_strain(x, rim, u, radius) / sigma;
  std::printf("Kirsch plate from a DXF outline, jittered by 0.25 dx: concentration %.3f (%zu rim particles)\n",
              concentration, rim.size());
  RecordProperty("kirsch_concentration_jittered", std::to_string(concentration));
  EXPECT_NEAR(concentration, 3.0, 0.15);
}

}  // namespace
}  // namespace periflex
