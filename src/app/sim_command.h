// Requests from the user interface (panels, keys, mouse, scripts) to the simulation thread.
// They travel through a CommandQueue and are applied between two steps, in order.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "solve/simulation.h"

namespace periflex {

// One type per request, each carrying only what it needs.
namespace command {
struct Run {};        // start or continue stepping
struct Pause {};      // stop stepping after the current step
struct ToggleRun {};  // run when paused, pause when running
struct Step {         // pause, then take `steps` steps (at least 1)
  int steps = 1;
};
struct StepTo {  // pause, then step until the time reaches `time` (the first step at or after it)
  double time = 0.0;
};
struct Reset {};   // rebuild the current scene from memory, keeping the live settings
struct Reload {};  // re-read the scene file from disk (keeps the old model if it fails)
struct LoadScene {  // switch to the scene file at `path`
  std::string path;
};
struct ApplySettings {  // replace the live settings
  LiveSettings settings;
};
struct SetParameter {  // set one live setting by name (set_live_parameter below)
  std::string key, value;
};
struct SetSpeed {  // real-time factor; <= 0 runs as fast as possible
  double factor = 1.0;
};
struct MouseSpring {  // set the mouse spring, or release it when `spring` is empty
  std::optional<periflex::MouseSpring> spring;
  bool new_grab = false;  // a grab, not a drag of the one held (for the log)
};
struct Cut {  // a knife: cut the bonds the segment from .. to crosses
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  std::vector<float> drawn_x, drawn_y;  // the particles where the window draws them
};
struct Reactions {  // snapshots carry the joints' reactions or not
  bool with_reactions = false;
};
struct Record {  // publish recording snapshots every `interval` simulated seconds; 0 stops
  double interval = 0.0;
};
struct History {  // keep a state every `interval` simulated seconds (<= 0: off) within `budget_mb`
  double interval = 0.0;
  int budget_mb = 1;  // at least 1
};
struct Scrub {  // pause and show the history state nearest the time `time`
  double time = 0.0;
};
struct ScrubStep {  // pause and show the history state next to the one shown
  enum class Direction { kBack, kForward };
  Direction direction = Direction::kForward;
};
struct Resume {};  // drop the history after the state shown and run from it
struct Quit {};    // end the simulation thread
}  // namespace command

using SimAction = std::variant<command::Run, command::Pause, command::ToggleRun, command::Step, command::StepTo,
                               command::Reset, command::Reload, command::LoadScene, command::ApplySettings,
                               command::SetParameter, command::SetSpeed, command::MouseSpring, command::Cut,
                               command::Reactions, command::Record, command::History, command::Scrub,
                               command::ScrubStep, command::Resume, command::Quit>;

// A request and who made it.
struct SimCommand {
  SimAction action;
  std::string origin = "ui";  // who asked, for the log: "ui", "key", "mouse", "script"
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
