// One case of the stability suite: a scene (a file of scenes/stability/ or a shipped scene with
// --set overrides) pushed to an edge, and the behaviour the program must show there.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace periflex {

// What a case must end as.
enum class Expectation {
  kStable,           // exit 0; energy error and constraint violation within the stated bounds
  kStopped,          // exit 3 with a diagnostic naming one of `message_terms`; outputs so far valid
  kStableOrStopped,  // either of the above (both are acceptable behaviour at this edge)
  kRefused,          // exit 2 with a message naming one of `message_terms`, quickly
  kWarned,           // `periflex check` exits 0 (or 2 where stated) and prints one of `message_terms`
};

struct StabilityCase {
  std::string name;          // unique, snake_case
  std::string group;         // stiff_material | time_step | constraints | loading | long_run | check
  std::string description;   // one line for the table
  std::string scene;         // path relative to the resource root, e.g. "scenes/stability/spring.toml"
  std::vector<std::string> sets;     // --set overrides
  // Further arguments of `periflex run`, e.g. {"--until", "0.1"}; "{out}" stands for the case's
  // output directory.
  std::vector<std::string> options;
  std::string command = "run";       // run | check
  // > 0: the time step is this multiple of the critical step `periflex check` reports for the
  // scene (after the overrides), passed as --dt.
  double dt_over_critical = 0.0;
  double dt = 0.0;                   // > 0: this time step, passed as --dt
  // > 0: run this many steps (--until steps * dt, one series row per steps / 1000); needs a step
  // from `dt` or `dt_over_critical`.
  long run_steps = 0;
  Expectation expect = Expectation::kStable;
  // Stopped / refused / warned: the message must contain one of these (case-insensitive).
  std::vector<std::string> message_terms;
  // Stopped: the remedy (the text after "Try:") must name one of these parameters; empty: any.
  std::vector<std::string> remedy_terms;
  // Stable: bounds, and why they are what they are.
  double max_relative_energy_error = std::numeric_limits<double>::infinity();
  double max_violation = std::numeric_limits<double>::infinity();
  std::string bounds_reason;
  std::string requires_integrator;   // skipped when integrator_names() lacks it
  bool requires_rendering = false;   // skipped when the program was built without the off-screen renderer
  double timeout_seconds = 120.0;
  bool quick = false;                // part of `periflex stability --quick` and of ctest
  bool long_run = false;             // report drift per unit time
};

// The catalogue: every case of the full suite, quick ones marked.
std::vector<StabilityCase> stability_cases();

// "stable", "stopped", "stable or stopped", "refused", "warned".
const char* expectation_name(Expectation e);

}  // namespace periflex
