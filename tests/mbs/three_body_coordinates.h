// Coordinates of a system of three planar bodies (x, y, phi each), for the tests that check a
// joint's or a force element's derivatives against finite differences.
#pragma once

#include <Eigen/Core>
#include <random>

namespace periflex::testing {

inline constexpr int kThreeBodyCoordinates = 9;

// Each coordinate drawn uniformly from [-scale, scale].
inline Eigen::VectorXd random_coordinates(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(kThreeBodyCoordinates);
  for (int k = 0; k < kThreeBodyCoordinates; ++k) v[k] = u(rng);
  return v;
}

// A fixed pose with no coordinate zero or repeated, where a sign or an index slip shows.
inline const Eigen::VectorXd kSpreadPose = Eigen::VectorXd::LinSpaced(kThreeBodyCoordinates, 0.1, 0.9);

}  // namespace periflex::testing
