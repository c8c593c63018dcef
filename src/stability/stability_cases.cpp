// The stability suite's catalogue. Each case states what it pushes to an edge, what the program
// must do there, and (for stable cases) the bounds with the reason for each.
#include <string>
#include <vector>

#include "stability/stability_case.h"

namespace periflex {

namespace {

// Words a diagnostic of each kind of failure must contain (any one of them).
const std::vector<std::string> kStepTerms = {"critical"};
const std::vector<std::string> kDivergenceTerms = {"energy", "finite", "nan", "diverg", "constraint violation"};
const std::vector<std::string> kConstraintTerms = {"constraint", "violation", "finite", "nan", "diverg", "energy"};
// (whole words only where a joint name could contain them: "crank_pin" contains "rank")
const std::vector<std::string> kSingularTerms = {"singular", "jacobian", "rank defici", "dependent"};
const std::vector<std::string> kAnyFailureTerms = {"energy",   "finite",   "nan",      "diverg",    "constraint",
                                                   "singular", "jacobian", "newton",   "critical",  "step"};

// Scenes of the suite, and shipped scenes it reuses.
const char* kSpring = "scenes/stability/spring_oscillator.toml";
const char* kBlock = "scenes/stability/pd_block.toml";
const char* kDust = "scenes/stability/dust_burst.toml";
const char* kPendulum = "scenes/stability/pendulum.toml";
const char* kRedundant = "scenes/stability/redundant_pendulum.toml";
const char* kToggle = "scenes/stability/toggle_slider_crank.toml";
const char* kLightLink = "scenes/stability/light_link_chain.toml";
const char* kVirtualHub = "scenes/stability/virtual_hub.toml";
const char* kUndetermined = "scenes/stability/undetermined_body.toml";
const char* kFlexPendulum = "scenes/flexible_pendulum.toml";
const char* kFlexSliderCrank = "scenes/flexible_slider_crank.toml";
const char* kNotchedPlate = "scenes/notched_plate.toml";

// Bounds of a bounded (stable) explicit run of an undamped elastic body: a symplectic integrator
// below its limit keeps a modified energy, so the error stays a fraction of the energy that
// moved; an unstable one grows without bound. 10 % separates the two with room for the high
// modes the sudden gravity load excites.
constexpr double kElasticEnergyBound = 0.1;
const char* kElasticReason =
    "symplectic integrator below its limit: bounded error, a fraction of the energy exchanged; "
    "instability grows without bound";

StabilityCase make(std::string name, std::string group, std::string description, std::string scene,
                   Expectation expect) {
  StabilityCase c;
  c.name = std::move(name);
  c.group = std::move(group);
  c.description = std::move(description);
  c.scene = std::move(scene);
  c.expect = expect;
  return c;
}

StabilityCase stable(std::string name, std::string group, std::string description, std::string scene,
                     double energy_bound, double violation_bound, std::string reason) {
  StabilityCase c = make(std::move(name), std::move(group), std::move(description), std::move(scene),
                         Expectation::kStable);
  c.max_relative_energy_error = energy_bound;
  c.max_violation = violation_bound;
  c.bounds_reason = std::move(reason);
  return c;
}

StabilityCase stopped(std::string name, std::string group, std::string description, std::string scene,
                      std::vector<std::string> terms) {
  StabilityCase c = make(std::move(name), std::move(group), std::move(description), std::move(scene),
                         Expectation::kStopped);
  if (terms == kStepTerms) c.remedy_terms = {"dt", "auto_substep"};
  c.message_terms = std::move(terms);
  return c;
}

// A time step above the explicit critical step of a flexible body, chosen by the input: known at
// set-up, so refused as bad input (exit 2) naming the step and the critical step, not run.
StabilityCase refused_step(std::string name, std::string group, std::string description, std::string scene) {
  StabilityCase c = make(std::move(name), std::move(group), std::move(description), std::move(scene),
                         Expectation::kRefused);
  c.message_terms = kStepTerms;
  c.timeout_seconds = 60;
  return c;
}

// Either a bounded run or a diagnostic: both are acceptable at this edge; NaN, a crash, a hang or
// an unbounded result that is not reported are not.
StabilityCase survives(std::string name, std::string group, std::string description, std::string scene,
                       double energy_bound, double violation_bound, std::vector<std::string> terms,
                       std::string reason) {
  StabilityCase c = stable(std::move(name), std::move(group), std::move(description), std::move(scene), energy_bound,
                           violation_bound, std::move(reason));
  c.expect = Expectation::kStableOrStopped;
  c.message_terms = std::move(terms);
  return c;
}

StabilityCase warned(std::string name, std::string description, std::string scene, std::vector<std::string> terms) {
  StabilityCase c = make(std::move(name), "check", std::move(description), std::move(scene), Expectation::kWarned);
  c.command = "check";
  c.message_terms = std::move(terms);
  c.timeout_seconds = 60;
  return c;
}

void add_stiff_material(std::vector<StabilityCase>& cases) {
  auto base = stable("pd_block_base", "stiff_material", "32-particle elastic block at its scene step", kBlock,
                     kElasticEnergyBound, 0.0, kElasticReason);
  base.quick = true;
  cases.push_back(base);

  // E x 1000 at the same grid: the critical step falls by sqrt(1000) = 31.6, below the scene's step
  auto stiff = refused_step("stiff_E1000_scene_dt", "stiff_material", "E x 1000, scene dt (now ~10x critical)", kBlock);
  stiff.sets = {"flex_body.block.material.youngs_modulus=1e9"};
  stiff.quick = true;
  cases.push_back(stiff);

  auto stiff_sub = stable("stiff_E1000_auto_substep", "stiff_material", "E x 1000, scene dt, automatic sub-steps",
                          kBlock, kElasticEnergyBound, 0.0, kElasticReason);
  stiff_sub.sets = {"flex_body.block.material.youngs_modulus=1e9", "solver.auto_substep=true"};
  stiff_sub.options = {"--until", "0.05"};
  stiff_sub.quick = true;
  cases.push_back(stiff_sub);

  auto stiff_small = stable("stiff_E1000_below_critical", "stiff_material", "E x 1000, dt = 0.7 dt_crit", kBlock,
                            kElasticEnergyBound, 0.0, kElasticReason);
  stiff_small.sets = {"flex_body.block.material.youngs_modulus=1e9"};
  stiff_small.dt_over_critical = 0.7;
  stiff_small.options = {"--until", "0.05"};
  cases.push_back(stiff_small);

  // dx halved twice (16x the particles). At a fixed horizon ratio the critical step is proportional
  // to dx; the scene's step is 0.33 of the critical step at dx = 0.01, so 0.65 of it at dx / 2
  // (still under dt_safety = 0.8: runs) and 1.3 of it at dx / 4 (refused)
  for (const auto& [tag, dx] : {std::pair{"dx_half", "0.005"}, std::pair{"dx_quarter", "0.0025"}}) {
    const bool refused = std::string(tag) == "dx_quarter";
    auto fine = refused ? refused_step(std::string("fine_") + tag + "_scene_dt", "stiff_material",
                                       std::string("grid spacing ") + dx + " m at the scene's dt (1.3 dt_crit)", kBlock)
                        : stable(std::string("fine_") + tag + "_scene_dt", "stiff_material",
                                 std::string("grid spacing ") + dx + " m at the scene's dt (0.65 dt_crit)", kBlock,
                                 kElasticEnergyBound, 0.0, kElasticReason);
    fine.sets = {std::string("flex_body.block.grid_spacing=") + dx};
    fine.quick = std::string(tag) == "dx_quarter";
    cases.push_back(fine);
    auto fine_ok = stable(std::string("fine_") + tag + "_below_critical", "stiff_material",
                          std::string("grid spacing ") + dx + " m, dt = 0.7 dt_crit", kBlock, kElasticEnergyBound,
                          0.0, kElasticReason);
    fine_ok.sets = fine.sets;
    fine_ok.dt_over_critical = 0.7;
    fine_ok.options = {"--until", "0.05"};
    fine_ok.quick = fine.quick;
    cases.push_back(fine_ok);
  }

  // horizon ratio m = 2 ... 6: more bonds per particle, a smaller critical step
  for (int m = 2; m <= 6; ++m) {
    auto h = stable("horizon_m" + std::to_string(m), "stiff_material",
                    "horizon ratio " + std::to_string(m) + ", dt = 0.7 dt_crit", kBlock, kElasticEnergyBound, 0.0,
                    kElasticReason);
    h.sets = {"flex_body.block.horizon_ratio=" + std::to_string(m)};
    h.dt_over_critical = 0.7;
    h.options = {"--until", "0.05"};
    h.quick = m == 2 || m == 6;
    cases.push_back(h);
  }
}

void add_time_step(std::vector<StabilityCase>& cases) {
  // the spring oscillator: Verlet is stable exactly when omega dt < 2 (omega = 100 rad/s)
  auto below = stable("spring_verlet_0.9_limit", "time_step", "omega dt = 1.8 (just below Verlet's limit 2)",
                      kSpring, 1.0, 0.0,
                      "Verlet keeps (1 - (w dt/2)^2) w^2 x^2 + v^2 constant, so E stays in [0.19 E0, E0]: "
                      "error below the energy exchanged");
  below.dt = 0.018;
  below.quick = true;
  cases.push_back(below);

  // at the limit from rest: exactly x_n = (-1)^n x0, so E = E0 at every step; only round-off
  // (of 1e-16 per step, and of omega dt = 2 itself) feeds the growing mode over 1000 steps
  auto at = stable("spring_verlet_at_limit", "time_step", "omega dt = 2 from rest (x_n = (-1)^n x0 exactly)",
                   kSpring, 1e-6, 0.0,
                   "the discrete solution from rest is the bounded eigenvector; round-off excites the linear mode "
                   "by far less than 1e-6 of E0 in 1000 steps");
  at.dt = 0.02;
  at.options = {"--until", "20"};
  at.quick = true;
  cases.push_back(at);

  // at the limit with v0 = 0.1 m/s: x_n = (-1)^n (x0 - 2 n v0 / omega), the energy grows as n^2 and
  // passes 1000 E0 within 200 steps while the kinetic energy stays at its initial 0.005 J
  auto at_moving = stopped("spring_verlet_at_limit_moving", "time_step",
                           "omega dt = 2 with v0 = 0.1 m/s (amplitude grows linearly)", kSpring, kDivergenceTerms);
  at_moving.sets = {"body.mass.velocity=[0.1,0]"};
  at_moving.remedy_terms = {"dt"};
  at_moving.dt = 0.02;
  at_moving.options = {"--until", "20"};
  at_moving.quick = true;
  cases.push_back(at_moving);

  auto above = stopped("spring_verlet_10x_limit", "time_step", "omega dt = 20 (exponential growth)", kSpring,
                       kDivergenceTerms);
  above.dt = 0.2;
  above.remedy_terms = {"dt"};
  above.options = {"--until", "20"};
  above.quick = true;
  cases.push_back(above);

  auto rk4 = stopped("spring_rk4_10x_limit", "time_step", "RK4 at omega dt = 20 (its limit is 2.79)", kSpring,
                     kDivergenceTerms);
  rk4.dt = 0.2;
  rk4.remedy_terms = {"dt"};
  rk4.options = {"--until", "20", "--integrator", "rk4"};
  cases.push_back(rk4);

  // the peridynamic block against its Silling-Askari critical step (dt_safety = 0.8)
  auto pd_below = stable("pd_dt_0.95_allowed", "time_step", "dt = 0.95 x 0.8 dt_crit", kBlock, kElasticEnergyBound,
                         0.0, kElasticReason);
  pd_below.dt_over_critical = 0.76;
  pd_below.quick = true;
  cases.push_back(pd_below);

  auto pd_at = refused_step("pd_dt_at_critical", "time_step", "dt = dt_crit, no sub-stepping (above 0.8 dt_crit)",
                            kBlock);
  pd_at.dt_over_critical = 1.0;
  pd_at.quick = true;
  cases.push_back(pd_at);

  auto pd_at_safety1 = survives("pd_dt_at_critical_safety_1", "time_step", "dt = dt_crit with dt_safety = 1",
                                kBlock, kElasticEnergyBound, 0.0, kDivergenceTerms,
                                "the Silling-Askari step is a conservative bound, so this may run; if not, the "
                                "divergence must be reported");
  pd_at_safety1.sets = {"solver.dt_safety=1"};
  pd_at_safety1.dt_over_critical = 1.0;
  // quick: the step is the critical step as `check` prints it, which a run must not refuse
  pd_at_safety1.quick = true;
  cases.push_back(pd_at_safety1);

  auto pd_far = refused_step("pd_dt_10x_critical", "time_step", "dt = 10 dt_crit, no sub-stepping", kBlock);
  pd_far.dt_over_critical = 10.0;
  pd_far.quick = true;
  cases.push_back(pd_far);

  auto pd_far_sub = stable("pd_dt_10x_critical_substep", "time_step", "dt = 10 dt_crit, automatic sub-steps",
                           kBlock, kElasticEnergyBound, 0.0, kElasticReason);
  pd_far_sub.sets = {"solver.auto_substep=true"};
  pd_far_sub.dt_over_critical = 10.0;
  pd_far_sub.quick = true;
  cases.push_back(pd_far_sub);

  auto pd_far_sub_euler = stable("pd_dt_10x_critical_substep_euler", "time_step",
                                 "symplectic Euler, dt = 10 dt_crit, automatic sub-steps", kBlock,
                                 kElasticEnergyBound, 0.0, kElasticReason);
  pd_far_sub_euler.sets = {"solver.auto_substep=true"};
  pd_far_sub_euler.options = {"--integrator", "symplectic_euler"};
  pd_far_sub_euler.dt_over_critical = 10.0;
  cases.push_back(pd_far_sub_euler);

  // adaptive Dormand-Prince on the stiff block with a tight tolerance: must finish or stop, not crawl forever
  auto dopri = survives("pd_stiff_dopri54_tight", "time_step", "E x 1000, dopri54 with rtol 1e-10", kBlock,
                        kElasticEnergyBound, 0.0, kAnyFailureTerms,
                        "an accurate adaptive run; the bound is that of any bounded elastic run");
  dopri.sets = {"flex_body.block.material.youngs_modulus=1e9", "solver.rtol=1e-10", "solver.atol=1e-14",
                "solver.auto_substep=true"};
  dopri.options = {"--integrator", "dopri54", "--until", "0.005"};
  dopri.timeout_seconds = 120;
  dopri.quick = true;
  cases.push_back(dopri);

  // a tolerance at round-off on a stiff body: the controller must give up with a diagnostic (or
  // finish), in bounded time, rather than shrink the step for ever
  auto roundoff = survives("pd_stiff_dopri54_roundoff_tolerance", "time_step",
                           "E x 1000, dopri54 with rtol 1e-15, atol 1e-300", kBlock, kElasticEnergyBound, 0.0,
                           {"step size", "tolerance", "rtol"},
                           "a tolerance double precision cannot meet: stopping is the expected answer; a finished "
                           "run is bounded like any elastic run");
  roundoff.sets = {"flex_body.block.material.youngs_modulus=1e9", "solver.rtol=1e-15", "solver.atol=1e-300"};
  roundoff.remedy_terms = {"rtol", "atol"};
  roundoff.options = {"--integrator", "dopri54", "--until", "0.005"};
  roundoff.timeout_seconds = 300;
  cases.push_back(roundoff);

  // the implicit integrator far above the explicit limit
  for (const char* name : {"hht"}) {
    for (double factor : {10.0, 100.0}) {
      const std::string tag = std::to_string(static_cast<int>(factor)) + "x";
      auto implicit = stable(std::string("pd_") + name + "_" + tag + "_critical", "time_step",
                             std::string(name) + " at " + tag + " the explicit critical step", kBlock, 0.5, 0.0,
                             "implicit and unconditionally stable; numerical damping removes high-mode energy that "
                             "the balance does not count, so up to half the energy exchanged may go");
      implicit.dt_over_critical = factor;
      implicit.options = {"--integrator", name};
      implicit.requires_integrator = name;
      implicit.quick = true;
      cases.push_back(implicit);
    }
  }
}

void add_constraints(std::vector<StabilityCase>& cases) {
  // rk4, dt = 1e-3 on a 1 m pendulum: local error ~ dt^5 per step; over 5000 steps far below 1e-6
  const char* rk4_reason = "RK4, dt = 1e-3, 1 m pendulum: truncation error ~1e-12 over the run; 1e-6 leaves room";
  auto base = stable("pendulum_baumgarte_5", "constraints", "pendulum, Baumgarte alpha = beta = 5", kPendulum, 1e-6,
                     1e-6, rk4_reason);
  base.quick = true;
  cases.push_back(base);

  auto none = stable("pendulum_baumgarte_0", "constraints", "pendulum, Baumgarte gains 0 (drift uncorrected)",
                     kPendulum, 1e-6, 1e-6, rk4_reason);
  none.sets = {"solver.correction.alpha=0", "solver.correction.beta=0"};
  none.quick = true;
  cases.push_back(none);

  auto high = stable("pendulum_baumgarte_1e3", "constraints", "pendulum, Baumgarte 1e3 (alpha dt = 1)", kPendulum,
                     1e-6, 1e-6, rk4_reason);
  high.sets = {"solver.correction.alpha=1e3", "solver.correction.beta=1e3"};
  cases.push_back(high);

  // alpha dt = 100: the correction's own dynamics (rate alpha) are far outside RK4's stability region
  auto huge = stopped("pendulum_baumgarte_1e5", "constraints", "pendulum, Baumgarte 1e5 (alpha dt = 100)", kPendulum,
                      kConstraintTerms);
  huge.sets = {"solver.correction.alpha=1e5", "solver.correction.beta=1e5"};
  huge.remedy_terms = {"alpha", "beta"};  // the gains are the cause; correction is already on
  huge.quick = true;
  cases.push_back(huge);

  auto loose = stable("pendulum_projection_loose", "constraints", "projection with tolerance 1e-2", kPendulum, 1e-2,
                      1e-2,
                      "projection holds |Phi| under its tolerance 1e-2; the energy follows the positions to "
                      "the same order");
  loose.sets = {"solver.correction.method=projection", "solver.correction.tolerance=1e-2"};
  loose.quick = true;
  cases.push_back(loose);

  auto tight = survives("pendulum_projection_below_roundoff", "constraints",
                        "projection with tolerance 1e-16 (below round-off)", kPendulum, 1e-6, 1e-12,
                        {"projection", "tolerance", "converge"},
                        "an unreachable tolerance: either the iteration cap ends each projection with |Phi| at "
                        "round-off (1e-12 allows for it), or the run stops naming the tolerance");
  tight.sets = {"solver.correction.method=projection", "solver.correction.tolerance=1e-16",
                "solver.correction.max_iterations=50"};
  tight.quick = true;
  tight.timeout_seconds = 60;
  cases.push_back(tight);

  auto virtual_hub = stable("massless_virtual_body", "constraints", "massless virtual hub carrying a welded bob",
                            kVirtualHub, 1e-6, 1e-6, rk4_reason);
  virtual_hub.quick = true;
  cases.push_back(virtual_hub);

  auto flex_hub = stable("massless_virtual_body_flexible", "constraints",
                         "flexible pendulum: massless hub holding a PD beam", kFlexPendulum, kElasticEnergyBound,
                         1e-4,
                         "Baumgarte 200 at dt = 1e-5 keeps the hub clamp within 0.1 mm of a 0.5 m beam; energy as "
                         "for any undamped elastic body");
  flex_hub.options = {"--until", "0.05"};
  flex_hub.quick = true;
  cases.push_back(flex_hub);

  auto light = stable("nearly_massless_link", "constraints", "middle link 1e-9 of its neighbours' mass", kLightLink,
                      1e-4, 1e-6,
                      "RK4, dt = 1e-4 on a chaotic chain: error ~1e-10 per unit energy; the ill-conditioned mass "
                      "matrix (1e9) may cost 9 digits of the accelerations, which 1e-4 still bounds");
  light.quick = true;
  cases.push_back(light);

  auto redundant = stable("redundant_joints", "constraints", "pendulum pinned twice at one point", kRedundant, 1e-6,
                          1e-6, rk4_reason);
  redundant.quick = true;
  cases.push_back(redundant);

  auto toggle = survives("slider_crank_toggle", "constraints", "slider-crank with r = l through its toggle",
                         kToggle, 1e-2, 1e-3, kSingularTerms,
                         "the mechanism is 0.1 m: joints more than 1 mm apart have come loose; the driver feeds "
                         "energy in, so 1e-2 of the energy exchanged bounds the bookkeeping error");
  toggle.quick = true;
  cases.push_back(toggle);
}

void add_loading(std::vector<StabilityCase>& cases) {
  // 100x the shipped crank speed, with consistent initial velocities (the scene's times 100)
  auto fast_crank = survives("flex_slider_crank_100x", "loading", "flexible slider-crank, crank at 5000 rad/s",
                             kFlexSliderCrank, 0.5, 1e-3, kAnyFailureTerms,
                             "the rod may break and radiate waves: half the energy exchanged and 1 mm of joint "
                             "separation bound a run that is still meaningful");
  fast_crank.sets = {"driver.crank_speed.function.rate=5000", "body.crank.angular_velocity=5000",
                     "body.crank.velocity=[-250,0]", "body.slider.velocity=[-500,0]",
                     "body.rod_left.velocity=[-500,0]", "body.rod_right.velocity=[-500,0]",
                     "flex_body.rod.velocity=[-500,0]"};
  fast_crank.options = {"--until", "2e-4"};
  fast_crank.quick = true;
  cases.push_back(fast_crank);

  // impulsive start: the driver demands 5000 rad/s at t = 0 from a mechanism at rest
  auto impulsive = survives("flex_slider_crank_impulsive_start", "loading",
                            "crank driven at 5000 rad/s from rest (velocity jump at t = 0)", kFlexSliderCrank, 0.5,
                            1e-3, kAnyFailureTerms,
                            "the initial velocity projection absorbs the jump; thereafter as for the fast crank");
  impulsive.sets = {"driver.crank_speed.function.rate=5000", "body.crank.angular_velocity=0",
                    "body.crank.velocity=[0,0]",  "body.slider.velocity=[0,0]", "body.rod_left.velocity=[0,0]",
                    "body.rod_right.velocity=[0,0]", "flex_body.rod.velocity=[0,0]"};
  impulsive.options = {"--until", "2e-4"};
  impulsive.quick = true;
  cases.push_back(impulsive);

  auto fast_grips = survives("notched_plate_100x", "loading", "notched plate, grips turned at 2000 rad/s",
                             kNotchedPlate, 0.5, 1e-3, kAnyFailureTerms,
                             "the plate shatters; the energy balance must still account for most of it");
  fast_grips.sets = {"driver.left_turn.function.rate=-2000", "driver.right_turn.function.rate=2000"};
  fast_grips.options = {"--until", "5e-5"};
  cases.push_back(fast_grips);

  // damping: over-critical but resolvable (alpha dt ~ 0.3), then far beyond the explicit limit alpha dt < 2
  auto damped = stable("pd_global_damping_overcritical", "loading", "global damping 1e3 /s (over-critical)", kBlock,
                       kElasticEnergyBound, 0.0,
                       "dissipation is counted in the balance; what remains is the integrator's bounded error");
  damped.sets = {"flex_body.block.global_damping=1e3"};
  damped.quick = true;
  cases.push_back(damped);

  auto over = survives("pd_global_damping_huge", "loading", "global damping 1e5 /s (alpha dt >> 2)", kBlock,
                       kElasticEnergyBound, 0.0, kDivergenceTerms,
                       "an explicit damping term is unstable beyond alpha dt = 2 unless treated implicitly: bounded "
                       "or reported");
  over.sets = {"flex_body.block.global_damping=1e5"};
  over.remedy_terms = {"damping"};
  over.quick = true;
  cases.push_back(over);

  auto bond = survives("pd_bond_damping_huge", "loading", "bond damping 1e6 Pa s", kBlock, kElasticEnergyBound, 0.0,
                       kDivergenceTerms, "as for global damping: bounded or reported");
  bond.sets = {"flex_body.block.bond_damping=1e6"};
  bond.remedy_terms = {"damping"};
  bond.quick = true;
  cases.push_back(bond);

  auto dust = stable("dust_burst", "loading", "every bond breaks; end columns fly 1 m at 50 m/s", kDust, 0.1, 0.0,
                     "released strain energy goes to the fracture account and the prescribed ends do work "
                     "outside the balance only through their constant velocity (no force)");
  dust.max_relative_energy_error = std::numeric_limits<double>::infinity();
  dust.bounds_reason = "no energy bound: prescribed motion does unaccounted work; the run must end without NaN";
  dust.quick = true;
  cases.push_back(dust);

  auto dust_frame = dust;
  dust_frame.name = "dust_burst_rendered";
  dust_frame.description = "the dust burst drawn at its end, particles far outside the initial bounds";
  dust_frame.options = {"--snapshot-at", "0.02", "--screenshot", "{out}/dust.png"};
  dust_frame.quick = false;
  dust_frame.requires_rendering = true;
  cases.push_back(dust_frame);

  auto tiny_s0 = survives("flex_slider_crank_dust", "loading", "slider-crank rod with G0 = 1e-12 J/m^2: turns to dust",
                          kFlexSliderCrank, std::numeric_limits<double>::infinity(), 1e-3, kAnyFailureTerms,
                          "the rod's pieces stay attached to their pins; joints within 1 mm");
  tiny_s0.sets = {"flex_body.rod.material.fracture_energy=1e-12"};
  tiny_s0.options = {"--until", "5e-3"};
  cases.push_back(tiny_s0);
}

void add_long_runs(std::vector<StabilityCase>& cases) {
  auto block = stable("long_pd_block_1e6_steps", "long_run", "10^6 steps of the undamped 32-particle block", kBlock,
                      kElasticEnergyBound, 0.0, kElasticReason);
  block.dt_over_critical = 0.5;
  block.run_steps = 1000000;
  block.long_run = true;
  block.timeout_seconds = 1800;
  cases.push_back(block);

  auto pendulum = stable("long_pendulum_1e6_steps", "long_run", "10^6 RK4 steps of the pendulum (1000 s)", kPendulum,
                         1e-4, 1e-6,
                         "RK4's energy error grows linearly in time; 1e-4 over 1000 s bounds a drift of 1e-7 per "
                         "second");
  pendulum.dt = 1e-3;
  pendulum.run_steps = 1000000;
  pendulum.long_run = true;
  pendulum.timeout_seconds = 1800;
  cases.push_back(pendulum);

  auto verlet = stable("long_pendulum_verlet_1e6_steps", "long_run", "10^6 Verlet steps of the pendulum, projection",
                       kPendulum, 1e-3, 1e-9,
                       "Verlet's error is bounded (not growing) at (w dt)^2 ~ 1e-5; projection holds |Phi| < 1e-10");
  verlet.dt = 1e-3;
  verlet.run_steps = 1000000;
  verlet.sets = {"solver.correction.method=projection"};
  verlet.options = {"--integrator", "verlet"};
  verlet.long_run = true;
  verlet.timeout_seconds = 1800;
  cases.push_back(verlet);
}

void add_checks(std::vector<StabilityCase>& cases) {
  auto dt = warned("check_dt_above_critical", "`check` with dt = 10 dt_crit", kBlock, {"critical"});
  dt.dt_over_critical = 10.0;
  dt.quick = true;
  cases.push_back(dt);

  auto undetermined =
      warned("check_undetermined_body", "`check` on a free massless body", kUndetermined, {"undetermined"});
  undetermined.quick = true;
  cases.push_back(undetermined);

  // two identical pins: 4 equations, of which 2 depend on the others
  auto redundant = warned("check_redundant_constraints", "`check` on a doubly pinned pendulum", kRedundant,
                          {"(2 redundant)"});
  redundant.quick = true;
  cases.push_back(redundant);

  // bond-based PD fixes Poisson's ratio at 1/3 in plane stress
  auto poisson = warned("check_poisson_mismatch", "`check` with poisson_ratio = 0.2 in plane stress", kBlock,
                        {"poisson"});
  poisson.sets = {"flex_body.block.material.poisson_ratio=0.2"};
  poisson.quick = true;
  cases.push_back(poisson);

  auto horizon = warned("check_horizon_below_2dx", "`check` with horizon ratio 1.5", kBlock, {"horizon"});
  horizon.sets = {"flex_body.block.horizon_ratio=1.5"};
  horizon.quick = true;
  cases.push_back(horizon);

  // 0.1 m x 0.04 m at dx = 1e-8 m is 4e13 particles: refused with the count before any allocation
  auto absurd = make("absurd_particle_count", "check", "notched plate at dx = 1e-8 m (4e13 particles)",
                     kNotchedPlate, Expectation::kRefused);
  absurd.sets = {"flex_body.plate.grid_spacing=1e-8"};
  absurd.message_terms = {"particle"};
  absurd.timeout_seconds = 30;
  absurd.quick = true;
  cases.push_back(absurd);

  auto undetermined_run = make("run_undetermined_body", "check", "`run` on a free massless body", kUndetermined,
                               Expectation::kRefused);
  undetermined_run.message_terms = {"undetermined"};
  undetermined_run.quick = true;
  cases.push_back(undetermined_run);
}

}  // namespace

std::vector<StabilityCase> stability_cases() {
  std::vector<StabilityCase> cases;
  add_stiff_material(cases);
  add_time_step(cases);
  add_constraints(cases);
  add_loading(cases);
  add_checks(cases);
  add_long_runs(cases);
  return cases;
}

}  // namespace periflex
