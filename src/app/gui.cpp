#include "app/gui.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "app/event_log.h"
#include "app/gui_app.h"
#include "app/gui_script.h"
#include "app/key_presses.h"
#include "app/playback_source.h"
#include "app/sim_worker.h"
#include "core/error.h"
#include "core/resources.h"
#include "render/view.h"

namespace periflex {

namespace {

void glfw_error(int code, const char* description) {
  std::fprintf(stderr, "gui: GLFW error %d: %s\n", code, description);
}

}  // namespace

int run_gui(const GuiOptions& options) {
  EventLog log;

  // the script and the first scene are checked before any window opens
  std::vector<ScriptAction> script;
  std::unique_ptr<SimWorker> worker;
  std::unique_ptr<PlaybackSource> playback;
  try {
    if (!options.script.empty()) script = parse_script(options.script);
    if (!options.playback_dir.empty()) {
      // a checkpoint folder: the same window on a replay that steps nothing
      playback = std::make_unique<PlaybackSource>(options.playback_dir);
      worker = std::make_unique<SimWorker>(playback->factory(), playback->scene_path(), options.overrides, log);
    } else {
      worker = std::make_unique<SimWorker>(live_run_factory(), options.scene_path, options.overrides,
                                           log);
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "periflex: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const NumericalError& e) {
    std::fprintf(stderr, "periflex: numerical failure: %s\n", e.what());
    return kExitNumerical;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "periflex: error: %s\n", e.what());
    return kExitOther;
  }

  // the window: OpenGL 3.3 core
  glfwSetErrorCallback(glfw_error);
  if (!glfwInit()) {
    std::fprintf(stderr,
                 "periflex: error: cannot open a window (no display?). On a machine without one, run under "
                 "xvfb-run -a -s \"-screen 0 1280x800x24\", or record with `periflex run --frames`.\n");
    return kExitOther;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  const int samples =
      options.samples > 0 ? options.samples : default_samples(worker->status().info.particles);
  glfwWindowHint(GLFW_SAMPLES, samples > 1 ? samples : 0);
  const std::string title = "periflex - " + worker->status().scene_name;
  GLFWwindow* window = glfwCreateWindow(std::max(320, options.width), std::max(240, options.height),
                                        title.c_str(), nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "periflex: error: cannot create an OpenGL 3.3 core window\n");
    glfwTerminate();
    return kExitOther;
  }
  glfwMakeContextCurrent(window);
  // scripted runs draw as fast as they can; interactive ones follow the display
  glfwSwapInterval(options.frames > 0 ? 0 : 1);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the current directory
  ImGui::StyleColorsDark();
  install_key_presses(window);  // before ImGui's callbacks, which chain to it
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330");

  int code = kExitOk;
  try {
    GuiApp app(options, std::move(script), log, *worker, window, find_resource_root());
    app.attach_playback(playback.get());
    // a scene whose whole run is under a second of simulated time (a fracture in microseconds)
    // starts in slow motion, so that it plays over about ten seconds; longer ones at 1x
    const double end = worker->status().end_time;
    const double speed = end > 0.0 && end < 1.0 ? end / 10.0 : 1.0;
    worker->start(!playback, speed);
    code = app.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "periflex: error: %s\n", e.what());
    code = kExitOther;
  }
  worker->stop();
  // a scripted run that ends on a standing numerical failure reports it
  const WorkerStatus final_status = worker->status();
  if (code == kExitOk && options.frames > 0 && final_status.numerical_error) {
    std::fprintf(stderr, "numerical error: %s\n", final_status.numerical_message.c_str());
    code = kExitNumerical;
  }

  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace periflex
