#include "scene/grid_scan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "scene/shape_boolean.h"

namespace periflex {

namespace {

using Run = std::pair<long, long>;  // cells [first, second) of a row

// A double cell index clamped into [lo, hi] before it becomes an integer.
long clamp_index(double value, long lo, long hi) {
  if (!(value > static_cast<double>(lo))) return lo;
  if (!(value < static_cast<double>(hi))) return hi;
  return static_cast<long>(value);
}

// Runs of one shape on successive rows. Convex shapes give one candidate interval per row,
// trimmed at both ends by the inside test itself; polygons give the exact crossings the inside
// test counts.
class RowShape {
 public:
  RowShape(const ShapeDef& shape, const GridFrame& frame) : shape_(shape), frame_(frame) {
    // a box's (or a bar's) rotation, once rather than on every row
    if (shape.kind == ShapeDef::Kind::kBox) angle_ = shape.angle;
    if (shape.kind == ShapeDef::Kind::kBar) angle_ = std::atan2(shape.p2.y() - shape.p1.y(), shape.p2.x() - shape.p1.x());
    cos_ = std::cos(angle_);
    sin_ = std::sin(angle_);
    // a combined shape combines the runs of its operands, row by row
    for (const ShapeDef& operand : shape.operands)
      if (shape.kind == ShapeDef::Kind::kBoolean) operands_.push_back(std::make_unique<RowShape>(operand, frame));
    if (shape.kind != ShapeDef::Kind::kPolygon) return;
    // edges sorted by their lower end, so a row adds the edges it reaches
    const size_t n = shape.vertices.size();
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
      if (shape.vertices[i].y() == shape.vertices[j].y()) continue;  // never crossed
      edges_.push_back({i, j});
    }
    std::sort(edges_.begin(), edges_.end(), [&](const Edge& a, const Edge& b) { return low(a) < low(b); });
  }

  // Appends the runs of row j (called with j increasing).
  void runs(long j, std::vector<Run>& out) {
    switch (shape_.kind) {
      case ShapeDef::Kind::kNone:
        return;
      case ShapeDef::Kind::kPolygon:
        polygon_runs(j, out);
        return;
      case ShapeDef::Kind::kBoolean:
        boolean_runs(j, out);
        return;
      default:
        convex_runs(j, out);
        return;
    }
  }

 private:
  struct Edge {
    size_t i, j;  // vertex indices as ShapeDef::contains pairs them (a = v[i], b = v[j])
  };
  double low(const Edge& e) const { return std::min(shape_.vertices[e.i].y(), shape_.vertices[e.j].y()); }
  double high(const Edge& e) const { return std::max(shape_.vertices[e.i].y(), shape_.vertices[e.j].y()); }

  // Candidate x interval of the shape on the line y (a superset of the inside cells).
  bool candidate(double y, double& xa, double& xb) const {
    const double inf = std::numeric_limits<double>::infinity();
    switch (shape_.kind) {
      case ShapeDef::Kind::kBox:
        return box_interval(shape_.center, 0.5 * shape_.width, 0.5 * shape_.height, y, xa, xb);
      case ShapeDef::Kind::kCircle:
        return circle_interval(shape_.center, shape_.radius, y, xa, xb);
      case ShapeDef::Kind::kBar: {
        // a stadium: the swept rectangle and the two end discs; convex, so their union is one interval
        xa = inf;
        xb = -inf;
        const Vec2 d = shape_.p2 - shape_.p1;
        double a = 0, b = 0;
        if (box_interval(0.5 * (shape_.p1 + shape_.p2), 0.5 * d.norm(), shape_.radius, y, a, b))
          xa = std::min(xa, a), xb = std::max(xb, b);
        if (circle_interval(shape_.p1, shape_.radius, y, a, b)) xa = std::min(xa, a), xb = std::max(xb, b);
        if (circle_interval(shape_.p2, shape_.radius, y, a, b)) xa = std::min(xa, a), xb = std::max(xb, b);
        return xa <= xb;
      }
      default:
        return false;
    }
  }

