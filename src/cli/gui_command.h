// `periflex gui`: hands over to the visualiser when the program was built with it.
#pragma once

#include <string>
#include <vector>

namespace periflex {

struct GuiCommandOptions {
  std::string scene_path;
  std::vector<std::string> overrides;
  int frames = 0;          // 0: interactive
  std::string screenshot;  // PNG of the last frame
  std::string script;      // timed actions for scripted runs
  int samples = -1;        // multisampling of the window; -1: chosen by scene size
  std::string size;        // "WxH" window size; empty: 1280x800
  std::string deform;      // deformation magnification "auto" or K >= 0; empty: auto
  std::string playback_dir;  // `periflex play DIR`: a checkpoint folder instead of a scene
  std::string device;        // --device: cpu | gpu for every scene the window loads; empty: solver.device
};

// Parses "WxH" (640 <= W, 480 <= H, both at most 16384) into width and height; false when it is
// not that.
bool parse_window_size(const std::string& text, int& width, int& height);
// The same as a command-line check: "" when valid, else what is wrong.
std::string parse_window_size_check(const std::string& text);

// Parses a deformation magnification: "auto" (factor < 0) or a number K in [0, 1e6]. Empty text is
// "auto". False when it is neither.
bool parse_deform(const std::string& text, double& factor);
// The same as a command-line check: "" when valid, else what is wrong.
std::string parse_deform_check(const std::string& text);

int gui_command(const GuiCommandOptions& options);

// What this build of the program can do.
bool gui_available();
bool render_available();
bool ffmpeg_available();

}  // namespace periflex
