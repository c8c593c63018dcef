// Off-screen drawing and recording speed on the software renderer (Mesa llvmpipe through EGL):
//   BM_DrawParticles/N          draw N particles at 1280x720 (goal: 250k at >= 30 frames/s)
//   BM_RenderAndEncodePng/N     draw, read back and PNG-encode N particles at 1280x720, serially
//   BM_EncodePng/N              PNG-encode one rendered 1280x720 frame of N particles
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "headless/offscreen_renderer.h"
#include "render/image.h"
#include "render/view.h"

namespace periflex {
namespace {

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

}  // namespace
}  // namespace periflex

BENCHMARK_MAIN();
