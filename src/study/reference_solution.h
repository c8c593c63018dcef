// Exact answers the work-precision studies measure errors against.
//
//   auto ref = make_reference_solution("pendulum_exact", scene);
//   std::vector<double> p = ref->probe_values(t);   // [x0, y0, x1, y1, ...] in scene.probes order
//
// Each reference reads the geometry, masses and drivers from the scene itself, so a study and its
// scene cannot drift apart; a scene of the wrong shape is refused with an InputError.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene/scene_def.h"

namespace periflex {

class ReferenceSolution {
 public:
  virtual ~ReferenceSolution() = default;
  // Global positions of every probe of the scene at time t, interleaved x, y, in scene order.
  virtual std::vector<double> probe_values(double t) const = 0;
  // One line saying what the reference is, for reports.
  virtual std::string describe() const = 0;
};

// Names of the exact references: "pendulum_exact", "slider_crank_exact".
const std::vector<std::string>& exact_reference_names();

// Builds the named exact reference for the scene. Throws InputError when the name is unknown or
// the scene is not of the kind the reference describes.
std::unique_ptr<ReferenceSolution> make_reference_solution(const std::string& name, const SceneDef& scene);

// The large-amplitude compound pendulum: one rigid body pinned to the ground by a revolute joint,
// released from rest; theta(t) = 2 asin(k cd(omega0 t | k^2)), k = sin(theta0 / 2),
// omega0^2 = m g d / (I + m d^2).
std::unique_ptr<ReferenceSolution> make_pendulum_exact(const SceneDef& scene);

// The driven slider-crank: crank pinned to the ground and driven by an absolute-angle driver,
// connecting rod, slider on a translational joint with the ground. Its motion is kinematic and
// follows in closed form from the crank angle f(t) and the loop closure |B - A| = l.
std::unique_ptr<ReferenceSolution> make_slider_crank_exact(const SceneDef& scene);

}  // namespace periflex
