#include "scene/dxf_shape.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace {

[[noreturn]] void fail(const std::string& path, long line, const std::string& message) {
  throw InputError(SourceLocation{path, static_cast<int>(line), 0, "shape.file"}, message);
}

// One entity: its type, the file line of its "0" code and its group codes in order.
struct Entity {
  std::string type;
  long line = 0;
  std::vector<std::pair<int, std::string>> groups;
  double number(int code, double fallback = 0.0) const {
    for (const auto& [c, v] : groups)
      if (c == code) return std::strtod(v.c_str(), nullptr);
    return fallback;
  }
  std::string text(int code) const {
    for (const auto& [c, v] : groups)
      if (c == code) return v;
    return "";
  }
};

// A chain of points from one or more entities; closed when its ends met.
struct Piece {
  std::vector<Vec2> points;
  std::string entity;  // "LINE at line 12", for messages
  bool closed = false;
};

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// The entities of the ENTITIES section (code/value line pairs).
std::vector<Entity> read_entities(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) fail(path, 0, "cannot be opened");
  if (static_cast<double>(in.tellg()) > kMaxDxfBytes)
    fail(path, 0, "is larger than " + format_count(kMaxDxfBytes) + " bytes");
  in.seekg(0);
  std::vector<Entity> entities;
  std::string code_text, value;
  long line = 0;
  bool in_entities = false, saw_section = false, section_name_next = false;
  Entity* current = nullptr;
  while (std::getline(in, code_text)) {
    ++line;
    if (!std::getline(in, value)) break;
    ++line;
    int code = 0;
    const std::string c = trim(code_text);
    const auto [end, ec] = std::from_chars(c.data(), c.data() + c.size(), code);
    if (ec != std::errc() || end != c.data() + c.size())
      fail(path, line - 1, "expected a group code (an integer) on this line, found '" + c.substr(0, 40) +
                               "'; is this an ASCII DXF file?");
    value = trim(value);
    if (code == 0) {
      current = nullptr;
      if (value == "SECTION") {
        saw_section = true;
        section_name_next = true;
        continue;
      }
      if (value == "ENDSEC") {
        in_entities = false;
        continue;
      }
      if (in_entities) {
        entities.push_back({value, line - 1, {}});
        current = &entities.back();
      }
      continue;
    }
    if (code == 2 && section_name_next) {
      in_entities = value == "ENTITIES";
      section_name_next = false;
      continue;
    }
    if (current != nullptr) current->groups.emplace_back(code, value);
  }
  if (!saw_section) fail(path, 0, "has no SECTION; is this an ASCII DXF file?");
  return entities;
}

// Points along an arc from angle a0 to a1 (radians, counter-clockwise), both ends included.
void append_arc(std::vector<Vec2>& out, const Vec2& c, double r, double a0, double a1) {
  while (a1 <= a0) a1 += 2.0 * kPi;
  const int n = std::max(2, static_cast<int>(std::ceil((a1 - a0) / (2.0 * kPi) * kDxfSegmentsPerTurn)));
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + (a1 - a0) * k / n;
    out.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
  }
}

// The segment p -> q with a bulge (tan of a quarter of the included angle; > 0 counter-clockwise),
// without its first point.
void append_bulge(std::vector<Vec2>& out, const Vec2& p, const Vec2& q, double bulge) {
  if (bulge == 0.0 || (q - p).norm() == 0.0) {
    out.push_back(q);
    return;
  }
  const double theta = 4.0 * std::atan(bulge);  // included angle, signed
  const double chord = (q - p).norm();
  const double r = chord / (2.0 * std::sin(std::abs(theta) / 2.0));
  const Vec2 mid = 0.5 * (p + q), dir = (q - p) / chord, normal(-dir.y(), dir.x());
  const double h = r * std::cos(theta / 2.0);  // centre's distance from the chord, to the left for bulge > 0
  const Vec2 c = mid + (bulge > 0 ? 1.0 : -1.0) * h * normal;
  const double a0 = std::atan2(p.y() - c.y(), p.x() - c.x());
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(theta) / (2.0 * kPi) * kDxfSegmentsPerTurn)));
  for (int k = 1; k <= n; ++k) {
    const double a = a0 + theta * k / n;
    out.push_back(k == n ? q : c + r * Vec2(std::cos(a), std::sin(a)));
  }
}

