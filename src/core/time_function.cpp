#include "core/time_function.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace periflex {

TimeFunction TimeFunction::constant(double v) {
  TimeFunction f;
  f.kind = Kind::kConstant;
  f.value = v;
  return f;
}

TimeFunction TimeFunction::linear(double v0, double r) {
  TimeFunction f;
  f.kind = Kind::kRate;
  f.value = v0;
  f.rate = r;
  return f;
}

TimeFunction TimeFunction::antiderivative() const {
  TimeFunction f = *this;
  f.integrated = true;
  return f;
}

double TimeFunction::eval(double t, int order) const {
  if (!integrated) return eval_plain(t, order);
  return order == 0 ? integral(t) : eval_plain(t, order - 1);
}

double TimeFunction::integral(double t) const {
  switch (kind) {
    case Kind::kConstant:
      return value * t;
    case Kind::kRate:
      return value * t + 0.5 * rate * t * t;
    case Kind::kPolynomial: {
      double sum = 0.0;
      for (int k = static_cast<int>(coefficients.size()) - 1; k >= 0; --k)
        sum = sum * t + coefficients[k] / (k + 1);
      return sum * t;
    }
    case Kind::kHarmonic:
      if (omega == 0.0) return (offset + amplitude * std::sin(phase)) * t;
      return offset * t - amplitude / omega * (std::cos(omega * t + phase) - std::cos(phase));
    case Kind::kTable: {
      // Exact integral of the piecewise-linear table, constant beyond its ends.
      if (times.empty()) return 0.0;
      auto area = [&](double a, double b) { return 0.5 * (eval_plain(a, 0) + eval_plain(b, 0)) * (b - a); };
      double sum = 0.0, from = 0.0;
      if (t < 0.0) return -area(t, 0.0);
      for (size_t k = 0; k < times.size() && times[k] < t; ++k) {
        if (times[k] > from) {
          sum += area(from, times[k]);
          from = times[k];
        }
      }
      return sum + area(from, t);
    }
  }
  return 0.0;
}

double TimeFunction::eval_plain(double t, int order) const {
  switch (kind) {
    case Kind::kConstant:
      return order == 0 ? value : 0.0;
    case Kind::kRate:
      return order == 0 ? value + rate * t : (order == 1 ? rate : 0.0);
    case Kind::kPolynomial: {
      // Horner on the order-th derivative of the polynomial.
      double sum = 0.0;
      for (int k = static_cast<int>(coefficients.size()) - 1; k >= order; --k) {
        double factor = 1.0;
        for (int m = 0; m < order; ++m) factor *= (k - m);
        sum = sum * t + factor * coefficients[k];
      }
      return sum;
    }
    case Kind::kHarmonic: {
      const double arg = omega * t + phase;
      if (order == 0) return offset + amplitude * std::sin(arg);
      if (order == 1) return amplitude * omega * std::cos(arg);
      return -amplitude * omega * omega * std::sin(arg);
    }
    case Kind::kTable: {
      if (times.empty()) return 0.0;
      if (t <= times.front()) return order == 0 ? values.front() : 0.0;
      if (t >= times.back()) return order == 0 ? values.back() : 0.0;
      const auto upper = std::upper_bound(times.begin(), times.end(), t);
      const size_t k = static_cast<size_t>(upper - times.begin()) - 1;
      const double slope = (values[k + 1] - values[k]) / (times[k + 1] - times[k]);
      if (order == 0) return values[k] + slope * (t - times[k]);
      return order == 1 ? slope : 0.0;
    }
  }
  return 0.0;
}

std::string TimeFunction::describe() const {
  std::ostringstream out;
  switch (kind) {
    case Kind::kConstant: out << value; break;
    case Kind::kRate: out << value << " + " << rate << "*t"; break;
    case Kind::kPolynomial: {
      out << "polynomial(";
      for (size_t k = 0; k < coefficients.size(); ++k) out << (k ? ", " : "") << coefficients[k];
      out << ")";
      break;
    }
    case Kind::kHarmonic:
      out << offset << " + " << amplitude << "*sin(" << omega << "*t + " << phase << ")";
      break;
    case Kind::kTable: out << "table(" << times.size() << " points)"; break;
  }
  return out.str();
}

}  // namespace periflex
