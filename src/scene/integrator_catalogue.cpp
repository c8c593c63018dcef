#include "scene/integrator_catalogue.h"

#include <stdexcept>

namespace periflex {

const std::vector<IntegratorTraits>& integrator_catalogue() {
  // the symplectic ones evaluate forces only at accepted positions, so their bonds break there;
  // stage vectors: rk4 keeps 4 stages of (q, qd) per coordinate pair (96 bytes a particle),
  // dopri54 its 7 stages and error estimate (272), hht its Newton vectors (96) and a tangent
  // of 480 bytes per stored neighbour
  static const std::vector<IntegratorTraits> catalogue = [] {
    std::vector<IntegratorTraits> rows(5);
    IntegratorTraits& euler = rows[0];
    euler.kind = IntegratorKind::kSymplecticEuler;
    euler.name = "symplectic_euler";
    euler.order = 1;
    euler.is_symplectic = true;
    euler.breaks_in_evaluation = true;

    IntegratorTraits& verlet = rows[1];
    verlet.kind = IntegratorKind::kVerlet;
    verlet.name = "verlet";
    verlet.order = 2;
    verlet.is_symplectic = true;
    verlet.breaks_in_evaluation = true;
    verlet.closing_kick = 0.5;
    verlet.keeps_end_acceleration = true;

    IntegratorTraits& rk4 = rows[2];
    rk4.kind = IntegratorKind::kRk4;
    rk4.name = "rk4";
    rk4.order = 4;
    rk4.stage_bytes_per_particle = 96.0;

    IntegratorTraits& dopri = rows[3];
    dopri.kind = IntegratorKind::kDopri54;
    dopri.name = "dopri54";
    dopri.order = 5;
    dopri.is_adaptive = true;
    dopri.stage_bytes_per_particle = 272.0;

    IntegratorTraits& hht = rows[4];
    hht.kind = IntegratorKind::kHht;
    hht.name = "hht";
    hht.order = 2;
    hht.is_explicit = false;
    hht.stage_bytes_per_particle = 96.0;
    hht.tangent_bytes_per_neighbor = 480.0;
    return rows;
  }();
  return catalogue;
}

const IntegratorTraits* find_integrator(std::string_view name) {
  for (const IntegratorTraits& row : integrator_catalogue()) {
    if (row.name == name) return &row;
  }
  return nullptr;
}

const IntegratorTraits& integrator_traits(IntegratorKind kind) {
  for (const IntegratorTraits& row : integrator_catalogue()) {
    if (row.kind == kind) return row;
  }
  throw std::logic_error("an integrator kind without a row in the catalogue");
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const IntegratorTraits& row : integrator_catalogue()) names.push_back(row.name);
  return names;
}

}  // namespace periflex
