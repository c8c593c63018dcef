// The state's bytes read back bit for bit, whatever the values: a particle grid whose rows the
// coder finds (and predicts across), values of every sign, zero, subnormal and infinite ones
// where no prediction fits, arrays too short for a row; and bytes cut short are refused.
#include "output/state_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace periflex {
namespace {

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

// Two rigid bodies (x, y, phi) then an nx by ny particle grid, displaced by a smooth field and
// by noise in the last bits, as a running plate's positions are.
SimState grid_state(int nx, int ny) {
  SimState s;
  const int n = 6 + 2 * nx * ny;
  s.q.resize(n);
  s.qd.resize(n);
  s.q.head(6) << -0.05, 0.0, 0.1, 0.05, 0.0, -0.1;
  s.qd.head(6) << 1e-3, -2e-3, 0.0, 3.5, -0.0, 1e300;
  unsigned noise = 12345;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      noise = noise * 1103515245u + 12345u;
      const double jitter = static_cast<double>(noise >> 8) * 1e-24;
      const double x = -0.05 + 2e-4 * i, y = -0.02 + 2e-4 * j;
      const int k = 6 + 2 * (j * nx + i);
      s.q[k] = x + 1e-6 * std::sin(40 * x) * std::cos(30 * y) + jitter;
      s.q[k + 1] = y + 1e-6 * std::cos(40 * x) + jitter;
      s.qd[k] = 0.3 * std::sin(50 * x + 20 * y) - jitter * 1e10;
      s.qd[k + 1] = -0.2 * std::cos(30 * y) + jitter * 1e10;
    }
  }
  s.integrator.name = "verlet";
  s.integrator.scalars = {1.0, 0.5};
  s.integrator.vectors = {s.qd * 1e5};
  return s;
}

void expect_round_trip(const SimState& s) {
  const std::vector<uint8_t> bytes = encode_state(s);
  const SimState back = decode_state(bytes.data(), bytes.size());
  EXPECT_TRUE(same_bits(back.q, s.q));
  EXPECT_TRUE(same_bits(back.qd, s.qd));
  ASSERT_EQ(back.integrator.vectors.size(), s.integrator.vectors.size());
  for (size_t k = 0; k < s.integrator.vectors.size(); ++k)
    EXPECT_TRUE(same_bits(back.integrator.vectors[k], s.integrator.vectors[k]));
}

TEST(StateCodec, GridStateReadsBackBitForBit) { expect_round_trip(grid_state(50, 20)); }

TEST(StateCodec, SmoothGridCodesToZeroHighBytes) {
  // the plane through three neighbours predicts a smooth field to its last bytes: most of the
  // coded positions' top two bytes are zero (the previous particle alone leaves the grid step)
  const SimState s = grid_state(200, 50);
  const std::vector<uint8_t> bytes = encode_state(s);
  // the positions follow the clock: time, steps, origin, dt, clock steps, flag, count, row
  const size_t at = 8 + 8 + 8 + 8 + 8 + 1;
  uint64_t count = 0, row = 0;
  std::memcpy(&count, bytes.data() + at, 8);
  std::memcpy(&row, bytes.data() + at + 8, 8);
  ASSERT_EQ(count, static_cast<uint64_t>(s.q.size()));
  EXPECT_EQ(row, 400u) << "the grid's row (200 particles, x and y) was not found";
  const uint8_t* planes = bytes.data() + at + 16;
  size_t zero = 0;
  for (size_t i = 0; i < count; ++i) zero += planes[7 * count + i] == 0 && planes[6 * count + i] == 0;
  EXPECT_GT(zero, count * 9 / 10);
}

TEST(StateCodec, AnyValuesReadBackBitForBit) {
  SimState s = grid_state(7, 5);
  const double inf = std::numeric_limits<double>::infinity();
  const double tiny = std::numeric_limits<double>::denorm_min();
  for (int k = 0; k < s.qd.size(); ++k) {
    const double odd[] = {-0.0, 0.0, tiny, -tiny, inf, -inf, 1e308, -1e-308};
    s.qd[k] = odd[k % 8];
  }
  s.q.reverse();  // rows found nowhere, or in the wrong place
  expect_round_trip(s);
  SimState tiny_state;
  tiny_state.q = Eigen::VectorXd::Constant(1, 2.0);
  tiny_state.qd = Eigen::VectorXd::Constant(1, -3.0);
  expect_round_trip(tiny_state);
}

// The passage watch's record of the energy balance (the integrator's own error a dead point is
// judged against) and the largest pivot seen (what "near singular" is measured against) survive
// a checkpoint, wrapped ring included: a restarted run judges its next passage as the
// uninterrupted run does.
TEST(StateCodec, PassageWatchBalanceRecordReadsBack) {
  SimState s = grid_state(4, 3);
  for (int k = 0; k < BalanceDrift::kSamples + 17; ++k) s.passage.drift.record(1e-3 * k, std::sin(0.37 * k) * 1e-3 * k);
  s.passage.best_pivot = 0.152683;
  const std::vector<uint8_t> bytes = encode_state(s);
  const SimState back = decode_state(bytes.data(), bytes.size());
  EXPECT_EQ(back.passage.best_pivot, s.passage.best_pivot);
  std::vector<double> t0, b0, t1, b1;
  s.passage.drift.samples(t0, b0);
  back.passage.drift.samples(t1, b1);
  EXPECT_EQ(t1, t0);
  EXPECT_EQ(b1, b0);
  for (double span : {0.0105, 0.03, 1.0})
    EXPECT_EQ(back.passage.drift.change_over(span), s.passage.drift.change_over(span)) << span;
}

TEST(StateCodec, BytesCutShortAreRefused) {
  const SimState s = grid_state(10, 10);
  const std::vector<uint8_t> bytes = encode_state(s);
  for (size_t cut : {size_t{20}, size_t{60}, bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW(decode_state(bytes.data(), cut), std::runtime_error) << cut;
}

}  // namespace
}  // namespace periflex
