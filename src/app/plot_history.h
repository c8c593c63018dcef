// Time series for the plots panel, one value per snapshot the render thread sees. Bounded:
// when full, the older half is thinned to every second value, so a long run keeps its whole
// history at a coarser spacing. No GL.
#pragma once

#include <string>
#include <vector>

#include "solve/snapshot.h"

namespace periflex {

class PlotHistory {
 public:
  enum Series {
    kKinetic, kPotential, kElastic, kDissipated, kBalance, kViolation, kBrokenBonds, kMaxDamage,
    kStepsPerSecond, kSeriesCount
  };
  static const char* name(int series) {
    static const char* names[kSeriesCount] = {"kinetic energy", "gravity potential", "elastic energy",
                                              "dissipated + fracture", "energy balance",
                                              "constraint violation |Phi|", "broken bonds",
                                              "max damage", "steps/s"};
    return names[series];
  }

  explicit PlotHistory(size_t capacity = 2000) : capacity_(capacity) {}

  // Appends the values of a snapshot (once per simulation step it shows).
  void add(const Snapshot& s, double steps_per_second) {
    if (s.step == last_step_ && !times_.empty()) return;
    last_step_ = s.step;
    if (times_.size() >= capacity_) thin();
    times_.push_back(s.time);
    const Energies& e = s.energies;
    const double values[kSeriesCount] = {e.kinetic, e.potential_gravity, e.potential_elastic,
                                         e.dissipated + e.fracture, e.balance, s.violation_position,
                                         static_cast<double>(s.broken_bonds), s.max_damage,
                                         steps_per_second};
    for (int k = 0; k < kSeriesCount; ++k) series_[k].push_back(static_cast<float>(values[k]));
  }
  void clear() {
    times_.clear();
    for (auto& v : series_) v.clear();
    last_step_ = -1;
  }
  const std::vector<float>& values(int series) const { return series_[series]; }
  size_t size() const { return times_.size(); }
  double first_time() const { return times_.empty() ? 0.0 : times_.front(); }
  double last_time() const { return times_.empty() ? 0.0 : times_.back(); }

 private:
  // keep every second of the older half, all of the newer half
  void thin() {
    const size_t half = times_.size() / 2;
    const auto squeeze = [half](auto& v) {
      size_t out = 0;
      for (size_t i = 0; i < half; i += 2) v[out++] = v[i];
      for (size_t i = half; i < v.size(); ++i) v[out++] = v[i];
      v.resize(out);
    };
    squeeze(times_);
    for (auto& v : series_) squeeze(v);
  }

  size_t capacity_;
  long last_step_ = -1;
  std::vector<double> times_;
  std::vector<float> series_[kSeriesCount];
};

}  // namespace periflex