// Vertices and bulges of a polyline (LWPOLYLINE: in its own groups; POLYLINE: its VERTEX entities).
Piece polyline_piece(const std::vector<Vec2>& vertices, const std::vector<double>& bulges, bool closed,
                     const std::string& name) {
  Piece piece;
  piece.entity = name;
  if (vertices.empty()) return piece;
  piece.points.push_back(vertices.front());
  for (size_t k = 1; k < vertices.size(); ++k) append_bulge(piece.points, vertices[k - 1], vertices[k], bulges[k - 1]);
  if (closed) {
    append_bulge(piece.points, vertices.back(), vertices.front(), bulges.back());
    piece.points.pop_back();  // the first point again
    piece.closed = true;
  }
  return piece;
}

bool point_in_loop(const Vec2& p, const std::vector<Vec2>& loop) {
  bool inside = false;
  for (size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Vec2 &a = loop[i], &b = loop[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      inside = !inside;
  }
  return inside;
}

double signed_area(const std::vector<Vec2>& loop) {
  double twice = 0.0;
  for (size_t i = 0, n = loop.size(); i < n; ++i) twice += cross(loop[i], loop[(i + 1) % n]);
  return 0.5 * twice;
}

std::string point_text(const Vec2& p) {
  std::string text(1, '(');
  text += format_number(p.x());
  text += ", ";
  text += format_number(p.y());
  text += ')';
  return text;
}

}  // namespace

