// Axes of the window's plots: tick positions at round numbers (1, 2 or 5 times a power of ten)
// and the visible range of a column. No GL, no ImGui.
#pragma once

#include <string>
#include <vector>

namespace periflex {

// Ticks within [lo, hi] at a round step giving at most `most` of them (at least 2 when the range
// is not empty). An empty or reversed range gives the one value lo.
std::vector<double> nice_ticks(double lo, double hi, int most);

// A tick's label: the value with the step's decimals ("0.04", "400", "-3"), in exponent form
// only below 1e-3 or from 1e5 ("2e-06"), never "-0".
std::string tick_label(double value, double step);

// The range of `y` over the points whose x lies in [x_lo, x_hi], widened by 5% each side (a flat
// series by its magnitude, a zero one to [-1, 1]). False when no point lies in the range.
bool visible_range(const std::vector<double>& x, const std::vector<double>& y, double x_lo, double x_hi,
                   double& y_lo, double& y_hi);

// The text of a plot exported as CSV: a header "x_name,y_name" and the points with x in
// [x_lo, x_hi], each value in the shortest form that reads back as the same double.
std::string plot_csv(const std::string& x_name, const std::string& y_name, const std::vector<double>& x,
                     const std::vector<double>& y, double x_lo, double x_hi);

// The same for several series sharing one x: a header "x_name,y_names[0],y_names[1],..." and one
// row per x in [x_lo, x_hi] with every series' value at it (ys[k] has as many values as x).
std::string plot_csv(const std::string& x_name, const std::vector<double>& x,
                     const std::vector<std::string>& y_names, const std::vector<const std::vector<double>*>& ys,
                     double x_lo, double x_hi);

}  // namespace periflex
