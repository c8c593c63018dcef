#include "solve/held_rotations.h"

#include <cmath>
#include <map>

#include "core/error.h"

namespace periflex {

namespace {

// Largest |d Phi / d q_c| over every constraint row at (q, t).
double column_size(const SystemModel& model, const Eigen::VectorXd& q, double t, int c) {
  Triplets entries;
  for (const auto& block : model.constraints) block.constraint->jacobian(q, t, block.first_row, entries);
  // entries of one row may come in parts (two points of the same body): sum them per row
  std::map<int, double> by_row;
  for (const auto& e : entries)
    if (e.col() == c) by_row[e.row()] += e.value();
  double worst = 0.0;
  for (const auto& [row, value] : by_row) worst = std::max(worst, std::abs(value));
  return worst;
}

// A location under the body's table, for the key the user would change.
SourceLocation body_key(const BodyDef& body, const std::string& key) {
  SourceLocation where = body.where;
  where.key = (where.key.empty() ? "body." + body.name : where.key) + "." + key;
  return where;
}

}  // namespace

std::vector<int> find_held_rotations(const SystemModel& model, double t) {
  std::vector<int> held;
  const double tiny = 1e-12 * std::max(1.0, model.length_scale);
  for (size_t k = 0; k < model.bodies.size(); ++k) {
    const int c = 3 * static_cast<int>(k) + 2;
    if (model.mass[c] > 0.0 || model.is_prescribed[c]) continue;
    // the column at the initial angle and at two others (a first-degree trigonometric
    // polynomial in phi vanishes everywhere when its derivative does at two such angles)
    Eigen::VectorXd q = model.q0;
    bool zero = true;
    for (double turn : {0.0, 1.0, 2.0}) {
      q[c] = model.q0[c] + turn;
      if (column_size(model, q, t, c) > tiny) zero = false;
    }
    if (!zero) continue;
    const BodyDef& body = model.bodies[k];
    if (model.qd0[c] != 0.0)
      throw InputError(body_key(body, "angular_velocity"),
                       "body '" + body.name + "' has zero inertia and no constraint fixes its rotation, so its "
                       "angle is held at its initial value; its angular_velocity must be 0");
    // no force element may turn it: try the initial angle and two others (a spring at its free
    // length pulls only once the point it holds has moved)
    for (const auto& force : model.forces) {
      for (double turn : {0.0, 1.0, 2.0}) {
        q[c] = model.q0[c] + turn;
        Eigen::VectorXd g = Eigen::VectorXd::Zero(model.coordinate_count);
        force->add_forces(q, model.qd0, t, g);
        if (std::abs(g[c]) > tiny)
          throw InputError(body.where, "'" + force->name() + "' puts a torque on body '" + body.name +
                                           "', which has zero inertia and a rotation no constraint fixes: "
                                           "its angular acceleration would be infinite; give it inertia, or "
                                           "apply the load at its origin");
      }
    }
    held.push_back(c);
  }
  return held;
}

void check_held_rotations(const SystemModel& model, const std::vector<int>& held, const Eigen::VectorXd& g,
                          double t) {
  const double tiny = 1e-12 * std::max(1.0, model.length_scale);
  for (int c : held) {
    if (std::abs(g[c]) <= tiny) continue;
    const std::string& name = model.bodies[c / 3].name;
    throw NumericalError({"torque on a zero-inertia body", -1, t,
                          "a force element turns body '" + name + "', which has zero inertia and a rotation no "
                          "constraint fixes (held at its initial angle): its angular acceleration is infinite",
                          "give body '" + name + "' inertia, or apply the load at its origin"});
  }
}

}  // namespace periflex