DxfOutline read_dxf_shape(const std::string& path, const DxfShapeOptions& options) {
  const std::vector<Entity> entities = read_entities(path);

  // each entity of the layer as a piece: closed already, or a chain to be joined
  std::vector<Piece> pieces;
  for (size_t k = 0; k < entities.size(); ++k) {
    const Entity& e = entities[k];
    if (!options.layer.empty() && e.text(8) != options.layer) continue;
    const std::string name = e.type + " at line " + std::to_string(e.line);
    if (e.type == "LINE") {
      pieces.push_back({{Vec2(e.number(10), e.number(20)), Vec2(e.number(11), e.number(21))}, name, false});
    } else if (e.type == "CIRCLE" || e.type == "ARC") {
      const Vec2 c(e.number(10), e.number(20));
      const double r = e.number(40);
      if (!(r > 0.0)) fail(path, e.line, name + " has radius " + format_number(r) + "; expected a positive radius");
      Piece piece;
      piece.entity = name;
      if (e.type == "CIRCLE") {
        append_arc(piece.points, c, r, 0.0, 2.0 * kPi);
        piece.points.pop_back();
        piece.closed = true;
      } else {
        append_arc(piece.points, c, r, e.number(50) * kPi / 180.0, e.number(51) * kPi / 180.0);
      }
      pieces.push_back(piece);
    } else if (e.type == "LWPOLYLINE") {
      std::vector<Vec2> vertices;
      std::vector<double> bulges;
      for (const auto& [code, value] : e.groups) {
        if (code == 10) vertices.emplace_back(std::strtod(value.c_str(), nullptr), 0.0), bulges.push_back(0.0);
        if (code == 20 && !vertices.empty()) vertices.back().y() = std::strtod(value.c_str(), nullptr);
        if (code == 42 && !bulges.empty()) bulges.back() = std::strtod(value.c_str(), nullptr);
      }
      pieces.push_back(polyline_piece(vertices, bulges, (static_cast<long>(e.number(70)) & 1) != 0, name));
    } else if (e.type == "POLYLINE") {
      std::vector<Vec2> vertices;
      std::vector<double> bulges;
      size_t m = k + 1;
      for (; m < entities.size() && entities[m].type == "VERTEX"; ++m) {
        vertices.emplace_back(entities[m].number(10), entities[m].number(20));
        bulges.push_back(entities[m].number(42));
      }
      pieces.push_back(polyline_piece(vertices, bulges, (static_cast<long>(e.number(70)) & 1) != 0, name));
      k = m;  // past its vertices (and SEQEND)
    }
  }
  pieces.erase(std::remove_if(pieces.begin(), pieces.end(), [](const Piece& p) { return p.points.size() < 2; }),
               pieces.end());
  if (pieces.empty())
    fail(path, 0, "has no line, arc, circle or polyline" +
                      (options.layer.empty() ? std::string() : " on layer '" + options.layer + "'"));

  // the gap closed between ends: 1e-6 of the drawing's size unless given
  Vec2 lo = pieces.front().points.front(), hi = lo;
  for (const Piece& p : pieces)
    for (const Vec2& v : p.points) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double tolerance = options.tolerance >= 0.0 ? options.tolerance : 1e-6 * (hi - lo).maxCoeff();

  // open chains joined end to end into loops
  std::vector<std::vector<Vec2>> loops;
  std::vector<bool> used(pieces.size(), false);
  for (size_t k = 0; k < pieces.size(); ++k) {
    if (used[k]) continue;
    used[k] = true;
    if (pieces[k].closed) {
      loops.push_back(pieces[k].points);
      continue;
    }
    std::vector<Vec2> chain = pieces[k].points;
    std::string last = pieces[k].entity;
    while ((chain.back() - chain.front()).norm() > tolerance) {
      // the next piece: one whose start or end is at the chain's end
      size_t best = pieces.size();
      bool reversed = false;
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t m = 0; m < pieces.size(); ++m) {
        if (used[m] || pieces[m].closed) continue;
        const double ds = (pieces[m].points.front() - chain.back()).norm();
        const double de = (pieces[m].points.back() - chain.back()).norm();
        if (std::min(ds, de) < nearest) {
          nearest = std::min(ds, de);
          best = m;
          reversed = de < ds;
        }
      }
      if (best == pieces.size() || nearest > tolerance)
        fail(path, 0, "the outline is not closed: " + last + " ends at " + point_text(chain.back()) +
                          " where no other entity starts or ends (gap " +
                          (best == pieces.size() ? "to the loop's start " + format_number((chain.back() - chain.front()).norm())
                                                 : format_number(nearest) + " to " + pieces[best].entity) +
                          ", tolerance " + format_number(tolerance) + " drawing units)");
      used[best] = true;
      std::vector<Vec2> next = pieces[best].points;
      if (reversed) std::reverse(next.begin(), next.end());
      chain.insert(chain.end(), next.begin() + 1, next.end());
      last = pieces[best].entity;
    }
    chain.pop_back();  // the start again
    if (chain.size() >= 3) loops.push_back(chain);
  }
  if (loops.empty()) fail(path, 0, "has no closed loop");

  // loops inside no other loop are material, inside one a hole; scaled to metres, counter-clockwise
  DxfOutline outline;
  for (size_t k = 0; k < loops.size(); ++k) {
    int depth = 0;
    for (size_t m = 0; m < loops.size(); ++m)
      if (m != k && point_in_loop(loops[k].front(), loops[m])) ++depth;
    if (depth > 1)
      fail(path, 0, "a loop through " + point_text(loops[k].front()) + " lies inside a hole; "
                        "islands inside holes are not supported (draw them as another body)");
    std::vector<Vec2> loop = loops[k];
    for (Vec2& v : loop) v *= options.scale;
    if (signed_area(loop) < 0.0) std::reverse(loop.begin(), loop.end());
    (depth == 0 ? outline.material : outline.holes).push_back(std::move(loop));
  }
  return outline;
}

}  // namespace periflex
