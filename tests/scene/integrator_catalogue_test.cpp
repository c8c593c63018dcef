// The integrator catalogue against its readers: the scene reader's names, the factory, the
// studies' orders and the scene budget's bytes all come from its rows.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "scene/integrator_catalogue.h"
#include "scene/scene_budget.h"
#include "scene/scene_loader.h"
#include "solve/integrator.h"
#include "study/study_def.h"

namespace periflex {
namespace {

TEST(IntegratorCatalogue, NamesAreUniqueAndFoundAgainByNameAndKind) {
  std::set<std::string> names;
  for (const IntegratorTraits& row : integrator_catalogue()) {
    EXPECT_TRUE(names.insert(row.name).second) << row.name;
    EXPECT_EQ(find_integrator(row.name), &row);
    EXPECT_EQ(&integrator_traits(row.kind), &row);
    EXPECT_GT(row.order, 0) << row.name;
  }
  EXPECT_EQ(find_integrator("generalized_alpha"), nullptr);
  EXPECT_EQ(find_integrator(""), nullptr);
  EXPECT_EQ(find_integrator("Verlet"), nullptr);
}

TEST(IntegratorCatalogue, SceneFilesAcceptExactlyItsNames) {
  EXPECT_EQ(scene_integrator_names(), integrator_names());
  // a scene naming one outside it is refused with the choices
  try {
    parse_scene("[solver]\nintegrator = \"leapfrog\"\n", "leapfrog.toml");
    FAIL() << "a scene with an unknown integrator loaded";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("solver.integrator"), std::string::npos) << text;
    for (const std::string& name : integrator_names()) EXPECT_NE(text.find(name), std::string::npos) << text;
  }
}

TEST(IntegratorCatalogue, FactoryBuildsEachRowWithItsTraits) {
  SolverDef solver;
  for (const IntegratorTraits& row : integrator_catalogue()) {
    const auto integrator = make_integrator(row.name, solver);
    ASSERT_NE(integrator, nullptr) << row.name;
    EXPECT_EQ(&integrator->traits(), &row);
    EXPECT_EQ(integrator->name(), row.name);
    EXPECT_EQ(integrator->order(), row.order);
    EXPECT_EQ(integrator->is_adaptive(), row.is_adaptive);
    // what its cache holds: velocity Verlet keeps the acceleration at the end of a step
    IntegratorCache cache;
    integrator->save_cache(cache);
    EXPECT_EQ(cache.name, row.name);
  }
  EXPECT_THROW(make_integrator("leapfrog", solver), InputError);
}

TEST(IntegratorCatalogue, StudiesAndBudgetReadItsRows) {
  for (const IntegratorTraits& row : integrator_catalogue()) {
    EXPECT_EQ(theoretical_order(row.name), row.order) << row.name;
    EXPECT_EQ(is_adaptive_integrator(row.name), row.is_adaptive) << row.name;
    EXPECT_EQ(integrator_bytes_per_particle(row.name), row.stage_bytes_per_particle) << row.name;
    EXPECT_EQ(integrator_bytes_per_neighbor(row.name), row.tangent_bytes_per_neighbor) << row.name;
  }
  EXPECT_EQ(theoretical_order("leapfrog"), 0);
  EXPECT_FALSE(is_adaptive_integrator("leapfrog"));
}

// the traits the stepper reads in place of names: bonds break in the evaluation for the
// integrators that evaluate only at accepted positions, and only velocity Verlet closes its step
// with a half-kick and keeps the acceleration
TEST(IntegratorCatalogue, StepperTraitsOfTheShippedIntegrators) {
  EXPECT_TRUE(find_integrator("verlet")->breaks_in_evaluation);
  EXPECT_TRUE(find_integrator("symplectic_euler")->breaks_in_evaluation);
  EXPECT_FALSE(find_integrator("rk4")->breaks_in_evaluation);
  EXPECT_FALSE(find_integrator("hht")->is_explicit);
  int kicks = 0, caches = 0;
  for (const IntegratorTraits& row : integrator_catalogue()) {
    kicks += row.closing_kick != 0.0;
    caches += row.keeps_end_acceleration;
  }
  EXPECT_EQ(kicks, 1);
  EXPECT_EQ(caches, 1);
  EXPECT_EQ(find_integrator("verlet")->closing_kick, 0.5);
}

}  // namespace
}  // namespace periflex
