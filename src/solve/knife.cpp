// The knife: the bonds a drawn segment crosses are cut, their energy booked as released by
// fracture.
#include "solve/simulation_impl.h"

#include <vector>

namespace periflex {

long Simulation::cut_bonds(const Vec2& a, const Vec2& b, const std::vector<float>& drawn_x,
                           const std::vector<float>& drawn_y) {
  Impl& s = *impl_;
  long cut = 0;
  size_t first = 0;
  std::vector<double> positions;
  for (auto& flex : s.model->flex_bodies) {
    // this body's particles as the caller shows them, when it gave every particle
    const size_t n = static_cast<size_t>(flex->particle_count());
    positions.clear();
    if (drawn_x.size() == drawn_y.size() && first + n <= drawn_x.size()) {
      for (size_t i = first; i < first + n; ++i) positions.insert(positions.end(), {drawn_x[i], drawn_y[i]});
    }
    first += n;
    const FractureUpdate update = flex->cut_bonds(s.state.q, positions, a, b);
    s.fracture_energy += update.energy_released;
    s.broken_bonds += update.bonds_broken;
    cut += update.bonds_broken;
    // the integrator's stored forces no longer hold
    if (update.forces_stale) s.integrator->reset();
  }
  return cut;
}

}  // namespace periflex
