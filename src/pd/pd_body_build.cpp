// PdBody::build: particles on the grid, bonds to the neighbours within the horizon (notches cut,
// partial volumes weighed), the material law's coefficients, and the region loads.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/parallel_chunks.h"
#include "pd/block_materials.h"
#include "pd/cloud_grid.h"
#include "pd/neighbor_search.h"
#include "pd/pd_body_impl.h"
#include "pd/pd_material.h"

namespace periflex {

namespace {

// Largest grid a body may request; above it set-up refuses before allocating anything.
constexpr double kMaxParticles = 2e7;

SourceLocation with_key(SourceLocation where, const std::string& key) {
  where.key = where.key.empty() ? key : where.key + "." + key;
  return where;
}

// Partial-volume factor of the neighbour at grid offset (a, b): without the correction 1
// inside the horizon; with it the exact fraction of its cell inside the horizon disc
// (cells whose centre lies beyond delta + dx/2 hold under 1% and are left out).
class PartialVolumes {
 public:
  explicit PartialVolumes(const FlexBodyDef& def) {
    const double ratio = def.horizon_ratio;
    size_ = static_cast<int>(std::ceil(ratio + 0.5)) + 1;
    table_.assign(size_ * size_, 0.0);
    for (int a = 0; a < size_; ++a) {
      for (int b = 0; b < size_; ++b) table_[a * size_ + b] = fraction(a, b, def.partial_volume_correction, ratio);
    }
  }
  double operator()(int a, int b) const {
    a = std::abs(a);
    b = std::abs(b);
    return a < size_ && b < size_ ? table_[a * size_ + b] : 0.0;
  }
  // The factor of a neighbour off the grid at (a, b) spacings, from the same formula as the grid's
  // table (whose entries it reproduces at whole offsets); |a|, |b| so both directions agree.
  static double fraction(double a, double b, bool corrected, double ratio) {
    a = std::abs(a);
    b = std::abs(b);
    const double r2 = a * a + b * b;
    if (!corrected) return r2 <= ratio * ratio * (1 + 1e-12) ? 1.0 : 0.0;
    if (r2 < (ratio + 0.5) * (ratio + 0.5) * (1 - 1e-12)) return cell_fraction_in_disc(a, b, ratio);
    return 0.0;
  }

 private:
  int size_ = 0;
  std::vector<double> table_;  // by (|a|, |b|)
};

// Bonds to every neighbour with a positive weight that no notch cuts. k0 receives each bond's
// stiffness before any correction, nx2 the squared x-component of its unit vector.
// Reference lengths come from the integer grid offsets, so both directions hold identical values.
// Rows are judged and filled on the team's threads in two passes (which candidates stay, then
// their values at their places after a prefix sum of the counts): each row's bonds come out in
// the same order as one thread would make them, so the bonds are the same bits on any count.
void make_bonds(PdBody::Impl& m, const ParticleMaterials& materials, std::vector<double>& k0, std::vector<double>& nx2) {
  const FlexBodyDef& def = m.def;
  const PartialVolumes volume_fraction(def);
  BondStore& bonds = m.bonds;
  // neighbours within the horizon, plus the half cell the partial-volume band reaches
  const double reach = def.partial_volume_correction ? m.delta + 0.5 * m.dx : m.delta;
  const NeighborList nl = find_neighbors(m.grid.x, m.grid.y, reach * (1 + 1e-9));
  const int count = m.n();
  const double v = m.volume.front();
  // a candidate's offset (in spacings), its partial volume and its influence: on the grid from
  // the whole grid offset, off it from the positions (x_j - x_i is exactly -(x_i - x_j), so both
  // directions of a bond hold the same bits)
  struct Offset {
    double di, dj;
    double r2, beta, w;
  };
  const bool on_grid = m.grid.on_grid;
  const bool graded = !m.grid.volume.empty();  // particles of unequal volumes
  auto offset_of = [&](int i, int32_t j) {
    Offset o;
    if (on_grid) {
      const int di = m.grid.ix[j] - m.grid.ix[i], dj = m.grid.iy[j] - m.grid.iy[i];
      o.di = di;
      o.dj = dj;
      o.r2 = o.di * o.di + o.dj * o.dj;
      o.beta = volume_fraction(di, dj);
      o.w = influence(def.influence, m.dx * std::sqrt(o.r2), m.delta);
      return o;
    }
    const double ex = m.grid.x[j] - m.grid.x[i], ey = m.grid.y[j] - m.grid.y[i];
    o.di = ex / m.dx;
    o.dj = ey / m.dx;
    o.r2 = o.di * o.di + o.dj * o.dj;
    o.beta = PartialVolumes::fraction(o.di, o.dj, def.partial_volume_correction, def.horizon_ratio);
    o.w = influence(def.influence, std::sqrt(ex * ex + ey * ey), m.delta);
    return o;
  };

  // pass 1: which candidates stay (a positive weight, no notch across), and the weight notches cut
  std::vector<uint8_t> keep(nl.col.size(), 0);
  std::vector<double> notch_weight(count, 0.0);
  bonds.row.assign(count + 1, 0);
  parallel_chunks(count, [&](int64_t, int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      int64_t kept = 0;
      for (int64_t b = nl.row[i]; b < nl.row[i + 1]; ++b) {
        const int32_t j = nl.col[b];
        const Offset o = offset_of(static_cast<int>(i), j);
        if (o.beta <= 0.0 || o.w <= 0.0) continue;
        const Vec2 pi(m.grid.x[i], m.grid.y[i]), pj(m.grid.x[j], m.grid.y[j]);
        bool cut = false;
        for (const NotchDef& notch : def.notches)
          cut = cut || notch_cuts_bond(pi, pj, notch.p1, notch.p2, 1e-9 * m.dx * m.dx);
        if (cut) {
          notch_weight[i] += o.beta;  // counted as broken when the scene asks for it
          continue;
        }
        keep[b] = 1;
        ++kept;
      }
      bonds.row[i + 1] = kept;
    }
  });
  for (int i = 0; i < count; ++i) bonds.row[i + 1] += bonds.row[i];

