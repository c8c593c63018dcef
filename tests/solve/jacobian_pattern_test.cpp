// The structure of d qdd / d(q, qd) taken from the model (solve/jacobian_pattern.cpp) against
// the one perturbation finds, and what it buys the HHT integrator: a first step whose force
// evaluations do not grow with the particles, a set-up linear in them, and the same results as
// with the pattern found by perturbing every coordinate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/cpu_time.h"
#include "core/sparsity_pattern.h"
#include "model/system_model.h"
#include "scene/scene_loader.h"
#include "solve/dynamics.h"
#include "solve/integrator_hht.h"

namespace periflex {
namespace {

const std::string kScenes = std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/";

// A shipped scene's model and its equations of motion at a consistent start.
struct Model {
  std::unique_ptr<SystemModel> model;
  std::unique_ptr<Dynamics> dynamics;
  OdeState state;
};

Model build(const std::string& scene_file, const std::vector<std::string>& overrides) {
  const SceneDef scene = load_scene(kScenes + scene_file, overrides);
  Model m;
  m.model = build_system_model(scene);
  m.dynamics = std::make_unique<Dynamics>(*m.model);
  m.dynamics->set_correction(scene.solver.correction);
  m.dynamics->analyse(0.0);
  m.state.q = m.model->q0;
  m.state.qd = m.model->qd0;
  m.dynamics->project_positions(0.0, m.state.q, 1e-12, 20);
  m.dynamics->project_velocities(0.0, m.state.q, m.state.qd);
  return m;
}

// The equations of motion as a system that cannot give its pattern: the integrator then
// perturbs every coordinate (what it did for every system before the model gave the pattern).
// Counts the evaluations either way.
class Counted final : public OdeSystem {
 public:
  Counted(Dynamics& inner, bool pattern) : inner_(inner), pattern_(pattern) {}
  void derivative(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& qdd,
                  Eigen::Vector3d& power) override {
    ++evaluations;
    inner_.derivative(t, q, qd, qdd, power);
  }
  bool jacobian_pattern(double t, const Eigen::VectorXd& q, SparsityPattern& pattern) override {
    return pattern_ && inner_.jacobian_pattern(t, q, pattern);
  }
  long evaluations = 0;

