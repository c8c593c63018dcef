#include "app/playback_source.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "core/error.h"
#include "output/checkpoint_file.h"
#include "io/state_replay.h"

namespace periflex {

namespace {

// The replay as the worker's model: a step shows the requested state, or the next one.
class PlaybackRun final : public SteppedRun {
 public:
  PlaybackRun(std::unique_ptr<StateReplay> replay, std::shared_ptr<PlaybackSource::Cursor> cursor)
      : replay_(std::move(replay)), cursor_(std::move(cursor)) {
    show(0);
  }
  void step() override {
    const long asked = cursor_->requested.exchange(-1);
    const long last = static_cast<long>(replay_->size()) - 1;
    if (asked >= 0) {
      show(std::min(asked, last));
    } else if (shown_ < last) {
      show(shown_ + 1);
    } else {
      // the last state: nothing further to show; a running window waits here, not spinning
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  double time() const override { return replay_->time(static_cast<size_t>(shown_)); }
  long step_count() const override { return snapshot_step_; }
  double end_time() const override { return replay_->times().back(); }
  const ModelInfo& info() const override { return replay_->simulation().info(); }
  // the state shown, as the replay filled it (its series row when it has one)
  void fill_snapshot(Snapshot& out) const override { out = scratch_; }
  LiveSettings settings() const override { return replay_->simulation().settings(); }
  // the states are as the run computed them: live settings change nothing shown
  void apply(const LiveSettings&) override {}
  double set_mouse_spring(const std::optional<MouseSpring>&) override { return 0.0; }
  bool reset_to_start() override {
    cursor_->requested = -1;
    show(0);
    return true;
  }

 private:
  void show(long index) {
    replay_->show(static_cast<size_t>(index), scratch_);
    shown_ = index;
    snapshot_step_ = scratch_.step;
    cursor_->shown = index;
  }
  std::unique_ptr<StateReplay> replay_;
  std::shared_ptr<PlaybackSource::Cursor> cursor_;
  long shown_ = 0;
  long snapshot_step_ = 0;
  Snapshot scratch_;
};

std::unique_ptr<StateReplay> open_replay(const std::string& dir) {
  try {
    return open_state_replay(dir);
  } catch (const CheckpointError& e) {
    throw InputError({"command line", 0, 0, "play"}, std::string("cannot replay: ") + e.what());
  }
}

}  // namespace

PlaybackSource::PlaybackSource(const std::string& dir) : dir_(dir), cursor_(std::make_shared<Cursor>()) {
  auto replay = open_replay(dir);
  scene_path_ = replay->scene_path();
  times_ = replay->times();
  for (size_t k = 0; k < replay->size(); ++k) {
    const std::string path = replay->path(k);
    files_.push_back(path.empty() ? "the scene's start" : std::filesystem::path(path).filename().string());
  }
  pending_ = std::make_shared<std::unique_ptr<StateReplay>>(std::move(replay));
}

PlaybackSource::~PlaybackSource() = default;

RunFactory PlaybackSource::factory() {
  RunFactory f;
  // the worker loads its scene and builds its model once at start, and again on a reset that
  // the model cannot do or on a reload: the replay built in the constructor first, a fresh one
  // of the same folder after (which checks the scene file again)
  auto pending = pending_;
  const std::string dir = dir_;
  f.load = [pending, dir](const std::string&, const std::vector<std::string>&) {
    if (!*pending) *pending = open_replay(dir);
    return (*pending)->scene();
  };
  auto cursor = cursor_;
  f.build = [pending, dir, cursor](const SceneDef&) -> std::unique_ptr<SteppedRun> {
    std::unique_ptr<StateReplay> replay = *pending ? std::move(*pending) : open_replay(dir);
    return std::make_unique<PlaybackRun>(std::move(replay), cursor);
  };
  return f;
}

void PlaybackSource::request(long index, SimWorker& worker, const char* origin) {
  index = std::clamp(index, 0L, static_cast<long>(times_.size()) - 1);
  cursor_->requested = index;
  worker.send(SimCommand{command::Step{}, origin});
}

bool PlaybackSource::on_key(int key, SimWorker& worker) {
  if (key != GLFW_KEY_LEFT) return false;
  const long at = cursor_->requested >= 0 ? cursor_->requested.load() : cursor_->shown.load();
  request(at - 1, worker, "key");
  return true;
}

void PlaybackSource::draw(SimWorker& worker, WidgetDump& dump, int fb_width, int fb_height, float panel_width) {
  ImGuiIO& io = ImGui::GetIO();
  const float scale = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
  const float width = std::max(200.0f, (fb_width - panel_width) / scale - 20.0f);
  ImGui::SetNextWindowPos(ImVec2(panel_width / scale + 10.0f, fb_height / scale - 70.0f));
  ImGui::SetNextWindowSize(ImVec2(width, 0.0f));
  ImGui::Begin("Playback", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_AlwaysAutoResize);
  const long shown = cursor_->shown;
  const long count = static_cast<long>(times_.size());
  // the slider follows the state shown unless the user is dragging it
  if (!ImGui::IsAnyItemActive()) slider_ = static_cast<int>(shown);
  ImGui::PushItemWidth(width - 20.0f);
  char label[96];
  std::snprintf(label, sizeof label, "%ld / %ld   t = %.6g s", shown + 1, count, times_[shown]);
  if (ImGui::SliderInt("##timeline", &slider_, 0, static_cast<int>(count - 1), label)) {
    request(slider_, worker, "slider");
  }
  dump.note_item("playback_slider");
  ImGui::PopItemWidth();
  ImGui::TextDisabled("%s   (Left / Right: previous / next state, Space: play)", files_[shown].c_str());
  ImGui::End();
  dump.state("playback_index", static_cast<double>(shown));
  dump.state("playback_count", static_cast<double>(count));
}

}  // namespace periflex
