// Small planar math used throughout: 2-vectors and the rotation matrix A(phi) of Nikravesh.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace periflex {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

// A(phi) maps body-fixed vectors to global ones.
inline Mat2 rotation(double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  Mat2 a;
  a << c, -s, s, c;
  return a;
}

// B(phi) = dA/dphi = A(phi) * R90.
inline Mat2 rotation_derivative(double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  Mat2 b;
  b << -s, -c, c, -s;
  return b;
}

// Counter-clockwise quarter turn: perp(v) = [-v.y, v.x].
inline Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }

inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

constexpr double kPi = 3.14159265358979323846;

}  // namespace periflex