 private:
  Dynamics& inner_;
  bool pattern_;
};

// The pattern perturbation finds at the state: rows whose acceleration changes when one
// coordinate and its rate move, diagonal included. A change counts above round-off (1e-12 of
// the largest acceleration): the constraint solve passes a change of the forces on a gripped
// particle to the grips' accelerations in the last bit, though the drivers alone set them.
SparsityPattern perturbed_pattern(Dynamics& dynamics, const OdeState& s) {
  const int n = static_cast<int>(s.q.size());
  Eigen::VectorXd f0, f, q, qd;
  Eigen::Vector3d power;
  dynamics.derivative(0.0, s.q, s.qd, f0, power);
  SparsityPattern pattern;
  pattern.reset(n);
  const double scale = std::max(s.q.lpNorm<Eigen::Infinity>(), 1e-6);
  const double noise = 1e-12 * std::max(f0.lpNorm<Eigen::Infinity>(), 1.0);
  for (int j = 0; j < n; ++j) {
    q = s.q;
    qd = s.qd;
    const double eps = 1.5e-8 * std::max(std::abs(s.q[j]), scale);
    q[j] += eps;
    qd[j] += eps;
    dynamics.derivative(0.0, q, qd, f, power);
    for (int i = 0; i < n; ++i)
      if (std::abs(f[i] - f0[i]) > noise) pattern.add(i, j);
  }
  pattern.finish();
  return pattern;
}

// Entries of `found` that `model` lacks.
long missing_entries(const SparsityPattern& model, const SparsityPattern& found) {
  long missing = 0;
  for (int j = 0; j < found.size(); ++j) {
    const auto first = model.rows().begin() + model.start()[j], last = model.rows().begin() + model.start()[j + 1];
    for (int k = found.start()[j]; k < found.start()[j + 1]; ++k)
      if (!std::binary_search(first, last, found.rows()[k])) ++missing;
  }
  return missing;
}

// Scenes of the three kinds of constrained groups: grips turned by drivers (determined by the
// constraints alone), a flexible rod in a mechanism with a degree of freedom (the forces enter
// the constraint solve), and state-based plates (couplings two bonds deep); and the contacts: the
// hammer's beam resting on its rollers at the start (rigid bodies against particles, and rigid
// bodies against each other), its particles against each other.
struct PatternCase {
  const char* name;
  const char* scene;
  std::vector<std::string> overrides;
};

class ModelPattern : public ::testing::TestWithParam<PatternCase> {};

TEST_P(ModelPattern, HoldsEveryEntryPerturbationFindsWithNoMoreColours) {
  Model m = build(GetParam().scene, GetParam().overrides);
  SparsityPattern model;
  ASSERT_TRUE(m.dynamics->jacobian_pattern(0.0, m.state.q, model));
  const SparsityPattern found = perturbed_pattern(*m.dynamics, m.state);
  EXPECT_EQ(missing_entries(model, found), 0) << "of " << found.nonzeros();
  // a superset that is not much larger: the columns need about as many colours (evaluations)
  const size_t model_colours = colour_columns(model).size(), found_colours = colour_columns(found).size();
  EXPECT_LE(model_colours, found_colours + found_colours / 10) << model.nonzeros() << " against " << found.nonzeros();
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, ModelPattern,
    ::testing::Values(PatternCase{"DrivenGrips", "notched_plate.toml", {"flex_body.plate.grid_spacing=2e-3"}},
                      PatternCase{"FlexibleRodInAMechanism", "flexible_slider_crank.toml", {}},
                      PatternCase{"StateBasedPlates", "notched_plate_models.toml", {}},
                      PatternCase{"Contacts", "hammer.toml", {}}),
    [](const ::testing::TestParamInfo<PatternCase>& param) { return std::string(param.param.name); });

// Force evaluations of the first HHT step of the notched plate at spacing dx.
long first_step_evaluations(double dx, bool pattern, int* coordinates) {
  Model m = build("notched_plate.toml", {"flex_body.plate.grid_spacing=" + std::to_string(dx)});
  Counted system(*m.dynamics, pattern);
  auto hht = make_hht(kDefaultHhtAlpha);
  hht->step(system, 0.0, 4e-6, m.state);
  *coordinates = static_cast<int>(m.state.q.size());
  return system.evaluations;
}

TEST(JacobianPattern, FirstHhtStepEvaluationsDoNotGrowWithTheParticles) {
  // twice the particles: the same number of evaluations (colours, Newton iterations), each
  // linear in the particles, so the step's set-up is linear too; one evaluation per coordinate
  // to find the pattern would double them
  int n1 = 0, n2 = 0;
  const long e1 = first_step_evaluations(2e-3, true, &n1);
  const long e2 = first_step_evaluations(2e-3 / std::sqrt(2.0), true, &n2);
  ASSERT_GT(n2, 19 * n1 / 10);
  EXPECT_LT(e1, n1 / 4);
  EXPECT_LT(e2, e1 + e1 / 4) << e1 << " evaluations at " << n1 << " coordinates";
}

TEST(JacobianPattern, SetUpTimeIsLinearInTheParticles) {
  // pattern and colouring of the notched plate at 4000 and 8000 particles, best of seven taken
  // in turns (a loaded machine only adds time, and the two sizes see the same load):
  // quadratic growth would take four times as long
  Model small_model = build("notched_plate.toml", {"flex_body.plate.grid_spacing=" + std::to_string(1e-3)});
  Model large_model =
      build("notched_plate.toml", {"flex_body.plate.grid_spacing=" + std::to_string(1e-3 / std::sqrt(2.0))});
  SparsityPattern pattern;
  auto set_up = [&pattern](Model& m) {
    const double start = thread_cpu_seconds();
    m.dynamics->jacobian_pattern(0.0, m.state.q, pattern);
    const auto colours = colour_columns(pattern);
    EXPECT_GT(colours.size(), 0u);
    return thread_cpu_seconds() - start;
  };
  double small = std::numeric_limits<double>::infinity(), large = small;
  for (int k = 0; k < 7; ++k) {
    small = std::min(small, set_up(small_model));
    large = std::min(large, set_up(large_model));
  }
  EXPECT_LT(large, 3.0 * small) << small << " s against " << large << " s";
}

TEST(JacobianPattern, HhtStepsEqualThoseWithThePerturbedPattern) {
  // three steps of the notched plate with either pattern: the colours group the columns
  // differently, so the finite differences, and through them the Newton iterates, differ in
  // the last bits only
  Model a = build("notched_plate.toml", {"flex_body.plate.grid_spacing=2e-3"});
  Model b = build("notched_plate.toml", {"flex_body.plate.grid_spacing=2e-3"});
  Counted with_model(*a.dynamics, true), perturbed(*b.dynamics, false);
  auto hht_a = make_hht(kDefaultHhtAlpha), hht_b = make_hht(kDefaultHhtAlpha);
  const double h = 4e-6;
  for (int k = 0; k < 3; ++k) {
    hht_a->step(with_model, k * h, h, a.state);
    hht_b->step(perturbed, k * h, h, b.state);
  }
  // positions against the plate's size, velocities against the fastest particle
  const double size = a.state.q.lpNorm<Eigen::Infinity>(), speed = a.state.qd.lpNorm<Eigen::Infinity>();
  EXPECT_LT((a.state.q - b.state.q).lpNorm<Eigen::Infinity>(), 1e-13 * size);
  EXPECT_LT((a.state.qd - b.state.qd).lpNorm<Eigen::Infinity>(), 1e-13 * speed);
  EXPECT_LT(with_model.evaluations, perturbed.evaluations / 4);
}

// The structure that lets HHT factorise the free particles' block alone, by Cholesky
// (iteration_matrix_factors.h): on the notched plate no row of a gripped particle or a grip
// reads a free coordinate, and the free coordinates are the plate's particles off the grips.
TEST(JacobianPattern, DrivenGripsReadNoFreeCoordinate) {
  Model m = build("notched_plate.toml", {"flex_body.plate.grid_spacing=2e-3"});
  SparsityPattern pattern;
  ASSERT_TRUE(m.dynamics->jacobian_pattern(0.0, m.state.q, pattern));
  Eigen::VectorXd mass;
  m.dynamics->free_masses(mass);
  ASSERT_EQ(mass.size(), m.state.q.size());
  const int n = static_cast<int>(mass.size());
  const int free = static_cast<int>((mass.array() > 0.0).count());
  EXPECT_EQ(free, n - m.dynamics->constrained_coordinates());
  EXPECT_GT(free, n / 2);
  int read = 0;
  for (int j = 0; j < n; ++j) {
    if (mass[j] <= 0.0) continue;
    for (int k = pattern.start()[j]; k < pattern.start()[j + 1]; ++k) read += mass[pattern.rows()[k]] <= 0.0;
  }
  EXPECT_EQ(read, 0);
}

// The equations of motion without their free masses: HHT then factorises S whole by LU.
class WithoutMasses final : public OdeSystem {
 public:
  explicit WithoutMasses(Dynamics& inner) : inner_(inner) {}
  void derivative(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& qdd,
                  Eigen::Vector3d& power) override {
    inner_.derivative(t, q, qd, qdd, power);
  }
  bool jacobian_pattern(double t, const Eigen::VectorXd& q, SparsityPattern& pattern) override {
    return inner_.jacobian_pattern(t, q, pattern);
  }