  // pass 2: the kept bonds' values at their places
  const size_t total = static_cast<size_t>(bonds.row[count]);
  bonds.neighbor.resize(total);
  bonds.length_class.assign(total, 0);
  if (!on_grid) {
    bonds.bond_inv_length.resize(total);
    m.bond_weight.resize(total);
  }
  bonds.grid_spacing = m.dx;
  k0.resize(total);
  nx2.resize(total);
  parallel_chunks(count, [&](int64_t, int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      int64_t at = bonds.row[i];
      for (int64_t b = nl.row[i]; b < nl.row[i + 1]; ++b) {
        if (!keep[b]) continue;
        const int32_t j = nl.col[b];
        const Offset o = offset_of(static_cast<int>(i), j);
        bonds.neighbor[at] = j;
        if (on_grid) {
          bonds.length_class[at] = static_cast<uint8_t>(o.r2);
        } else {
          const double ex = m.grid.x[j] - m.grid.x[i], ey = m.grid.y[j] - m.grid.y[i];
          bonds.bond_inv_length[at] = 1.0 / std::sqrt(ex * ex + ey * ey);
          m.bond_weight[at] = o.beta;
        }
        // V_i V_j as one product: the same bits in both directions
        k0[at] = graded ? m.c * o.w * o.beta * (m.volume[i] * m.volume[j]) : m.c * o.w * o.beta * v * v;
        // materials by block: the bond's two halves in series
        if (!materials.empty()) k0[at] *= series_modulus(materials.modulus_ratio[i], materials.modulus_ratio[j]);
        nx2[at] = o.di * o.di / o.r2;
        ++at;
      }
    }
  });
  // the partial volume of each length class, as the last bond of that class in row order has it
  // (the factor depends on the offset's length only, so one entry per length class); off the
  // grid each bond keeps its own
  for (int i = on_grid ? count - 1 : -1; i >= 0; --i)
    for (int64_t b = bonds.row[i + 1] - 1; b >= bonds.row[i]; --b) {
      const size_t length_class = bonds.length_class[b];
      if (m.class_weight.size() <= length_class) m.class_weight.resize(length_class + 1, -1.0);
      if (m.class_weight[length_class] < 0.0) m.class_weight[length_class] = offset_of(i, bonds.neighbor[b]).beta;
    }
  for (double& weight : m.class_weight) weight = std::max(weight, 0.0);
  // the damage pass weighs bonds by their length class: the initial weights are summed from
  // the same table, so a particle with every bond intact has damage exactly 0
  m.initial_weight.assign(count, 0.0);
  parallel_chunks(count, [&](int64_t, int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      double sum = 0.0;
      for (int64_t b = bonds.row[i]; b < bonds.row[i + 1]; ++b)
        sum += on_grid ? m.class_weight[bonds.length_class[b]] : m.bond_weight[b];
      m.initial_weight[i] = sum + (def.damage == FlexBodyDef::Damage::kIncludeNotch ? notch_weight[i] : 0.0);
    }
  });
  bonds.make_length_table();
  bonds.make_offsets();
}

