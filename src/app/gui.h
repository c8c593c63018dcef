// The interactive visualiser: a GLFW window with Dear ImGui panels over the renderer's
// picture of a running simulation. The command line's `periflex gui SCENE` calls run_gui.
// docs/gui.md describes the controls, the threads and the script format.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace periflex {

struct GuiOptions {
  std::string scene_path;               // scene file to open
  std::vector<std::string> overrides;   // "key.path=value", as `periflex run --set`
  int frames = 0;                       // 0: interactive; N: draw N frames (script frames) then exit
  std::string screenshot;               // PNG of the last frame (scene and overlay, no panels)
  std::string script;                   // timed actions (see gui_script.h), or a file holding them
  int width = 1280, height = 800;       // window size in screen coordinates
  // Multisamples of the window (1: off); -1 chooses by the first scene (default_samples).
  int samples = -1;
  // Deformation magnification K of the flexible bodies (0: undeformed); negative: automatic.
  double deform = -1.0;
  // A checkpoint folder to replay instead of a scene (`periflex play DIR`, app/playback_source.h).
  std::string playback_dir;
  // Asked every frame: a signal the program received (Ctrl-C in the terminal that started it,
  // SIGTERM, a closed terminal), or 0. The window then closes as if asked to, a recording under
  // way is finished, and run_gui returns 128 + the signal.
  std::function<int()> interrupt;
};

// Opens the window and runs until it is closed (or, with frames > 0, for that many frames).
// Returns an exit code: 0 ok; 2 bad input (scene, override or script); 3 a numerical failure
// at start, or standing at the end of a --frames run; 1 anything else (no display, a failed
// script expectation, a screenshot that could not be written); 128 + a signal that interrupt
// reported.
int run_gui(const GuiOptions& options);

}  // namespace periflex
