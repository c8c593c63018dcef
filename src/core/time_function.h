// Functions of time used by drivers, prescribed motions and time-varying loads.
// Each gives its value and first two derivatives, which the acceleration
// constraints (gamma) of a rheonomic constraint need.
#pragma once

#include <string>
#include <vector>

namespace periflex {

struct TimeFunction {
  enum class Kind {
    kConstant,    // f = value
    kRate,        // f = value + rate * t
    kPolynomial,  // f = sum_k coefficients[k] * t^k
    kHarmonic,    // f = offset + amplitude * sin(omega * t + phase)
    kTable,       // piecewise-linear through (times[k], values[k]); constant outside
  };

  Kind kind = Kind::kConstant;
  double value = 0.0;
  double rate = 0.0;
  std::vector<double> coefficients;
  double offset = 0.0, amplitude = 0.0, omega = 0.0, phase = 0.0;
  std::vector<double> times, values;
  // When true the function is the antiderivative (from t = 0) of the one described above:
  // a prescribed velocity turned into the displacement it produces.
  bool integrated = false;

  static TimeFunction constant(double v);
  static TimeFunction linear(double v0, double rate);
  // The displacement function of a prescribed velocity v(t): u(t) = int_0^t v.
  TimeFunction antiderivative() const;

  double operator()(double t) const { return eval(t, 0); }
  double d1(double t) const { return eval(t, 1); }
  double d2(double t) const { return eval(t, 2); }

  // derivative_order in {0, 1, 2}.
  double eval(double t, int derivative_order) const;

 private:
  double eval_plain(double t, int derivative_order) const;
  double integral(double t) const;  // int_0^t of the plain function

  // Human-readable form for `periflex check`.
  std::string describe() const;
};

}  // namespace periflex
