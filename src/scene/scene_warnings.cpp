#include "scene/scene_warnings.h"

#include <algorithm>
#include <sstream>

#include "scene/grid_scan.h"
#include "scene/toml_reader.h"

namespace periflex {

namespace {

std::string point_text(const Vec2& p) {
  std::ostringstream out;
  out << '(' << format_number(p.x()) << ", " << format_number(p.y()) << ')';
  return out.str();
}

std::string located(SourceLocation where, const std::string& key, const std::string& message) {
  where.key = key;
  return format_location(where) + ": " + message;
}

// Particles of `flex` inside every shape of `inside`.
long particles_inside(const FlexBodyDef& flex, const std::vector<ShapeDef>& inside) {
  // particles given one by one are tested one by one
  if (flex.particles) {
    long count = 0;
    for (long k = 0; k < flex.particles->size(); ++k) {
      const Vec2 p(flex.particles->x[k], flex.particles->y[k]);
      count += std::all_of(inside.begin(), inside.end(), [&](const ShapeDef& s) { return s.contains(p); }) ? 1 : 0;
    }
    return count;
  }
  return count_grid_cells(flex.shape, flex.holes, grid_frame(flex.shape, flex.grid_spacing), inside);
}

ShapeDef disc(const Vec2& center, double radius) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::kCircle;
  s.center = center;
  s.radius = radius;
  return s;
}

// Axis-aligned bounds of two shapes meet.
bool bounds_overlap(const ShapeDef& a, const ShapeDef& b) {
  Vec2 alo, ahi, blo, bhi;
  shape_bounds(a, alo, ahi);
  shape_bounds(b, blo, bhi);
  return alo.x() <= bhi.x() && blo.x() <= ahi.x() && alo.y() <= bhi.y() && blo.y() <= ahi.y();
}

constexpr int kMaxOverlapWarnings = 10;

const FlexBodyDef* find_flex(const SceneDef& scene, const std::string& name) {
  for (const FlexBodyDef& flex : scene.flex_bodies)
    if (flex.name == name) return &flex;
  return nullptr;
}

}  // namespace

std::vector<std::string> scene_warnings(const SceneDef& scene) {
  std::vector<std::string> out;
  for (const FlexBodyDef& flex : scene.flex_bodies) {
    const double horizon = flex.horizon_ratio * flex.grid_spacing;
    const std::string base = "flex_body." + flex.name;

    // a notch cuts bonds only where particles lie within a horizon of it
    for (size_t k = 0; k < flex.notches.size(); ++k) {
      const NotchDef& notch = flex.notches[k];
      ShapeDef band;
      band.kind = ShapeDef::Kind::kBar;
      band.p1 = notch.p1;
      band.p2 = notch.p2;
      band.radius = horizon;
      if (particles_inside(flex, {band}) == 0)
        out.push_back(located(flex.where, base + ".notches." + std::to_string(k),
                              "warning: the notch from " + point_text(notch.p1) + " to " + point_text(notch.p2) +
                                  " lies outside flexible body '" + flex.name + "' (no particle within a horizon of "
                                  "it): it cuts no bond"));
    }

    // a load on no particle does nothing
    for (const RegionLoadDef& load : flex.loads)
      if (particles_inside(flex, {load.region}) == 0)
        out.push_back(located(load.where, base + ".load." + load.name + ".region",
                              "warning: load '" + load.name + "' covers no particle of flexible body '" + flex.name +
                                  "': it does nothing"));
  }

  // a probe on a flexible body follows its nearest particle, however far
  for (const ProbeDef& probe : scene.probes) {
    const FlexBodyDef* flex = find_flex(scene, probe.body);
    if (flex == nullptr) continue;
    const double horizon = flex->horizon_ratio * flex->grid_spacing;
    if (particles_inside(*flex, {disc(probe.point, horizon)}) == 0)
      out.push_back(located(probe.where, "probe." + probe.name + ".point",
                            "warning: probe '" + probe.name + "' at " + point_text(probe.point) +
                                " is more than a horizon (" + format_number(horizon) +
                                " m) from every particle of '" + flex->name + "'; it will follow the nearest one"));
  }

  // two attachments holding the same particles (an empty one is refused when the model is built);
  // only pairs whose bounds meet are scanned, and a few reports say enough
  int overlaps = 0;
  for (size_t a = 0; a < scene.attachments.size(); ++a) {
    const AttachmentDef& first = scene.attachments[a];
    const FlexBodyDef* flex = find_flex(scene, first.flex_body);
    if (flex == nullptr) continue;
    for (size_t b = a + 1; b < scene.attachments.size() && overlaps < kMaxOverlapWarnings; ++b) {
      const AttachmentDef& second = scene.attachments[b];
      if (second.flex_body != first.flex_body || !bounds_overlap(first.region, second.region)) continue;
      const long shared = particles_inside(*flex, {first.region, second.region});
      if (shared > 0 && ++overlaps <= kMaxOverlapWarnings)
        out.push_back(located(second.where, "attachment." + second.name + ".region",
                              "warning: attachments '" + first.name + "' and '" + second.name + "' both hold " +
                                  std::to_string(shared) + " particles of '" + flex->name +
                                  "'; a particle held by two bodies over-constrains the model"));
    }
  }
  return out;
}

}  // namespace periflex
