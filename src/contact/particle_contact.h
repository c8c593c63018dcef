// Short-range repulsion between particles (Silling & Askari 2005; LAMMPS's peri pair styles):
// two particles of the listed flexible bodies that are not joined by an intact bond and come
// closer than d = distance_ratio * dx (the mean grid spacing of their bodies) repel with
//   F = max(0, k (d - r) + c (d - r)_dot)   along the line between them,
// k = 15 c V_i V_j / delta from the micromodulus unless given, c from the coefficient of
// restitution with the pair's reduced mass. So crack faces that close and fragments, of one
// body or of two, push apart instead of passing through each other.
//
// Candidate pairs come from the bodies' cell-grid neighbour search (pd/neighbor_search.h)
// with radius d + skin, bonded pairs included with their bond, kept until a particle has moved
// half the skin (a Verlet list): a bond that breaks makes its pair a contact pair at once,
// without a new search. Each particle gathers its own force from its row of candidates, and both
// rows of a pair compute bit-identical, opposite forces: the same result on any thread count
// and momentum conserved to round-off.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "contact/contact_element.h"
#include "pd/neighbor_search.h"
#include "pd/pd_body.h"

namespace periflex {

class ParticleContact final : public ContactElement {
 public:
  ParticleContact(const ContactDef& def, const std::vector<const PdBody*>& bodies);

  void add_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t, Eigen::VectorXd& g) override;
  double add_forces_dissipating(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t,
                                Eigen::VectorXd& g) override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  double dissipation_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  // The candidate pairs of the Verlet list at q: a pair that comes into contact within the skin.
  bool add_coupling(const Eigen::VectorXd& q, SparsityPattern& pattern) const override;

  ContactTotals totals(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  double critical_time_step() const override;
  void collect_points(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                      std::vector<ContactPoint>& out) const override;

  void save_cache(ContactCache& out) const override;
  // Throws std::invalid_argument for a list of other particles.
  void restore_cache(const ContactCache& in) override;

  // Times the candidate list was built (the first build included), for tests.
  long rebuilds() const { return rebuilds_; }

 private:
  struct Sums {
    double energy = 0.0, dissipation = 0.0, normal_force = 0.0;
    long active = 0;
  };
  // Rebuilds the candidate pairs when a particle has moved half the skin since the last build.
  void refresh(const Eigen::VectorXd& q) const;
  // The bond (broken or not) joining particles a and b (global numbering) in their body's
  // store, the copy in the lower particle's row; -1 when none does.
  int64_t bond_between(int a, int b) const;
  // candidate_bond_ (and candidate_distance_) for the candidate list.
  void find_bonds() const;
  // The contact distance of particles a and b: d, except within one body off the grid, where two
  // particles may start closer than d: at most distance_ratio times their reference distance
  // there (Littlewood's short-range forces), so neither a body at rest nor a bond just broken
  // pushes its particles apart. On the grid no bonded pair starts closer than one spacing.
  double pair_distance(int a, int b, double d) const;
  // One pass at q (and qd when given): forces into g when given, each pair's contact into
  // points when given (then on one thread), and the sums over pairs.
  Sums sweep(const Eigen::VectorXd& q, const Eigen::VectorXd* qd, Eigen::VectorXd* g,
             std::vector<ContactPoint>* points = nullptr) const;

  std::vector<const PdBody*> bodies_;
  // particles of all listed bodies, numbered body after body
  std::vector<int> coordinate_, body_of_, local_;
  std::vector<double> mass_;
  std::vector<uint8_t> off_grid_;  // per body: 1 when its particles lie off the grid
  double distance_ = 0.0, skin_ = 0.0, zeta_ = 0.0, distance_ratio_ = 0.0;
  double lightest_ = 0.0;

  // the Verlet list and the state it was built at
  mutable NeighborList candidates_;
  mutable std::vector<int64_t> candidate_bond_;  // per candidate: bond_between, -1 if none
  mutable std::vector<double> candidate_distance_;  // per candidate: pair_distance; empty: all distance_
  mutable std::vector<double> built_at_;  // x, y per particle
  mutable long rebuilds_ = 0;
  mutable std::vector<double> x_, y_;
};

}  // namespace periflex
