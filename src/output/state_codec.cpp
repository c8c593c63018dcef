// SimState <-> bytes: a writer and a reader of fixed-width little-endian fields, in one order.
#include "output/state_codec.h"

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

namespace periflex {

namespace {

static_assert(std::endian::native == std::endian::little, "checkpoint files are written little-endian");

// Doubles are coded against the one this many places before: x with x, y with y.
constexpr size_t kStride = 2;

uint64_t bits_of(double v) {
  uint64_t b;
  std::memcpy(&b, &v, 8);
  return b;
}
// 0, -1, 1, -2, ... -> 0, 1, 2, 3, ...: small magnitudes of either sign get zero high bytes
uint64_t zigzag(uint64_t v) { return (v << 1) ^ static_cast<uint64_t>(static_cast<int64_t>(v) >> 63); }
uint64_t unzigzag(uint64_t z) { return (z >> 1) ^ (~(z & 1) + 1); }

// The prediction of value i from the ones before it (see Writer::put_planed).
uint64_t predicted(const double* data, size_t i, size_t row) {
  if (i < kStride) return 0;
  const uint64_t previous = bits_of(data[i - kStride]);
  if (row <= kStride || i < row + kStride) return previous;
  return previous + bits_of(data[i - row]) - bits_of(data[i - row - kStride]);
}

// The number of values per row of a particle grid in q (x, y interleaved, row by row): the
// distance between two places where x falls back (a new row begins); 0 when there is none. Only
// the size of the file depends on it, never what is read back.
size_t grid_row(const Eigen::VectorXd& q) {
  const size_t n = static_cast<size_t>(q.size());
  for (size_t parity = 0; parity < kStride; ++parity) {
    size_t wraps[3] = {0, 0, 0};
    int found = 0;
    for (size_t i = parity + kStride; i < n && found < 3; i += kStride)
      if (q[static_cast<Eigen::Index>(i)] < q[static_cast<Eigen::Index>(i - kStride)]) wraps[found++] = i;
    if (found == 3 && wraps[2] - wraps[1] > kStride) return wraps[2] - wraps[1];
  }
  return 0;
}

// Appends fields; arrays carry their length first.
struct Writer {
  std::vector<uint8_t> out;
  template <typename T>
  void put(T value) {
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    out.insert(out.end(), p, p + sizeof(T));
  }
  template <typename T>
  void put_array(const T* data, size_t count) {
    put<uint64_t>(count);
    const auto* p = reinterpret_cast<const uint8_t*>(data);
    out.insert(out.end(), p, p + sizeof(T) * count);
  }
  template <typename T>
  void put_vector(const std::vector<T>& v) { put_array(v.data(), v.size()); }
  // Doubles as the difference of their bit patterns (as integers) from a prediction, zigzag-coded
  // so small differences of either sign have zero high bytes, then byte-planed: plane b holds
  // byte b of every value. The prediction is the value two before (the same coordinate of the
  // previous particle); in arrays laid out like the positions of a particle grid (`row` values
  // per grid row, 0: none), the previous particle's value plus the change between the same two
  // particles one row before (a plane through three neighbours): a smooth field then leaves
  // differences of a few low bytes. Exact in both directions (integer arithmetic, wrapping).
  void put_planed(const double* data, size_t count, size_t row = 0) {
    put<uint64_t>(count);
    put<uint64_t>(row);
    const size_t at = out.size();
    out.resize(at + 8 * count);
    uint8_t* planes = out.data() + at;
    for (size_t i = 0; i < count; ++i) {
      const uint64_t coded = zigzag(bits_of(data[i]) - predicted(data, i, row));
      for (size_t b = 0; b < 8; ++b) planes[b * count + i] = static_cast<uint8_t>(coded >> (8 * b));
    }
  }
  // particle arrays (the size of q) with the grid's row, others without
  size_t row_of(size_t count) const { return count == row_count ? grid_row : 0; }
  size_t row_count = 0, grid_row = 0;
  void put_vector(const Eigen::VectorXd& v) {
    put_planed(v.data(), static_cast<size_t>(v.size()), row_of(static_cast<size_t>(v.size())));
  }
  void put_string(const std::string& s) { put_array(s.data(), s.size()); }
};

// Reads what Writer wrote; every length is checked against the bytes left.
struct Reader {
  const uint8_t* at;
  const uint8_t* end;
  void need(size_t bytes, const char* what) const {
    if (static_cast<size_t>(end - at) < bytes)
      throw std::runtime_error(std::string("the state ends inside ") + what);
  }
  template <typename T>
  T get(const char* what) {
    need(sizeof(T), what);
    T value;
    std::memcpy(&value, at, sizeof(T));
    at += sizeof(T);
    return value;
  }
  size_t count(size_t element, const char* what) {
    const uint64_t n = get<uint64_t>(what);
    if (element > 0 && n > static_cast<uint64_t>(end - at) / element)
      throw std::runtime_error(std::string("the state ends inside ") + what);
    return static_cast<size_t>(n);
  }
  template <typename T>
  void get_vector(std::vector<T>& v, const char* what) {
    const size_t n = count(sizeof(T), what);
    v.resize(n);
    if (n) std::memcpy(v.data(), at, sizeof(T) * n);
    at += sizeof(T) * n;
  }
  void get_vector(Eigen::VectorXd& v, const char* what) {
    const size_t n = count(8, what);
    const uint64_t row = get<uint64_t>(what);
    if (row > n) throw std::runtime_error(std::string("an impossible grid row in ") + what);
    need(8 * n, what);
    v.resize(static_cast<Eigen::Index>(n));
    double* data = v.data();
    for (size_t i = 0; i < n; ++i) {
      uint64_t coded = 0;
      for (size_t b = 0; b < 8; ++b) coded |= static_cast<uint64_t>(at[b * n + i]) << (8 * b);
      const uint64_t bits = unzigzag(coded) + predicted(data, i, static_cast<size_t>(row));
      std::memcpy(data + i, &bits, 8);
    }
    at += 8 * n;
  }
  std::string get_string(const char* what) {
    const size_t n = count(1, what);
    std::string s(reinterpret_cast<const char*>(at), n);
    at += n;
    return s;
  }
};

}  // namespace

std::vector<uint8_t> encode_state(const SimState& s) {
  Writer w;
  w.row_count = static_cast<size_t>(s.q.size());
  w.grid_row = grid_row(s.q);
  // clock and step count
  w.put(s.time);
  w.put<int64_t>(s.steps);
  w.put(s.clock_origin);
  w.put(s.clock_dt);
  w.put<int64_t>(s.clock_steps);
  w.put<uint8_t>(s.initialized ? 1 : 0);
  // coordinates and velocities
  w.put_vector(s.q);
  w.put_vector(s.qd);
  // energy accounts
  for (int k = 0; k < 3; ++k) w.put(s.work[k]);
  w.put(s.fracture_energy);
  w.put<int64_t>(s.broken_bonds);
  w.put(s.initial_total);
  w.put(s.initial_gravity);
  w.put(s.energy_scale);
  w.put(s.initial_position_correction);
  w.put(s.initial_velocity_correction);
  // singular-position watch and the dropped constraint rows
  w.put<uint8_t>(s.passage.open ? 1 : 0);
  w.put<int64_t>(s.passage.seen_changes);
  w.put<uint64_t>(s.passage.stable_dependent);
  w.put(s.passage.best_pivot);
  w.put(s.passage.entry_time);
  w.put(s.passage.entry_balance);
  w.put_vector(s.passage.rows);
  w.put_vector(s.passage.open ? s.passage.entry_q : Eigen::VectorXd());
  {
    std::vector<double> times, balances;
    s.passage.drift.samples(times, balances);
    w.put_vector(times);
    w.put_vector(balances);
  }
  w.put_vector(s.rank.dropped);
  w.put_vector(s.rank.last_dependent);
  w.put<int64_t>(s.rank.rank_changes);
  // integrator cache
  w.put_string(s.integrator.name);
  w.put_vector(s.integrator.scalars);
  w.put<uint64_t>(s.integrator.vectors.size());
  for (const auto& v : s.integrator.vectors) w.put_vector(v);
  w.put<int64_t>(s.integrator.accepted);
  w.put<int64_t>(s.integrator.rejected);
  w.put<uint8_t>(s.integrator.predicted ? 1 : 0);
  // flexible bodies
  w.put<uint64_t>(s.flex.size());
  for (const FlexState& f : s.flex) {
    w.put_vector(f.broken_bits);
    w.put<int64_t>(f.broken_pairs);
    w.put<int64_t>(f.pending_broken);
    w.put(f.pending_energy);
    w.put_planed(f.weighted_volume.data(), f.weighted_volume.size());
    w.put_planed(f.shear_coef.data(), f.shear_coef.size());
    w.put_planed(f.bond_history.data(), f.bond_history.size());
  }
  // contacts
  w.put<uint64_t>(s.contacts.size());
  for (const ContactCache& c : s.contacts) {
    w.put_vector(c.row);
    w.put_vector(c.col);
    w.put_planed(c.built_at.data(), c.built_at.size());
    w.put<int64_t>(c.built_broken);
  }
  return std::move(w.out);
}

SimState decode_state(const uint8_t* bytes, size_t size) {
  Reader r{bytes, bytes + size};
  SimState s;
  s.time = r.get<double>("the time");
  s.steps = r.get<int64_t>("the step count");
  s.clock_origin = r.get<double>("the clock");
  s.clock_dt = r.get<double>("the clock");
  s.clock_steps = r.get<int64_t>("the clock");
  s.initialized = r.get<uint8_t>("the clock") != 0;
  r.get_vector(s.q, "the positions");
  r.get_vector(s.qd, "the velocities");
  if (s.q.size() != s.qd.size()) throw std::runtime_error("positions and velocities differ in number");
  for (int k = 0; k < 3; ++k) s.work[k] = r.get<double>("the energy accounts");
  s.fracture_energy = r.get<double>("the energy accounts");
  s.broken_bonds = r.get<int64_t>("the energy accounts");
  s.initial_total = r.get<double>("the energy accounts");
  s.initial_gravity = r.get<double>("the energy accounts");
  s.energy_scale = r.get<double>("the energy accounts");
  s.initial_position_correction = r.get<double>("the energy accounts");
  s.initial_velocity_correction = r.get<double>("the energy accounts");
  s.passage.open = r.get<uint8_t>("the passage watch") != 0;
  s.passage.seen_changes = r.get<int64_t>("the passage watch");
  s.passage.stable_dependent = r.get<uint64_t>("the passage watch");
  s.passage.best_pivot = r.get<double>("the passage watch");
  s.passage.entry_time = r.get<double>("the passage watch");
  s.passage.entry_balance = r.get<double>("the passage watch");
  r.get_vector(s.passage.rows, "the passage watch");
  r.get_vector(s.passage.entry_q, "the passage watch");
  {
    std::vector<double> times, balances;
    r.get_vector(times, "the passage watch");
    r.get_vector(balances, "the passage watch");
    if (times.size() != balances.size() || times.size() > BalanceDrift::kSamples)
      throw std::runtime_error("the passage watch's energy samples do not fit its record");
    s.passage.drift.clear();
    for (size_t k = 0; k < times.size(); ++k) s.passage.drift.record(times[k], balances[k]);
  }
  r.get_vector(s.rank.dropped, "the constraint rows");
  r.get_vector(s.rank.last_dependent, "the constraint rows");
  s.rank.rank_changes = r.get<int64_t>("the constraint rows");
  s.integrator.name = r.get_string("the integrator cache");
  r.get_vector(s.integrator.scalars, "the integrator cache");
  s.integrator.vectors.resize(r.count(8, "the integrator cache"));
  for (auto& v : s.integrator.vectors) r.get_vector(v, "the integrator cache");
  s.integrator.accepted = r.get<int64_t>("the integrator cache");
  s.integrator.rejected = r.get<int64_t>("the integrator cache");
  s.integrator.predicted = r.get<uint8_t>("the integrator cache") != 0;
  if (s.integrator.predicted && s.integrator.vectors.empty())
    throw std::runtime_error("the integrator cache is marked predicted but holds no vector");
  s.flex.resize(r.count(8, "the flexible bodies"));
  for (FlexState& f : s.flex) {
    r.get_vector(f.broken_bits, "the broken bonds");
    f.broken_pairs = r.get<int64_t>("the broken bonds");
    f.pending_broken = r.get<int64_t>("the broken bonds");
    f.pending_energy = r.get<double>("the broken bonds");
    Eigen::VectorXd v;
    r.get_vector(v, "the weighted volumes");
    f.weighted_volume.assign(v.data(), v.data() + v.size());
    r.get_vector(v, "the weighted volumes");
    f.shear_coef.assign(v.data(), v.data() + v.size());
    r.get_vector(v, "the bond histories");
    f.bond_history.assign(v.data(), v.data() + v.size());
  }
  s.contacts.resize(r.count(8, "the contacts"));
  for (ContactCache& c : s.contacts) {
    r.get_vector(c.row, "a contact list");
    r.get_vector(c.col, "a contact list");
    Eigen::VectorXd v;
    r.get_vector(v, "a contact list");
    c.built_at.assign(v.data(), v.data() + v.size());
    c.built_broken = r.get<int64_t>("a contact list");
  }
  if (r.at != r.end) throw std::runtime_error(std::to_string(r.end - r.at) + " bytes follow the state");
  return s;
}

}  // namespace periflex
