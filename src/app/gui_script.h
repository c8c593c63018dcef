// Scripts of timed GUI actions, for tests and demonstrations. A script is a list of actions
// separated by ';' or new lines, each `verb [arguments] @frame`:
//
//   pause@5; step 3@6; set bond_damping=0.1@7; resume@8; colormap viridis@9
//
// `frame` counts the frames the window has drawn (0 is the first); actions of one frame run
// in the order written. `#` starts a comment that runs to the end of the line. Verbs:
//   run | resume, pause, step [N], reset, reload, scene PATH, set KEY=VALUE, speed X|max,
//   colormap NAME, field damage|displacement|speed|strain, range auto|MIN MAX,
//   show bodies|markers|springs|bonds|probes|trails|overlay on|off, fit, follow BODY|none,
//   screenshot FILE, screenshot_ui FILE (with the panels), record PATH INTERVAL, stop_record,
//   grab X Y, drag X Y, release, wait T, expect running|paused, expect KEY=VALUE, quit,
//   history T [MB], back [N], scrub T
// `grab` takes hold of what lies at the world point (X, Y) as a left-drag would (the script
// fails when nothing is there), `drag` moves the held point's target, `release` lets go.
// `history T [MB]` keeps a state every T simulated seconds (0: off) within MB megabytes; `back`
// shows the saved state N before the one shown (Left pressed N times), `scrub T` the one nearest
// T; `run` or `resume` then continues from it.
// `wait T` holds the frame count until the simulated time reaches T (or the run stops);
// `expect` first waits until the simulation thread has applied every request sent so far,
// then fails the run (exit code 1) when the state differs.
#pragma once

#include <string>
#include <vector>

namespace periflex {

struct ScriptAction {
  long frame = 0;
  std::string verb;
  std::vector<std::string> args;  // words after the verb; `set` and `expect` keep KEY=VALUE whole
  std::string text;               // the action as written, for the log
};

// Parses a script (or, when `text` names a readable file, the script in it), sorted by frame
// with the written order kept within a frame. Throws InputError keyed "--script" naming the
// action, for an unknown verb, a missing '@frame' or wrong arguments.
std::vector<ScriptAction> parse_script(const std::string& text);

}  // namespace periflex