// Region loads: imposed motions become prescribed coordinates, tractions and body forces
// become per-particle force scales.
void collect_loads(PdBody::Impl& m) {
  for (const RegionLoadDef& load : m.def.loads) {
    std::vector<int> inside;
    for (int i = 0; i < m.n(); ++i)
      if (load.region.contains(Vec2(m.grid.x[i], m.grid.y[i]))) inside.push_back(i);
    if (inside.empty()) {
      m.warnings.push_back("load '" + load.name + "' selects no particle");
      continue;
    }
    switch (load.kind) {
      case RegionLoadDef::Kind::kPrescribedVelocity:
      case RegionLoadDef::Kind::kPrescribedDisplacement: {
        const bool velocity = load.kind == RegionLoadDef::Kind::kPrescribedVelocity;
        for (int i : inside) {
          for (int comp = 0; comp < 2; ++comp) {
            const std::optional<TimeFunction>& f = comp == 0 ? load.fx : load.fy;
            if (!f) continue;
            PrescribedCoordinate pc;
            pc.coordinate = m.offset + 2 * i + comp;
            pc.reference = m.reference[2 * i + comp];
            pc.displacement = velocity ? f->antiderivative() : *f;
            m.prescribed.push_back(pc);
          }
        }
        break;
      }
      case RegionLoadDef::Kind::kTraction: {
        // traction [Pa] on the boundary the region covers: total force = traction * length * t,
        // length = particles * dx / layers, layers = particle rows across the region (the
        // smaller of its numbers of distinct grid columns and rows)
        std::set<int32_t> cols, rows;
        for (int i : inside) {
          cols.insert(m.grid.ix[i]);
          rows.insert(m.grid.iy[i]);
        }
        const double layers = static_cast<double>(std::min(cols.size(), rows.size()));
        m.loads.push_back({inside, m.def.thickness * m.dx / layers, load.fx, load.fy, {}});
        break;
      }
      case RegionLoadDef::Kind::kBodyForce: {
        // force density times each particle's volume (unequal on a graded point file)
        AppliedLoad applied{inside, m.volume.front(), load.fx, load.fy, {}};
        if (!m.grid.volume.empty())
          for (int i : inside) applied.weights.push_back(m.volume[i] / m.volume.front());
        m.loads.push_back(std::move(applied));
        break;
      }
    }
  }
}

}  // namespace

// The notch is a closed segment: a bond that passes exactly through one of its end points is cut,
// as it would be by a notch reaching a hair further. The bond's own ends must lie strictly on
// either side of the notch's line: a bond from a particle sitting on the notch line is not cut (it
// only touches). Within `tolerance` (an area: a billionth of a grid cell) a signed area counts as zero.
bool notch_cuts_bond(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double tolerance) {
  const double o3 = cross(d - c, a - c), o4 = cross(d - c, b - c);  // bond ends against the notch line
  const bool ends_apart = (o3 > tolerance && o4 < -tolerance) || (o3 < -tolerance && o4 > tolerance);
  if (!ends_apart) return false;
  const double o1 = cross(b - a, c - a), o2 = cross(b - a, d - a);  // notch ends against the bond line
  return std::min(o1, o2) <= tolerance && std::max(o1, o2) >= -tolerance;
}

