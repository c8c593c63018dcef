// Where the panels' controls are, for tests that drive the window with real input events
// (xdotool under Xvfb): when PERIFLEX_GUI_WIDGETS names a file, every frame that changes it
// rewrites that file with one line per visible control, `widget NAME X0 Y0 X1 Y1` in window
// coordinates (what the X server's pointer uses), and a few lines of state (`state KEY VALUE`)
// a test compares against. Without the variable nothing is collected. Internal to src/app/.
#pragma once

#include <map>
#include <string>

namespace periflex {

class WidgetDump {
 public:
  // Reads PERIFLEX_GUI_WIDGETS; enabled() is false when it is unset or empty.
  WidgetDump();
  bool enabled() const { return !path_.empty(); }

  // Starts a frame's collection (forgets the controls of the last frame).
  void begin_frame();
  // Notes the last ImGui item under `name` when it is visible (call right after the item).
  void note_item(const std::string& name);
  // Notes a value for the state lines.
  void state(const std::string& key, const std::string& value);
  void state(const std::string& key, double value);
  // Writes the file when anything differs from what it holds (written whole, then renamed, so
  // a reader never sees half a file).
  void end_frame();

 private:
  std::string path_;
  std::map<std::string, std::string> lines_;
  std::string written_;
};

}  // namespace periflex
