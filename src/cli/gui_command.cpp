#include "cli/gui_command.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "cli/run_option_checks.h"
#include "core/error.h"

#ifdef PERIFLEX_WITH_GUI
#include "app/gui.h"
#endif

namespace periflex {

bool gui_available() {
#ifdef PERIFLEX_WITH_GUI
  return true;
#else
  return false;
#endif
}

bool render_available() {
#ifdef PERIFLEX_WITH_HEADLESS
  return true;
#else
  return false;
#endif
}

bool ffmpeg_available() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && std::filesystem::exists(std::filesystem::path(dir) / "ffmpeg")) return true;
  }
  return false;
}

int gui_command(const GuiCommandOptions& options) {
#ifdef PERIFLEX_WITH_GUI
  check_gui_options(options);  // flags, output file and the scene's budget, before a window opens
  GuiOptions gui;
  gui.scene_path = options.scene_path;
  gui.overrides = options.overrides;
  gui.frames = options.frames;
  gui.screenshot = options.screenshot;
  gui.script = options.script;
  gui.samples = options.samples;
  return run_gui(gui);
#else
  throw InputError({"command line", 0, 0, "gui"},
                   "this build has no visualiser (configured with -DPERIFLEX_GUI=OFF); use 'periflex run'");
#endif
}

}  // namespace periflex
