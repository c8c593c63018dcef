// Requests from the user interface (panels, keys, mouse, scripts) to the simulation thread.
// They travel through a CommandQueue and are applied between two steps, in order.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "solve/simulation.h"

namespace periflex {

struct SimCommand {
  enum class Kind {
    kRun,            // start or continue stepping
    kPause,          // stop stepping after the current step
    kToggleRun,      // run when paused, pause when running
    kStep,           // pause, then take `steps` steps
    kStepTo,         // pause, then step until the time reaches `number` (the first step at or after it)
    kReset,          // rebuild the current scene from memory, keeping the live settings
    kReload,         // re-read the scene file from disk (keeps the old model if it fails)
    kLoadScene,      // switch to the scene file in `text`
    kApplySettings,  // replace the live settings with `settings`
    kSetParameter,   // set one live setting by name: `text` = key, `value` = value
    kSetSpeed,       // real-time factor `number`; <= 0 runs as fast as possible
    kMouseSpring,    // set (or, when `spring` is empty, release) the mouse spring; `new_grab`: a
                     // grab, not a drag of the one held (for the log)
    kCut,            // a knife: cut the bonds the segment `from` .. `to` crosses (drawn_x, drawn_y:
                     // the particles where the window draws them)
    kReactions,      // snapshots carry the joints' reactions (`with_reactions`) or not
    kRecord,         // publish recording snapshots every `number` simulated seconds; 0 stops
    kHistory,        // keep a state every `number` simulated seconds (<= 0: off) within
                     // `history_budget_mb` MB
    kScrub,          // pause and show the history state nearest the time `number`
    kScrubStep,      // pause and show the history state next to the one shown, in `direction`
    kResume,         // drop the history after the state shown and run from it
    kQuit,           // end the simulation thread
  };
  Kind kind = Kind::kPause;
  // what some kinds carry, each field for one kind only
  int steps = 1;                 // kStep: how many steps (at least 1)
  bool new_grab = false;         // kMouseSpring: a new grab rather than a drag of the one held
  bool with_reactions = false;   // kReactions: snapshots carry the joints' reactions
  int history_budget_mb = 1;     // kHistory: the history's memory budget in MB (at least 1)
  enum class Direction { kBack, kForward };
  Direction direction = Direction::kForward;  // kScrubStep: back or forward in the history
  std::string text;
  std::string value;
  double number = 0.0;
  LiveSettings settings;
  std::optional<MouseSpring> spring;
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  std::vector<float> drawn_x, drawn_y;
  std::string origin = "ui";  // who asked, for the log: "ui", "key", "mouse", "script"

  static SimCommand make(Kind kind, std::string origin = "ui") {
    SimCommand c;
    c.kind = kind;
    c.origin = std::move(origin);
    return c;
  }
};

// Sets one live setting from text, as scripts and `set key=value` write it.
// Keys: dt, integrator, bond_damping, global_damping, fracture (on/off), correction
// (none/baumgarte/projection), alpha, beta, tolerance, max_iterations.
// Returns an empty string on success, else what is wrong (settings unchanged).
std::string set_live_parameter(LiveSettings& settings, const std::string& key, const std::string& value);

// True when every field of the two settings is equal.
bool same_live_settings(const LiveSettings& a, const LiveSettings& b);

// The live setting keys set_live_parameter accepts, for help texts.
const char* live_parameter_keys();

}  // namespace periflex
