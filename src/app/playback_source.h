// `periflex play DIR`: the window on a checkpoint folder (or a run's VTK series) instead of a
// running scene. The simulation thread keeps its place but steps nothing: its model is a replay
// (io/state_replay.h) whose "step" puts the next state in place, so Right, the
// step button and a script's `step` move one checkpoint on, Space plays them through at the
// window's speed, Backspace goes back to the first. Left and the timeline slider ask for a
// state by index (the request is taken at the thread's next step). Drawing, colour fields,
// screenshots and recording go through the same snapshot path as a live run.
// Internal to src/app/; run_gui opens it when GuiOptions::playback_dir is set.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "app/sim_worker.h"
#include "app/widget_dump.h"

namespace periflex {

class StateReplay;

class PlaybackSource {
 public:
  // Lists the folder and builds its scene's model (in the calling thread, so that a folder that
  // cannot be replayed is reported before a window opens). Throws InputError naming the file.
  explicit PlaybackSource(const std::string& dir);
  ~PlaybackSource();

  // The worker's factory: its model is this replay. The scene path it is given is ignored.
  RunFactory factory();
  // The scene file named by the folder's record (the worker's scene path, watched for changes).
  const std::string& scene_path() const { return scene_path_; }

  // Main thread: a key press the replay takes (Left: the state before the one shown); true when
  // taken. `worker` is sent the step that carries the request out.
  bool on_key(int key, SimWorker& worker);
  // Main thread: the timeline window along the bottom of the picture (slider, time, file).
  void draw(SimWorker& worker, WidgetDump& dump, int fb_width, int fb_height, float panel_width);

  // Shared with the simulation thread: the state asked for (-1: none, then a step moves on by
  // one) and the one shown.
  struct Cursor {
    std::atomic<long> requested{-1};
    std::atomic<long> shown{0};
  };

 private:
  void request(long index, SimWorker& worker, const char* origin);

  std::string dir_, scene_path_;
  std::vector<double> times_;
  std::vector<std::string> files_;
  std::shared_ptr<Cursor> cursor_;
  // the replay built here, handed to the worker's first build
  std::shared_ptr<std::unique_ptr<StateReplay>> pending_;
  int slider_ = 0;
};

}  // namespace periflex
