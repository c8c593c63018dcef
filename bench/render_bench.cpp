// Off-screen drawing and recording speed on the software renderer (Mesa llvmpipe through EGL):
//   BM_DrawParticles/N          draw N particles at 1280x720 (goal: 250k at >= 30 frames/s)
//   BM_RenderAndEncodePng/N     draw, read back and PNG-encode N particles at 1280x720, serially
//   BM_EncodePng/N              PNG-encode one rendered 1280x720 frame of N particles
//   BM_EncodeSceneFrame/scene   PNG-encode a 1280x720 frame of a shipped scene (notched plate,
//                               slider-crank) as `run --frames` draws it
//   BM_Record/png|mp4|png_and_mp4
//                               100k particles at 1280x720 through the Recorder (drawing and
//                               encoding in threads of their own), end to end: PNG sequence, MP4
//                               through ffmpeg, or both (goal: >= 20 frames/s)
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "headless/offscreen_renderer.h"
#include "headless/recorder.h"
#include "io/frame_writer.h"
#include "io/image.h"
#include "render/view.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace periflex {
namespace {

namespace fs = std::filesystem;

// A square plate of n particles with a band of damage across it.
Snapshot plate_snapshot(int n) {
  const int side = static_cast<int>(std::sqrt(static_cast<double>(n)));
  const double dx = 1.0 / side;
  auto geometry = std::make_shared<SceneGeometry>();
  geometry->scene_name = "plate";
  geometry->bodies.push_back({"ground", true, false, {}});
  SceneGeometry::FlexBody flex;
  flex.name = "plate";
  flex.particle_count = side * side;
  flex.grid_spacing = dx;
  geometry->flex_bodies.push_back(flex);
  geometry->bounds_max = Vec2(1.0, 1.0);
  Snapshot s;
  s.bodies.resize(1);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const float x = static_cast<float>((i + 0.5) * dx), y = static_cast<float>((j + 0.5) * dx);
      geometry->reference_x.push_back(x);
      geometry->reference_y.push_back(y);
      s.px.push_back(x);
      s.py.push_back(y);
      s.damage.push_back(std::exp(-std::pow((x - 0.5f) / 0.02f, 2.0f)));
      s.displacement.push_back(0.0f);
      s.speed.push_back(y);
      s.strain.push_back(0.0f);
    }
  geometry->particle_attached.assign(s.px.size(), 0);
  s.geometry = geometry;
  return s;
}

