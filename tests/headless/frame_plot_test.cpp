// The plot drawn into recorded frames, through the program as typed: `periflex run --render
// --plot driver_work,fracture` of the notched plate. The plot sits at the frames' top right; its
// two lines end where series.csv's values at the last frame put them on the plot's own axes,
// and a run without --plot has nothing there. Names that series.csv lacks are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "../cli/run_output_files.h"
#include "../cli/run_program.h"
#include "render/image.h"

namespace periflex::testing {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 640, kHeight = 480;
// where Renderer::draw_overlay puts the plot (a 640 x 480 frame: 288 x 192 pixels at 8 from the
// top right corner) and its inner frame (margins 62 left, 8 top, 12 right, 36 below)
constexpr float kPlotW = 0.45f * kWidth, kPlotH = 0.4f * kHeight;
constexpr float kOriginX = kWidth - kPlotW - 8.0f, kOriginY = 8.0f;
constexpr float kInnerX1 = kOriginX + kPlotW - 12.0f;
constexpr float kInnerY0 = kOriginY + 8.0f, kInnerY1 = kOriginY + kPlotH - 36.0f;

// the last frame of a run to 0.6 ms, a frame every 0.05 ms, with `extra` flags
RgbaImage last_frame(const std::string& name, const std::string& extra, fs::path& out) {
  out = fresh_directory("frame_plot_" + name);
  const auto r = run_periflex("run " + scene("notched_plate.toml") + " --until 6e-4 --render --frame-every 5e-5" +
                              " --frames " + (out / "frames").string() + " --size " + std::to_string(kWidth) + "x" +
                              std::to_string(kHeight) + " --camera 0,0,0.12 --quiet --out " + out.string() + " " +
                              extra);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return read_png((out / "frames" / "frame_000012.png").string());
}

// the plot's first two colours (render/plot_drawing.cpp), not the grips' orange edges
bool orange(const uint8_t* p) { return p[0] > 235 && p[1] > 180 && p[1] < 205 && p[2] < 90; }
bool blue(const uint8_t* p) { return p[0] < 130 && p[1] > 130 && p[1] < 200 && p[2] > 220; }

// the pixel rows of a colour in the last columns of the inner frame (where the lines end)
std::vector<int> line_end_rows(const RgbaImage& image, bool (*is)(const uint8_t*)) {
  std::vector<int> rows;
  for (int x = int(kInnerX1) - 3; x <= int(kInnerX1); ++x)
    for (int y = int(kInnerY0); y <= int(kInnerY1); ++y)
      if (is(image.at(x, y))) rows.push_back(y);
  return rows;
}

int count_in_plot(const RgbaImage& image, bool (*is)(const uint8_t*)) {
  int n = 0;
  for (int y = int(kOriginY); y < int(kOriginY + kPlotH); ++y)
    for (int x = int(kOriginX); x < int(kOriginX + kPlotW); ++x) n += is(image.at(x, y));
  return n;
}

TEST(FramePlot, TwoSeriesEndWhereSeriesCsvPutsThem) {
  fs::path plain_out, plot_out;
  const RgbaImage plain = last_frame("plain", "", plain_out);
  const RgbaImage plotted = last_frame("two", "--plot driver_work,fracture", plot_out);
  ASSERT_EQ(plotted.width, kWidth);
  // the lines and the legend in their colours, (nearly) none of them without --plot
  const int plain_orange = count_in_plot(plain, orange), plain_blue = count_in_plot(plain, blue);
  std::printf("plot colours: %d orange and %d blue pixels, %d and %d without --plot\n",
              count_in_plot(plotted, orange), count_in_plot(plotted, blue), plain_orange, plain_blue);
  EXPECT_GT(count_in_plot(plotted, orange), plain_orange + 100);
  EXPECT_GT(count_in_plot(plotted, blue), plain_blue + 100);

  // the y axis spans both series over the frames' instants (k * 0.05 ms), 5% more each side
  const Series s = read_series(plot_out / "series.csv");
  const int t = s.column("t"), work = s.column("driver_work"), fracture = s.column("fracture");
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, last_work = 0, last_fracture = 0;
  int frames = 0;
  for (const auto& row : s.rows) {
    const double k = row[t] / 5e-5;
    if (std::fabs(k - std::round(k)) > 1e-6) continue;
    ++frames;
    lo = std::min({lo, row[work], row[fracture]});
    hi = std::max({hi, row[work], row[fracture]});
    last_work = row[work], last_fracture = row[fracture];
  }
  ASSERT_EQ(frames, 13) << "series.csv rows at the frames' instants";
  ASSERT_GT(last_fracture, 0.0) << "the crack has not started: the test would not tell the lines apart";
  const double pad = 0.05 * (hi - lo);
  lo -= pad, hi += pad;
  const auto pixel_row = [&](double v) { return kInnerY1 - (v - lo) / (hi - lo) * (kInnerY1 - kInnerY0); };
  for (const auto& [name, rows, value] : {std::tuple{"driver_work", line_end_rows(plotted, orange), last_work},
                                          std::tuple{"fracture", line_end_rows(plotted, blue), last_fracture}}) {
    ASSERT_FALSE(rows.empty()) << name << ": no line at the plot's right edge";
    const double expected = pixel_row(value);
    int nearest = rows.front();
    for (int y : rows)
      if (std::fabs(y - expected) < std::fabs(nearest - expected)) nearest = y;
    std::printf("%s = %.4g J at t = 0.6 ms: drawn at row %d, expected %.1f\n", name, value, nearest, expected);
    EXPECT_NEAR(nearest, expected, 2.5) << name;
  }
}

TEST(FramePlot, UnknownColumnAndPlotWithoutFramesAreRefused) {
  const auto out = fresh_directory("frame_plot_bad");
  auto r = run_periflex("run " + scene("pendulum.toml") + " --until 0.1 --render --plot kinetic,lots --quiet --out " +
                        out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--plot"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'lots'"), std::string::npos) << r.output;
  r = run_periflex("run " + scene("pendulum.toml") + " --until 0.1 --plot kinetic --quiet --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--plot"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace periflex::testing
