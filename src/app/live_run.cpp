// The worker's model in the program: a Simulation built from a scene file.
#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "app/sim_worker.h"
#include "output/series_row.h"
#include "scene/scene_budget.h"
#include "scene/scene_loader.h"

namespace periflex {

namespace {

class LiveRun final : public SteppedRun {
 public:
  // the state after initialisation is kept: a reset restores it instead of building again
  explicit LiveRun(const SceneDef& scene) : sim_(scene) {
    sim_.initialize();
    sim_.save_state(start_);
  }
  void step() override { sim_.step(); }
  double time() const override { return sim_.time(); }
  long step_count() const override { return sim_.step_count(); }
  double end_time() const override { return sim_.end_time(); }
  const ModelInfo& info() const override { return sim_.info(); }
  void fill_snapshot(Snapshot& out) const override {
    // the joints' reactions while the rigid-body inspector shows them
    out.with_reactions = reactions_;
    sim_.fill_snapshot(out);
    // the row series.csv would hold now, for the plots
    fill_series_row(sim_, columns_, out);
  }
  LiveSettings settings() const override { return sim_.settings(); }
  void apply(const LiveSettings& settings) override { sim_.apply(settings); }
  double set_mouse_spring(const std::optional<MouseSpring>& spring) override {
    return sim_.set_mouse_spring(spring);
  }
  void set_reactions(bool wanted) override { reactions_ = wanted; }
  long cut_bonds(const Vec2& from, const Vec2& to, const std::vector<float>& drawn_x,
                 const std::vector<float>& drawn_y) override {
    return sim_.cut_bonds(from, to, drawn_x, drawn_y);
  }
  bool reset_to_start() override {
    sim_.set_mouse_spring(std::nullopt);
    sim_.restore_state(start_);
    return true;
  }
  bool save_state(SimState& out) const override {
    sim_.save_state(out);
    return true;
  }
  bool restore_state(const SimState& in) override {
    sim_.restore_state(in);
    return true;
  }

 private:
  Simulation sim_;
  mutable std::shared_ptr<const std::vector<std::string>> columns_;
  bool reactions_ = false;
  SimState start_;
};

}  // namespace

RunFactory live_run_factory() {
  RunFactory f;
  // a scene picked or reloaded in the window meets the limits the command line enforces, before
  // anything is built: a file edited to a million particles is refused, not allocated
  f.load = [](const std::string& path, const std::vector<std::string>& overrides) {
    SceneDef scene = load_scene(path, overrides);
    check_scene_budget(scene);
    return scene;
  };
  f.build = [](const SceneDef& scene) -> std::unique_ptr<SteppedRun> {
    return std::make_unique<LiveRun>(scene);
  };
  // the simulation thread's team leaves one core to drawing, unless OMP_NUM_THREADS says otherwise
  f.started = [] {
    const char* chosen = std::getenv("OMP_NUM_THREADS");
    if (chosen && *chosen) return;
    omp_set_num_threads(std::max(1, omp_get_num_procs() - 1));
  };
  return f;
}

}  // namespace periflex