void BM_DrawParticles(benchmark::State& state) {
  OffscreenRenderer renderer(1280, 720, static_cast<int>(state.range(1)));
  const Snapshot snapshot = plate_snapshot(static_cast<int>(state.range(0)));
  const Camera camera = fit_camera(snapshot, 1280, 720);
  const RenderSettings settings;
  for (auto _ : state) renderer.draw_only(snapshot, camera, settings);
  state.counters["frames_per_s"] = benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
  state.counters["particles"] = static_cast<double>(snapshot.px.size());
}
BENCHMARK(BM_DrawParticles)->Args({100000, 4})->Args({250000, 4})->Args({250000, 2})->Args({250000, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RenderAndEncodePng(benchmark::State& state) {
  OffscreenRenderer renderer(1280, 720, static_cast<int>(state.range(1)));
  const Snapshot snapshot = plate_snapshot(static_cast<int>(state.range(0)));
  const Camera camera = fit_camera(snapshot, 1280, 720);
  const RenderSettings settings;
  RgbaImage image;
  size_t bytes = 0;
  for (auto _ : state) {
    renderer.render(snapshot, camera, settings, image);
    bytes += encode_png(image).size();
  }
  benchmark::DoNotOptimize(bytes);
  state.counters["frames_per_s"] = benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderAndEncodePng)->Args({100000, 4})->Args({100000, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

// PNG encoding alone, of one rendered frame of N particles (no multisampling).
void BM_EncodePng(benchmark::State& state) {
  RgbaImage image;
  {
    OffscreenRenderer renderer(1280, 720, 1);
    const Snapshot snapshot = plate_snapshot(static_cast<int>(state.range(0)));
    renderer.render(snapshot, fit_camera(snapshot, 1280, 720), RenderSettings(), image);
  }
  size_t bytes = 0;
  for (auto _ : state) bytes = encode_png(image).size();
  state.counters["MB_per_s"] =
      benchmark::Counter(static_cast<double>(image.pixels.size()) * state.iterations() / 1e6, benchmark::Counter::kIsRate);
  state.counters["png_kB"] = static_cast<double>(bytes) / 1e3;
}
BENCHMARK(BM_EncodePng)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();

// A frame of a shipped scene a few steps in, drawn as `run --frames` draws it, PNG-encoded:
// the pictures users write, not a synthetic plate.
void BM_EncodeSceneFrame(benchmark::State& state, const char* scene_file) {
  const SceneDef scene = load_scene(std::string(PERIFLEX_SOURCE_ROOT) + "/scenes/" + scene_file);
  Simulation sim(scene);
  sim.initialize();
  for (int k = 0; k < 20; ++k) sim.step();
  Snapshot snapshot;
  sim.fill_snapshot(snapshot);
  RgbaImage image;
  {
    OffscreenRenderer renderer(1280, 720, 4);
    renderer.render(snapshot, fit_camera(snapshot, 1280, 720), RenderSettings(), image);
  }
  size_t bytes = 0;
  for (auto _ : state) bytes = encode_png(image).size();
  state.counters["png_kB"] = static_cast<double>(bytes) / 1e3;
}
BENCHMARK_CAPTURE(BM_EncodeSceneFrame, notched_plate, "notched_plate.toml")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_EncodeSceneFrame, slider_crank, "slider_crank.toml")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_EncodeSceneFrame, glass_branching, "glass_branching.toml")->Unit(benchmark::kMillisecond)->UseRealTime();

// Plates whose crack band sits somewhere else in each, so that consecutive frames differ (as they
// do in a run; identical frames would flatter the movie encoder).
std::vector<Snapshot> moving_crack_snapshots(int n, int count) {
  const Snapshot plate = plate_snapshot(n);
  std::vector<Snapshot> snapshots(count, plate);
  for (int k = 0; k < count; ++k) {
    Snapshot& s = snapshots[k];
    const float band = 0.2f + 0.6f * static_cast<float>(k) / static_cast<float>(count);
    for (size_t i = 0; i < s.px.size(); ++i) s.damage[i] = std::exp(-std::pow((s.px[i] - band) / 0.02f, 2.0f));
    s.time = 1e-3 * k;
    s.step = k;
  }
  return snapshots;
}

enum RecordOutputs { kPngSequence = 1, kMovie = 2 };

// End to end through the Recorder: kRecordFrames snapshots of N particles submitted as fast as the
// pipeline takes them, until every PNG is written and ffmpeg has closed the movie. The
// recorder's set-up (EGL context, ffmpeg start) is not timed. Per-frame busy times of each thread
// are reported beside the rate; they overlap.
constexpr int kRecordFrames = 60;

void BM_Record(benchmark::State& state, int outputs) {
  if ((outputs & kMovie) && find_ffmpeg().empty()) {
    state.SkipWithError("ffmpeg is not on PATH");
    return;
  }
  const int particles = 100000;
  const std::vector<Snapshot> snapshots = moving_crack_snapshots(particles, 8);
  const fs::path dir = fs::temp_directory_path() / ("periflex_record_bench_" + std::to_string(::getpid()));
  RecorderStats total;
  long frames = 0;
  for (auto _ : state) {
    state.PauseTiming();
    fs::remove_all(dir);
    fs::create_directories(dir);
    RecorderOptions options;
    options.width = 1280;
    options.height = 720;
    options.samples = default_samples(particles);
    if (outputs & kPngSequence) options.frames_dir = (dir / "frames").string();
    if (outputs & kMovie) options.movie_path = (dir / "movie.mp4").string();
    auto recorder = std::make_unique<Recorder>(options);
    state.ResumeTiming();

    for (int i = 0; i < kRecordFrames; ++i) recorder->submit(snapshots[i % snapshots.size()]);
    const RecorderStats stats = recorder->finish();

    state.PauseTiming();
    recorder.reset();
    frames += stats.frames;
    total.draw_seconds += stats.draw_seconds;
    total.png_seconds += stats.png_seconds;
    total.movie_seconds += stats.movie_seconds;
    total.submit_seconds += stats.submit_seconds;
    state.ResumeTiming();
  }
  fs::remove_all(dir);
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
  const double per_frame_ms = frames > 0 ? 1e3 / static_cast<double>(frames) : 0.0;
  state.counters["draw_ms"] = total.draw_seconds * per_frame_ms;
  state.counters["png_ms"] = total.png_seconds * per_frame_ms;
  state.counters["movie_ms"] = total.movie_seconds * per_frame_ms;
  state.counters["submit_ms"] = total.submit_seconds * per_frame_ms;
}
BENCHMARK_CAPTURE(BM_Record, png, kPngSequence)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Record, mp4, kMovie)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Record, png_and_mp4, kPngSequence | kMovie)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
