// Contact within one body acts only between particles no intact bond joins: squeezing an intact
// plate brings no contact at all, while the faces of a crack through it (cut by a notch) repel
// pair by pair as soon as they come closer than the contact distance, each pair pushed apart.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/particle_contact.h"
#include "model/system_model.h"
#include "scene/scene_loader.h"

namespace periflex {
namespace {

// A 10 x 10 mm plate (dx = 1 mm: 10 x 10 particles) with particle contact on itself, and a
// notch through it along x = 0 when `cracked`; its particles jittered by `jitter` spacings.
std::unique_ptr<SystemModel> plate(bool cracked, double jitter = 0.0) {
  std::string text = R"([scene]
name = "plate"
gravity = [0, 0]
[solver]
dt = 1e-7
end_time = 1e-6
[[flex_body]]
name = "plate"
shape = { type = "box", width = 0.01, height = 0.01 }
grid_spacing = 0.001
fracture = false
)";
  if (cracked) text += "notches = [{ p1 = [0, -0.01], p2 = [0, 0.01] }]\n";
  if (jitter > 0.0) text += "jitter = " + std::to_string(jitter) + "\n";
  text += R"([flex_body.material]
youngs_modulus = 1e9
density = 1000
[[contact]]
name = "faces"
type = "particles"
flex_bodies = ["plate"]
)";
  return build_system_model(parse_scene(text, "plate.toml"));
}

// The configuration squeezed to 85% of its size about the origin (every neighbour at 0.85 dx).
Eigen::VectorXd squeezed(const SystemModel& model) { return 0.85 * model.q0; }

TEST(SelfContact, IntactPlateFeelsNoContactHoweverSqueezed) {
  const auto model = plate(false);
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(model->coordinate_count);
  ContactElement& contact = *model->contacts.at(0);
  EXPECT_EQ(contact.totals(model->q0, rest).active, 0);
  EXPECT_EQ(contact.totals(squeezed(*model), rest).active, 0);
}

TEST(SelfContact, CrackFacesRepelPairByPairOnceCloserThanTheContactDistance) {
  const auto model = plate(true);
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(model->coordinate_count);
  ContactElement& contact = *model->contacts.at(0);
  // one spacing apart at rest: no contact (0.9 dx)
  EXPECT_EQ(contact.totals(model->q0, rest).active, 0);
  // squeezed: the ten pairs facing each other across the crack, and only they
  const Eigen::VectorXd q = squeezed(*model);
  EXPECT_EQ(contact.totals(q, rest).active, 10);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(model->coordinate_count);
  contact.add_forces(q, rest, 0.0, g);
  double net = 0.0;
  for (int c = 0; c < model->coordinate_count; c += 2) {
    const double x = model->q0[c];
    // a particle of a face is pushed away from the crack; every other one feels nothing
    if (std::abs(x) < 0.001) {
      EXPECT_GT(g[c] * x, 0.0) << "particle at x = " << x;
    } else {
      EXPECT_EQ(g[c], 0.0);
    }
    EXPECT_EQ(g[c + 1], 0.0);
    net += g[c];
  }
  EXPECT_NEAR(net, 0.0, 1e-9 * g.cwiseAbs().maxCoeff());
}

// Off the grid the crack's faces may start closer than the contact distance (0.9 dx): a pair's
// distance is then at most 0.9 times its reference distance, so the faces at rest feel nothing,
// and squeezed they repel.
TEST(SelfContact, JitteredCrackFacesFeelNothingAtRestAndRepelSqueezed) {
  const auto model = plate(true, 0.4);
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(model->coordinate_count);
  ContactElement& contact = *model->contacts.at(0);
  // some pair across the notch starts closer than 0.9 dx
  const Eigen::VectorXd& x = model->q0;  // the plate's particles only
  double closest = 1.0;
  for (int i = 0; i < x.size(); i += 2)
    for (int j = 0; j < x.size(); j += 2)
      if (x[i] < 0.0 && x[j] > 0.0) closest = std::min(closest, std::hypot(x[j] - x[i], x[j + 1] - x[i + 1]));
  ASSERT_LT(closest, 0.9e-3);
  EXPECT_EQ(contact.totals(model->q0, rest).active, 0);
  EXPECT_GT(contact.totals(squeezed(*model), rest).active, 0);
}

TEST(SelfContact, BondsCutAfterTheSearchMakeContactPairsWithoutANewSearch) {
  // the intact plate squeezed: its Verlet list is searched once and holds the bonded pairs too
  const auto model = plate(false);
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(model->coordinate_count);
  const auto& contact = dynamic_cast<ParticleContact&>(*model->contacts.at(0));
  const Eigen::VectorXd q = squeezed(*model);
  EXPECT_EQ(model->contacts.at(0)->totals(q, rest).active, 0);
  EXPECT_EQ(contact.rebuilds(), 1);
  // a knife along x = 0 breaks the bonds across it: at the next sum the ten pairs facing each
  // other across the cut repel, from the same list (no particle has moved)
  const FractureUpdate cut = model->flex_bodies.at(0)->cut_bonds(q, {}, Vec2(0.0, -0.01), Vec2(0.0, 0.01));
  EXPECT_GT(cut.bonds_broken, 0);
  EXPECT_EQ(model->contacts.at(0)->totals(q, rest).active, 10);
  EXPECT_EQ(contact.rebuilds(), 1);
}

}  // namespace
}  // namespace periflex
