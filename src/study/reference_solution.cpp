#include "study/reference_solution.h"

#include <cmath>
#include <optional>

#include "core/error.h"
#include "core/vec2.h"
#include "study/elliptic.h"

namespace periflex {

namespace {

SourceLocation scene_location(const SceneDef& scene, const std::string& key) {
  SourceLocation where;
  where.file = scene.path;
  where.key = key;
  return where;
}

int body_index(const SceneDef& scene, const std::string& name) {
  for (size_t k = 0; k < scene.bodies.size(); ++k)
    if (scene.bodies[k].name == name) return static_cast<int>(k);
  return -1;
}

// A joint between bodies a and b (either order), its points seen from a and from b.
struct JointEnds {
  const JointDef* joint = nullptr;
  Vec2 point_a, point_b;
  Vec2 axis_a;
};

std::optional<JointEnds> find_joint(const SceneDef& scene, JointDef::Kind kind, const std::string& a,
                                    const std::string& b) {
  for (const JointDef& j : scene.joints) {
    if (j.kind != kind) continue;
    if (j.body_i == a && j.body_j == b) return JointEnds{&j, j.point_i, j.point_j, j.axis_i};
    if (j.body_i == b && j.body_j == a) return JointEnds{&j, j.point_j, j.point_i, j.axis_j};
  }
  return std::nullopt;
}

// Probe positions from a pose per body (x, y, phi), for the probes on rigid bodies.
struct Pose {
  Vec2 r = Vec2::Zero();
  double phi = 0.0;
};

std::vector<int> probe_bodies(const SceneDef& scene, const std::string& reference) {
  std::vector<int> out;
  for (const ProbeDef& p : scene.probes) {
    const int k = body_index(scene, p.body);
    if (k < 0)
      throw InputError(p.where, reference + " describes rigid bodies only; probe '" + p.name +
                                    "' is on '" + p.body + "'");
    out.push_back(k);
  }
  return out;
}

std::vector<double> probes_from_poses(const SceneDef& scene, const std::vector<int>& bodies,
                                      const std::vector<Pose>& poses) {
  std::vector<double> out;
  out.reserve(2 * scene.probes.size());
  for (size_t p = 0; p < scene.probes.size(); ++p) {
    const Pose& pose = poses[bodies[p]];
    const Vec2 x = pose.r + rotation(pose.phi) * scene.probes[p].point;
    out.push_back(x.x());
    out.push_back(x.y());
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
class PendulumExact final : public ReferenceSolution {
 public:
  explicit PendulumExact(const SceneDef& scene) : scene_(scene) {
    const std::string name = "pendulum_exact";
    if (scene.bodies.size() != 1 || !scene.flex_bodies.empty() || !scene.drivers.empty() ||
        !scene.forces.empty() || scene.joints.size() != 1)
      throw InputError(scene_location(scene, "study.reference"),
                       name + " needs a scene of one rigid body, one revolute joint to the ground, "
                              "no drivers, forces or flexible bodies");
    const BodyDef& body = scene.bodies[0];
    const auto pin = find_joint(scene, JointDef::Kind::kRevolute, "ground", body.name);
    if (!pin) throw InputError(scene.joints[0].where, name + " needs a revolute joint between ground and '" + body.name + "'");
    if (body.velocity.norm() != 0.0 || body.angular_velocity != 0.0)
      throw InputError(body.where, name + " describes a release from rest; set velocity and angular_velocity to 0");
    const double g = scene.gravity.norm();
    if (g <= 0.0 || body.mass <= 0.0)
      throw InputError(body.where, name + " needs gravity and a positive mass");
    pivot_ = pin->point_a;  // global on the ground
    local_pin_ = pin->point_b;
    phi0_ = body.angle;
    // the body must start on its pin (consistent initial position)
    const Vec2 d = body.position - pivot_;
    if ((body.position + rotation(phi0_) * local_pin_ - pivot_).norm() > 1e-9 * (1.0 + d.norm()))
      throw InputError(body.where, name + ": the body's pin point does not start at the ground pin");
    const double arm = d.norm();
    if (arm <= 0.0) throw InputError(body.where, name + ": the centre of mass lies on the pin");
    // theta from the direction of gravity to the arm (pin -> centre of mass)
    const Vec2 down = scene.gravity / g;
    theta0_ = std::atan2(cross(down, d), down.dot(d));
    k_ = std::sin(0.5 * theta0_);
    if (std::abs(k_) >= 1.0) throw InputError(body.where, name + ": the pendulum starts inverted");
    omega0_ = std::sqrt(body.mass * g * arm / (body.inertia + body.mass * arm * arm));
    bodies_ = probe_bodies(scene, name);
  }

  std::vector<double> probe_values(double t) const override {
    const JacobiValues j = jacobi_elliptic(omega0_ * t, k_ * k_);
    const double theta = 2.0 * std::asin(k_ * j.cn / j.dn);
    Pose pose;
    pose.phi = phi0_ + (theta - theta0_);
    pose.r = pivot_ - rotation(pose.phi) * local_pin_;
    return probes_from_poses(scene_, bodies_, {pose});
  }

  std::string describe() const override {
    return "exact large-amplitude pendulum (Jacobi elliptic cd), amplitude " + std::to_string(theta0_) +
           " rad, period " + std::to_string(4.0 * elliptic_k(k_ * k_) / omega0_) + " s";
  }

 private:
  SceneDef scene_;
  Vec2 pivot_ = Vec2::Zero(), local_pin_ = Vec2::Zero();
  double phi0_ = 0.0, theta0_ = 0.0, k_ = 0.0, omega0_ = 0.0;
  std::vector<int> bodies_;
};

// ---------------------------------------------------------------------------------------------
class SliderCrankExact final : public ReferenceSolution {
 public:
  explicit SliderCrankExact(const SceneDef& scene) : scene_(scene) {
    const std::string name = "slider_crank_exact";
    const auto refuse = [&](const std::string& what) {
      throw InputError(scene_location(scene, "study.reference"), name + " needs " + what);
    };
    if (scene.bodies.size() != 3 || !scene.flex_bodies.empty())
      refuse("a scene of three rigid bodies (crank, rod, slider) and no flexible bodies");
    if (scene.drivers.size() != 1 || scene.drivers[0].kind != DriverDef::Kind::kAbsoluteAngle)
      refuse("one absolute-angle driver on the crank");
    driver_ = &scene_.drivers[0];
    crank_ = body_index(scene, driver_->body_i);
    if (crank_ < 0) refuse("the driver to act on a rigid body");
    const std::string& crank = scene.bodies[crank_].name;
    const auto base = find_joint(scene, JointDef::Kind::kRevolute, "ground", crank);
    if (!base) refuse("a revolute joint between ground and the crank");
    pivot_ = base->point_a;
    crank_pin_ = base->point_b;
    // the rod is the other body pinned to the crank, the slider the body on the translational joint
    for (int k = 0; k < 3; ++k) {
      if (k == crank_) continue;
      if (find_joint(scene, JointDef::Kind::kRevolute, crank, scene.bodies[k].name)) rod_ = k;
      else slider_ = k;
    }
    if (rod_ < 0 || slider_ < 0) refuse("a rod pinned to the crank and a slider");
    const std::string& rod = scene.bodies[rod_].name;
    const std::string& slider = scene.bodies[slider_].name;
    const auto crank_rod = find_joint(scene, JointDef::Kind::kRevolute, crank, rod);
    const auto rod_slider = find_joint(scene, JointDef::Kind::kRevolute, rod, slider);
    const auto guide = find_joint(scene, JointDef::Kind::kTranslational, "ground", slider);
    if (!rod_slider) refuse("a revolute joint between the rod and the slider");
    if (!guide) refuse("a translational joint between ground and the slider");
    crank_end_ = crank_rod->point_a;
    rod_a_ = crank_rod->point_b;
    rod_b_ = rod_slider->point_a;
    slider_pin_ = rod_slider->point_b;
    rod_length_ = (rod_b_ - rod_a_).norm();
    const BodyDef& s = scene.bodies[slider_];
    slider_angle_ = s.angle;
    // the guide axis: global when written on the ground, else on the slider at its initial angle
    axis_ = (guide->joint->body_i == "ground" ? guide->joint->axis_i
                                               : Vec2(rotation(s.angle) * guide->joint->axis_i)).normalized();
    slider_pin0_ = s.position + rotation(s.angle) * slider_pin_;
    // the branch of the loop closure the scene starts on
    const double s0 = 0.0;
    branch_ = 1.0;
    if (std::abs(slider_offset(0.0) - s0) > std::abs(slider_offset_branch(0.0, -1.0) - s0)) branch_ = -1.0;
    bodies_ = probe_bodies(scene, name);
  }

  std::vector<double> probe_values(double t) const override {
    std::vector<Pose> poses(3);
    // crank: driven angle, turning about its ground pin
    const double phi_c = (*driver_).function(t);
    poses[crank_].phi = phi_c;
    poses[crank_].r = pivot_ - rotation(phi_c) * crank_pin_;
    const Vec2 a = poses[crank_].r + rotation(phi_c) * crank_end_;
    // slider: its pin on the guide line at distance l from the crank pin
    const Vec2 b = slider_pin0_ + slider_offset(t) * axis_;
    poses[slider_].phi = slider_angle_;
    poses[slider_].r = b - rotation(slider_angle_) * slider_pin_;
    // rod: from crank pin A to slider pin B
    const Vec2 ab = b - a, local = rod_b_ - rod_a_;
    const double phi_r = std::atan2(ab.y(), ab.x()) - std::atan2(local.y(), local.x());
    poses[rod_].phi = phi_r;
    poses[rod_].r = a - rotation(phi_r) * rod_a_;
    return probes_from_poses(scene_, bodies_, poses);
  }

  std::string describe() const override {
    return "closed-form slider-crank kinematics, rod length " + std::to_string(rod_length_) + " m";
  }

 private:
  double slider_offset(double t) const { return slider_offset_branch(t, branch_); }

  // distance s along the guide with |B0 + s u - A(t)| = l, on the chosen root
  double slider_offset_branch(double t, double branch) const {
    const double phi_c = (*driver_).function(t);
    const Vec2 a = pivot_ - rotation(phi_c) * crank_pin_ + rotation(phi_c) * crank_end_;
    const Vec2 w = slider_pin0_ - a;
    const double half_b = axis_.dot(w), c = w.squaredNorm() - rod_length_ * rod_length_;
    const double disc = half_b * half_b - c;
    if (disc < 0.0) throw std::runtime_error("slider_crank_exact: the mechanism locks (rod too short)");
    return -half_b + branch * std::sqrt(disc);
  }

  SceneDef scene_;
  const DriverDef* driver_ = nullptr;  // into scene_
  int crank_ = -1, rod_ = -1, slider_ = -1;
  Vec2 pivot_ = Vec2::Zero(), crank_pin_ = Vec2::Zero(), crank_end_ = Vec2::Zero();
  Vec2 rod_a_ = Vec2::Zero(), rod_b_ = Vec2::Zero(), slider_pin_ = Vec2::Zero();
  Vec2 axis_ = Vec2::UnitX(), slider_pin0_ = Vec2::Zero();
  double rod_length_ = 0.0, slider_angle_ = 0.0, branch_ = 1.0;
  std::vector<int> bodies_;
};

}  // namespace

const std::vector<std::string>& exact_reference_names() {
  static const std::vector<std::string> names = {"pendulum_exact", "slider_crank_exact"};
  return names;
}

std::unique_ptr<ReferenceSolution> make_pendulum_exact(const SceneDef& scene) {
  return std::make_unique<PendulumExact>(scene);
}

std::unique_ptr<ReferenceSolution> make_slider_crank_exact(const SceneDef& scene) {
  return std::make_unique<SliderCrankExact>(scene);
}

std::unique_ptr<ReferenceSolution> make_reference_solution(const std::string& name, const SceneDef& scene) {
  if (name == "pendulum_exact") return make_pendulum_exact(scene);
  if (name == "slider_crank_exact") return make_slider_crank_exact(scene);
  throw InputError(scene_location(scene, "study.reference"),
                   "unknown exact reference '" + name + "' (pendulum_exact, slider_crank_exact, converged)");
}

}  // namespace periflex