  // x interval of a box rotated by angle_ (half sizes hw, hh, with the inside test's tolerance) on line y.
  bool box_interval(const Vec2& c, double hw, double hh, double y, double& xa, double& xb) const {
    const double co = cos_, si = sin_;
    const double w = hw * (1 + 1e-9), h = hh * (1 + 1e-9);
    const double dy = y - c.y();
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    // local x = co dx + si dy within [-w, w]; local y = -si dx + co dy within [-h, h]
    auto slab = [&](double coefficient, double offset, double half) {
      if (coefficient == 0.0) {
        if (std::abs(offset) > half) lo = hi + 1;  // empty
        return;
      }
      double a = (-half - offset) / coefficient, b = (half - offset) / coefficient;
      if (a > b) std::swap(a, b);
      lo = std::max(lo, a);
      hi = std::min(hi, b);
    };
    slab(co, si * dy, w);
    slab(-si, co * dy, h);
    if (!(lo <= hi)) return false;
    xa = c.x() + lo;
    xb = c.x() + hi;
    return true;
  }

  static bool circle_interval(const Vec2& c, double r, double y, double& xa, double& xb) {
    const double dy = y - c.y();
    const double left = r * r * (1 + 1e-9) - dy * dy;
    if (left < 0.0) return false;
    const double half = std::sqrt(left);
    xa = c.x() - half;
    xb = c.x() + half;
    return true;
  }

  void convex_runs(long j, std::vector<Run>& out) const {
    const double y = frame_.cell(0, j).y();
    double xa = 0, xb = 0;
    if (!candidate(y, xa, xb)) return;
    // one spare cell each side, then trimmed by the inside test: the shape is convex, so the
    // cells between the first and last inside cell are inside
    const double ox = frame_.origin.x(), dx = frame_.dx;
    long first = clamp_index(std::floor((xa - ox) / dx) - 1, 0, frame_.nx - 1);
    long last = clamp_index(std::ceil((xb - ox) / dx) + 1, 0, frame_.nx - 1);
    while (first <= last && !shape_.contains(frame_.cell(first, j))) ++first;
    while (last >= first && !shape_.contains(frame_.cell(last, j))) --last;
    if (first <= last) out.emplace_back(first, last + 1);
  }