 private:
  Dynamics& inner_;
};

TEST(JacobianPattern, HhtStepsWithTheFreeBlockByCholeskyEqualThoseByLu) {
  // the two factorisations solve the same Newton systems (the Cholesky's averaged within
  // finite-difference noise), so the converged steps agree well within the Newton tolerance
  // (1e-10 of the configuration's size): measured 3e-16 of the size in position, 1.5e-12 of
  // the fastest particle's speed in velocity
  Model a = build("notched_plate.toml", {"flex_body.plate.grid_spacing=2e-3"});
  Model b = build("notched_plate.toml", {"flex_body.plate.grid_spacing=2e-3"});
  WithoutMasses whole(*b.dynamics);
  auto hht_a = make_hht(kDefaultHhtAlpha), hht_b = make_hht(kDefaultHhtAlpha);
  const double h = 4e-6;
  for (int k = 0; k < 5; ++k) {
    hht_a->step(*a.dynamics, k * h, h, a.state);
    hht_b->step(whole, k * h, h, b.state);
  }
  const double size = a.state.q.lpNorm<Eigen::Infinity>(), speed = a.state.qd.lpNorm<Eigen::Infinity>();
  EXPECT_LT((a.state.q - b.state.q).lpNorm<Eigen::Infinity>(), 1e-13 * size);
  EXPECT_LT((a.state.qd - b.state.qd).lpNorm<Eigen::Infinity>(), 1e-10 * speed);
}

}  // namespace
}  // namespace periflex