std::unique_ptr<PdBody> PdBody::build(const FlexBodyDef& def, int coordinate_offset) {
  auto m = std::make_unique<Impl>();
  m->def = def;
  m->offset = coordinate_offset;
  const PdMaterialDef& mat = def.material;

  // reject what cannot be built, naming the key
  auto require = [&](bool ok, const std::string& key, const std::string& message) {
    if (!ok) throw InputError(with_key(def.where, key), "flex body '" + def.name + "': " + message);
  };
  require(def.shape.kind == ShapeDef::Kind::kBox || def.shape.kind == ShapeDef::Kind::kCircle ||
              def.shape.kind == ShapeDef::Kind::kPolygon || def.shape.kind == ShapeDef::Kind::kBar ||
              def.shape.kind == ShapeDef::Kind::kBoolean,
          "shape", "needs a box, circle, polygon, bar or combined shape");
  require(def.grid_spacing > 0.0, "grid_spacing", "grid_spacing must be positive");
  require(def.thickness > 0.0, "thickness", "thickness must be positive");
  require(def.horizon_ratio >= 1.0, "horizon_ratio", "horizon_ratio must be at least 1");
  // bonds store their squared grid offset in 8 bits
  require(def.horizon_ratio <= kMaxHorizonRatio, "horizon_ratio",
          "horizon_ratio must be at most " + std::to_string(int(kMaxHorizonRatio)));
  require(mat.youngs_modulus > 0.0, "material.youngs_modulus", "youngs_modulus must be positive");
  require(mat.density > 0.0, "material.density", "density must be positive");
  require(mat.fracture_energy >= 0.0, "material.fracture_energy", "fracture_energy must not be negative");
  require(mat.critical_stretch >= 0.0, "material.critical_stretch", "critical_stretch must not be negative");

  // refuse huge grids before allocating anything
  const double estimate = estimated_particle_count(def.shape, def.grid_spacing);
  if (estimate > kMaxParticles) {
    std::ostringstream msg;
    msg << "flex body '" << def.name << "': grid_spacing " << def.grid_spacing << " needs about "
        << static_cast<long long>(estimate) << " particles, more than the limit of "
        << static_cast<long long>(kMaxParticles) << "; raise grid_spacing";
    throw InputError(with_key(def.where, "grid_spacing"), msg.str());
  }

  // particles on the grid
  m->dx = def.grid_spacing;
  m->delta = def.horizon_ratio * def.grid_spacing;
  m->grid = body_particles(def);
  const int n = m->n();
  require(n > 0, "shape", "the shape holds no particle at this grid_spacing");
  const double v = m->dx * m->dx * def.thickness;
  m->reference.resize(2 * n);
  for (int i = 0; i < n; ++i) {
    m->reference[2 * i] = m->grid.x[i];
    m->reference[2 * i + 1] = m->grid.y[i];
  }
  // every particle the grid cell's volume, or (a graded point file) its own
  if (m->grid.volume.empty()) {
    m->volume.assign(n, v);
    m->mass.assign(n, mat.density * v);
  } else {
    m->volume = m->grid.volume;
    m->mass.resize(n);
    for (int i = 0; i < n; ++i) m->mass[i] = mat.density * m->volume[i];
  }

  // material constants: the micromodulus every law scales its bonds by, and the law itself
  m->c = periflex::micromodulus(mat.youngs_modulus, def.thickness, m->delta, mat.plane_strain);
  m->fracture = def.fracture;
  m->law = make_material_law(def, m->delta, v, m->warnings);
  m->s0 = m->law->critical_stretch();
  // materials by block: each particle's density and critical stretch (the body's s0 the smallest)
  const ParticleMaterials materials = particle_materials(def, n, m->delta, m->s0);
  if (!materials.empty()) {
    require(def.material.model == PdMaterialDef::Model::kBondBased, "material.model",
            "materials by block need the bond-based law");
    for (int i = 0; i < n; ++i) m->mass[i] = materials.density[i] * m->volume[i];
    m->s0 = *std::min_element(materials.critical_stretch.begin(), materials.critical_stretch.end());
  }

  // no-fail flags, bonds, the law's coefficients, loads
  m->no_fail = body_no_fail(def, m->grid);
  std::vector<double> k0, nx2;
  make_bonds(*m, materials, k0, nx2);
  const double* volumes = m->grid.volume.empty() ? nullptr : m->volume.data();
  const double* moduli = materials.empty() ? nullptr : materials.modulus_ratio.data();
  m->law->set_coefficients(LawSetup{def, m->grid, m->c, m->delta, v, volumes, k0, nx2, m->no_fail_flags(), moduli},
                           m->bonds);
  set_break_stretches(materials, m->bonds);
  m->live = BondState::intact(m->bonds);
  collect_loads(*m);

  m->bond_damping = def.bond_damping;
  m->global_damping = def.global_damping;
  return std::unique_ptr<PdBody>(new PdBody(std::move(m)));
}

}  // namespace periflex
