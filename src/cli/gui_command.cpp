#include "cli/gui_command.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "cli/interrupt.h"
#include "cli/run_option_checks.h"
#include "core/error.h"
#include "io/frame_writer.h"
#include "io/movie_format.h"

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
  // an ffmpeg on PATH that can write the default movie (H.264 in MP4)
  const std::string ffmpeg = find_ffmpeg();
  return !ffmpeg.empty() && ffmpeg_abilities(ffmpeg).can_write(*movie_format_of("movie.mp4"));
}

bool parse_window_size(const std::string& text, int& width, int& height) {
  // digits 'x' digits, nothing else
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos || x == 0 || x + 1 >= text.size()) return false;
  const std::string w = text.substr(0, x), h = text.substr(x + 1);
  const auto digits = [](const std::string& s) { return s.size() <= 5 && s.find_first_not_of("0123456789") == std::string::npos; };
  if (!digits(w) || !digits(h)) return false;
  width = std::atoi(w.c_str());
  height = std::atoi(h.c_str());
  return width >= 640 && height >= 480 && width <= 16384 && height <= 16384;
}

std::string parse_window_size_check(const std::string& text) {
  int w = 0, h = 0;
  if (parse_window_size(text, w, h)) return "";
  return "'" + text + "' is not a window size WxH (640x480 to 16384x16384, e.g. 1024x768)";
}

bool parse_deform(const std::string& text, double& factor) {
  if (text.empty() || text == "auto") {
    factor = -1.0;
    return true;
  }
  // the whole text a number, finite and within range
  char* end = nullptr;
  const double k = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(k) || k < 0.0 || k > 1e6) return false;
  factor = k;
  return true;
}

std::string parse_deform_check(const std::string& text) {
  double k = 0.0;
  if (parse_deform(text, k)) return "";
  return "'" + text + "' is not a deformation magnification: 'auto' or a number from 0 (undeformed) to 1e6";
}

int gui_command(const GuiCommandOptions& options) {
#ifdef PERIFLEX_WITH_GUI
  check_gui_options(options);  // flags, output file and the scene's budget, before a window opens
  GuiOptions gui;
  if (!options.size.empty() && !parse_window_size(options.size, gui.width, gui.height)) {
    throw InputError({"command line", 0, 0, "--size"}, parse_window_size_check(options.size));
  }
  gui.scene_path = options.scene_path;
  gui.overrides = options.overrides;
  // the device as a key of every scene the window loads, reloads included
  if (!options.device.empty()) gui.overrides.push_back("solver.device=" + options.device);
  gui.frames = options.frames;
  gui.screenshot = options.screenshot;
  gui.script = options.script;
  gui.samples = options.samples;
  gui.playback_dir = options.playback_dir;
  // Ctrl-C in the terminal, SIGTERM or a closed terminal close the window cleanly
  catch_interrupts();
  gui.interrupt = pending_interrupt;
  if (!parse_deform(options.deform, gui.deform)) {
    throw InputError({"command line", 0, 0, "--deform"}, parse_deform_check(options.deform));
  }
  const int exit_code = run_gui(gui);
  if (const int signal_number = pending_interrupt())
    std::fprintf(stderr, "periflex: the window was closed by %s\n", interrupt_name(signal_number));
  return exit_code;
#else
  throw InputError({"command line", 0, 0, "gui"},
                   "this build has no visualiser (configured with -DPERIFLEX_GUI=OFF); use 'periflex run'");
#endif
}

}  // namespace periflex