  void polygon_runs(long j, std::vector<Run>& out) {
    const double y = frame_.cell(0, j).y();
    // edges the row reaches join; edges it has passed leave (contains: low <= y < high)
    while (next_ < edges_.size() && low(edges_[next_]) <= y) active_.push_back(edges_[next_++]);
    active_.erase(std::remove_if(active_.begin(), active_.end(), [&](const Edge& e) { return !(y < high(e)); }),
                  active_.end());
    // the crossing abscissae, computed as the inside test computes them
    crossings_.clear();
    for (const Edge& e : active_) {
      const Vec2& a = shape_.vertices[e.i];
      const Vec2& b = shape_.vertices[e.j];
      if ((a.y() > y) == (b.y() > y)) continue;
      crossings_.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    std::sort(crossings_.begin(), crossings_.end());
    // a cell at x is inside when an odd number of crossings lie beyond it: x in [c_2k, c_2k+1)
    for (size_t k = 0; k + 1 < crossings_.size(); k += 2) {
      const long begin = first_at_or_after(crossings_[k], j);
      const long end = first_at_or_after(crossings_[k + 1], j);
      if (begin < end) out.emplace_back(begin, end);
    }
  }

  void boolean_runs(long j, std::vector<Run>& out);

  // Smallest i in [0, nx] whose cell centre is at or beyond x.
  long first_at_or_after(double x, long j) const {
    long i = clamp_index(std::ceil((x - frame_.origin.x()) / frame_.dx), 0, frame_.nx);
    while (i > 0 && frame_.cell(i - 1, j).x() >= x) --i;
    while (i < frame_.nx && frame_.cell(i, j).x() < x) ++i;
    return i;
  }

  const ShapeDef& shape_;
  const GridFrame& frame_;
  double angle_ = 0.0, cos_ = 1.0, sin_ = 0.0;
  std::vector<Edge> edges_, active_;
  size_t next_ = 0;
  std::vector<double> crossings_;
  std::vector<std::unique_ptr<RowShape>> operands_;
};

// Sorts runs and merges the overlapping ones.
void merge(std::vector<Run>& runs) {
  std::sort(runs.begin(), runs.end());
  size_t kept = 0;
  for (const Run& r : runs) {
    if (kept > 0 && r.first <= runs[kept - 1].second) {
      runs[kept - 1].second = std::max(runs[kept - 1].second, r.second);
    } else {
      runs[kept++] = r;
    }
  }
  runs.resize(kept);
}

// a minus b; both sorted and disjoint.
std::vector<Run> subtract(const std::vector<Run>& a, const std::vector<Run>& b) {
  std::vector<Run> out;
  size_t k = 0;
  for (Run r : a) {
    while (k < b.size() && b[k].second <= r.first) ++k;
    for (size_t m = k; m < b.size() && b[m].first < r.second; ++m) {
      if (b[m].first > r.first) out.emplace_back(r.first, b[m].first);
      r.first = std::max(r.first, b[m].second);
      if (r.first >= r.second) break;
    }
    if (r.first < r.second) out.emplace_back(r);
  }
  return out;
}

// a intersected with b; both sorted and disjoint.
std::vector<Run> intersect(const std::vector<Run>& a, const std::vector<Run>& b) {
  std::vector<Run> out;
  size_t i = 0, k = 0;
  while (i < a.size() && k < b.size()) {
    const long first = std::max(a[i].first, b[k].first), second = std::min(a[i].second, b[k].second);
    if (first < second) out.emplace_back(first, second);
    if (a[i].second < b[k].second) ++i;
    else ++k;
  }
  return out;
}

// The operands' runs of row j combined as the inside test combines them.
void RowShape::boolean_runs(long j, std::vector<Run>& out) {
  std::vector<Run> combined, other;
  for (size_t k = 0; k < operands_.size(); ++k) {
    other.clear();
    operands_[k]->runs(j, other);
    merge(other);
    if (k == 0) {
      combined = other;
    } else if (shape_.combine == ShapeDef::Combine::kUnion) {
      combined.insert(combined.end(), other.begin(), other.end());
      merge(combined);
    } else if (shape_.combine == ShapeDef::Combine::kIntersection) {
      combined = intersect(combined, other);
    } else {
      combined = subtract(combined, other);
    }
  }
  out.insert(out.end(), combined.begin(), combined.end());
}

// Rows of the frame a shape's bounds reach, as a [first, last] index range.
void row_range(const ShapeDef& shape, const GridFrame& frame, long& first, long& last) {
  Vec2 lo, hi;
  shape_bounds(shape, lo, hi);
  first = clamp_index(std::floor((lo.y() - frame.origin.y()) / frame.dx) - 1, 0, frame.ny - 1);
  last = clamp_index(std::ceil((hi.y() - frame.origin.y()) / frame.dx) + 1, 0, frame.ny - 1);
}

}  // namespace

void shape_bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi) {
  lo = Vec2::Zero();
  hi = Vec2::Zero();
  switch (shape.kind) {
    case ShapeDef::Kind::kNone:
      return;
    case ShapeDef::Kind::kBoolean:
      boolean_bounds(shape, lo, hi);
      return;
    case ShapeDef::Kind::kBox: {
      // the rotated half-extents projected on the axes
      const double c = std::abs(std::cos(shape.angle)), s = std::abs(std::sin(shape.angle));
      const Vec2 half(0.5 * (shape.width * c + shape.height * s), 0.5 * (shape.width * s + shape.height * c));
      lo = shape.center - half;
      hi = shape.center + half;
      return;
    }
    case ShapeDef::Kind::kCircle:
      lo = shape.center - Vec2(shape.radius, shape.radius);
      hi = shape.center + Vec2(shape.radius, shape.radius);
      return;
    case ShapeDef::Kind::kBar:
      lo = shape.p1.cwiseMin(shape.p2) - Vec2(shape.radius, shape.radius);
      hi = shape.p1.cwiseMax(shape.p2) + Vec2(shape.radius, shape.radius);
      return;
    case ShapeDef::Kind::kPolygon:
      if (shape.vertices.empty()) return;
      lo = hi = shape.vertices.front();
      for (const Vec2& v : shape.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      return;
  }
}

Vec2 grid_extent_cells(const ShapeDef& shape, double dx) {
  Vec2 lo, hi;
  shape_bounds(shape, lo, hi);
  return (hi - lo) / dx + Vec2(2.0, 2.0);
}

GridFrame grid_frame(const ShapeDef& shape, double dx) {
  GridFrame frame;
  frame.dx = dx;
  Vec2 lo, hi;
  shape_bounds(shape, lo, hi);
  const Vec2 mid = 0.5 * (lo + hi);
  // cells per axis: the extent in cells, plus one spare column each side that the inside test
  // removes again (keeps the parity, so aligned boxes are filled exactly)
  frame.nx = std::lround((hi.x() - lo.x()) / dx) + 2;
  frame.ny = std::lround((hi.y() - lo.y()) / dx) + 2;
  frame.origin = mid - 0.5 * dx * Vec2(static_cast<double>(frame.nx - 1), static_cast<double>(frame.ny - 1));
  return frame;
}

double grid_scan_work(const ShapeDef& shape, const std::vector<ShapeDef>& holes, const GridFrame& frame,
                      const std::vector<ShapeDef>& inside) {
  // every row asks every shape for its runs; a polygon also pays for each edge on each row it
  // spans; a combined shape, for each of its operands
  auto work = [&](const ShapeDef& s, auto&& self) -> double {
    double total = static_cast<double>(frame.ny);
    for (const ShapeDef& operand : s.operands) total += self(operand, self);
    if (s.kind != ShapeDef::Kind::kPolygon) return total;
    const size_t n = s.vertices.size();
    for (size_t i = 0, j = n - 1; i < n; j = i++)
      total += std::abs(s.vertices[i].y() - s.vertices[j].y()) / frame.dx + 1.0;
    return total;
  };
  double total = work(shape, work);
  for (const ShapeDef& h : holes) total += work(h, work);
  for (const ShapeDef& s : inside) total += work(s, work);
  return total;
}

void scan_grid(const ShapeDef& shape, const std::vector<ShapeDef>& holes, const GridFrame& frame,
               const std::vector<ShapeDef>& inside, const CellRunVisitor& visit) {
  if (frame.nx <= 0 || frame.ny <= 0) return;
  RowShape body(shape, frame);
  std::vector<std::unique_ptr<RowShape>> hole_rows, inside_rows;
  for (const ShapeDef& h : holes) hole_rows.push_back(std::make_unique<RowShape>(h, frame));
  for (const ShapeDef& s : inside) inside_rows.push_back(std::make_unique<RowShape>(s, frame));

  // only the rows every shape of `inside` and the body itself can reach
  long first = 0, last = frame.ny - 1;
  row_range(shape, frame, first, last);
  for (const ShapeDef& s : inside) {
    long a = 0, b = 0;
    row_range(s, frame, a, b);
    first = std::max(first, a);
    last = std::min(last, b);
  }

  std::vector<Run> runs, other;
  for (long j = first; j <= last; ++j) {
    runs.clear();
    body.runs(j, runs);
    merge(runs);
    for (auto& s : inside_rows) {
      if (runs.empty()) break;
      other.clear();
      s->runs(j, other);
      merge(other);
      runs = intersect(runs, other);
    }
    if (!runs.empty() && !hole_rows.empty()) {
      other.clear();
      for (auto& h : hole_rows) h->runs(j, other);
      merge(other);
      runs = subtract(runs, other);
    }
    for (const Run& r : runs) visit(j, r.first, r.second);
  }
}

long count_grid_cells(const ShapeDef& shape, const std::vector<ShapeDef>& holes, const GridFrame& frame,
                      const std::vector<ShapeDef>& inside) {
  long count = 0;
  scan_grid(shape, holes, frame, inside, [&](long, long begin, long end) { count += end - begin; });
  return count;
}

}  // namespace periflex
