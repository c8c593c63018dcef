// Checks a screenshot written by `periflex gui --screenshot`, for the GUI smoke tests:
//
//   gui_png_check IMAGE                      not blank: several distinct colours, and a good
//                                            share of pixels that are not the background
//   gui_png_check IMAGE --crack SCENE        also: damage-coloured pixels in the ligament above
//                                            the scene's first notch (the crack has grown)
//   gui_png_check IMAGE --no-crack SCENE     the opposite, for a picture taken before the crack
//                                            grows (proves the crack check can fail)
//   gui_png_check IMAGE --overlay            also: the overlay is drawn at the picture's left
//                                            edge (scene name and time box at the top, colour
//                                            legend at the bottom), as on screenshots and
//                                            recorded frames of a scene with particles
//   gui_png_check IMAGE --no-overlay         the opposite, for a picture drawn without it
//                                            (proves the overlay check can fail)
//   gui_png_check IMAGE --plot               the plot is drawn over the picture: pixels of the first
//                                            series' line inside the plot's box at the top right
//                                            (render/overlay_layout.h plot_box), below its title
//   gui_png_check IMAGE --no-plot            the opposite, for a picture drawn without it
//   gui_png_check IMAGE --grip-holds         the leftmost virtual body's outline encloses the
//                                            particles it holds (a magnified deformation)
//   gui_png_check IMAGE --lower-edge-spread MIN MAX
//                                            the lowest drawn row of each column of the middle
//                                            70 % of what is drawn varies by MIN to MAX pixels:
//                                            a flat lower edge (0 3: the particle discs
//                                            scallop it) or a bent one (20 1000)
//
// The notch is found where the GUI draws it: the scene is built, its first snapshot framed with
// the GUI's own fit_camera_beside_panels for the image's size. Exit code 0 pass, 1 fail, 2 usage.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/view_fit.h"
#include "core/resources.h"
#include "io/image.h"
#include "render/overlay_layout.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "solve/simulation.h"

namespace {

using namespace periflex;

// Share of non-background pixels a drawn scene has at least in the part of the window the GUI
// frames it in (right of the panel column; the overlay sits left of it, so text alone cannot
// pass): a blank picture has none there, while the thinnest shipped scene (a double pendulum
// of slender links framed with the whole reach of its swing) still covers about 0.3 percent.
// And distinct colours: the overlay alone gives three (background, its shaded boxes, its solid
// text, which has no blended edges), while the plainest shipped scene (the rigid pendulum,
// window screenshot without multisampling) adds fills, outlines and markers for seven.
constexpr double kMinForeground = 0.001;
constexpr size_t kMinColours = 6;
// A pixel is "damage-coloured" when the nearest colour-map entry lies within this RGB distance
// and sits at or above this point of the map; undamaged particles sit at 0, anti-aliased edges
// blend towards the dark background, so neither reaches it.
constexpr double kColourMatch = 30.0;
constexpr double kDamagedFrom = 0.4;
// Pixels needed to call a region damaged: a few broken-off particle discs.
constexpr long kMinDamagedPixels = 20;
// The overlay as Renderer::draw_overlay lays it out from the top-left corner: a shaded box from
// (6, 6) holding the scene name and the time in near-white text (a line of the default 13 px
// font each), and at the bottom left a colour bar from x = 12, its lower edge 29 px above the
// bottom. Text needs this many near-white pixels in the box, the bar this many distinct colours.
constexpr int kBoxLeft = 6, kBoxTop = 6, kBoxRight = 200, kBoxBottom = 40;
constexpr long kMinTextPixels = 40;
constexpr int kBarLeft = 16, kBarRight = 200, kBarFromBottom = 35;
constexpr size_t kMinBarColours = 16;

int usage() {
  std::fprintf(stderr,
               "usage: gui_png_check IMAGE [--crack SCENE | --no-crack SCENE | --overlay | --no-overlay |\n"
               "                             --lower-edge-spread MIN MAX | --grip-holds | --plot | --no-plot]\n");
  return 2;
}

bool check_not_blank(const RgbaImage& image) {
  // background: the default renderer background colour
  const RenderSettings defaults;
  int bg[3];
  for (int c = 0; c < 3; ++c) bg[c] = int(std::lround(defaults.background[c] * 255));
  std::set<uint32_t> colours;
  long foreground = 0, framed = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = image.at(x, y);
      colours.insert(uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2]);
      ++framed;
      if (std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]) > 12) ++foreground;
    }
  }
  const double share = framed ? double(foreground) / double(framed) : 0.0;
  std::printf("%zu distinct colours, %.2f%% non-background pixels\n", colours.size(),
              100.0 * share);
  bool ok = true;
  if (colours.size() < kMinColours) {
    std::printf("FAIL: fewer than %zu colours: the picture is blank\n", kMinColours);
    ok = false;
  }
  if (share < kMinForeground) {
    std::printf("FAIL: below %.1f%% non-background pixels: nothing drawn\n", 100.0 * kMinForeground);
    ok = false;
  }
  return ok;
}

// Damage-coloured pixels in a box of the ligament: from 4 mm (beyond one horizon of the 1 mm grid
// the shipped notched plate uses, so the notch's own cut bonds do not count) to 10 mm above the
// notch tip, 4 mm either side.
long damaged_pixels_above_notch(const RgbaImage& image, const std::string& scene_path) {
  const SceneDef scene = load_scene(scene_path);
  if (scene.flex_bodies.empty() || scene.flex_bodies[0].notches.empty()) {
    throw std::runtime_error(scene_path + " has no notched flexible body");
  }
  Simulation sim(scene);
  sim.initialize();
  Snapshot first;
  sim.fill_snapshot(first);
  // the picture the window writes: its first view, without the panels
  const Camera camera =
      picture_camera(fit_camera_beside_panels(first, image.width, image.height, kPanelWidth), image.height);

  // the notch end inside the body is its tip
  const FlexBodyDef& body = scene.flex_bodies[0];
  const NotchDef& notch = body.notches[0];
  const Vec2 tip = body.shape.contains(notch.p1) ? notch.p1 : notch.p2;
  const Vec2 base = body.shape.contains(notch.p1) ? notch.p2 : notch.p1;
  const Vec2 up = (tip - base).normalized();
  const Vec2 across = perp(up);

  // the colour map the GUI draws damage with by default
  const std::string map_path =
      find_resource_root() + "/assets/colormaps/" + RenderSettings{}.colormap + ".png";
  const RgbaImage map = read_png(map_path);

  std::set<std::pair<int, int>> damaged;  // distinct pixels: the sampling is finer than a pixel
  for (double along = 4e-3; along <= 10e-3; along += 0.1e-3) {
    for (double side = -4e-3; side <= 4e-3; side += 0.1e-3) {
      const Vec2 px = camera.to_pixels(tip + along * up + side * across, image.width, image.height);
      const int x = int(px.x()), y = int(px.y());
      if (x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
      const uint8_t* p = image.at(x, y);
      // nearest colour-map entry
      double best = 1e30;
      int best_i = 0;
      for (int i = 0; i < map.width; ++i) {
        const uint8_t* m = map.at(i, 0);
        const double d = std::hypot(double(p[0] - m[0]), double(p[1] - m[1]), double(p[2] - m[2]));
        if (d < best) best = d, best_i = i;
      }
      if (best <= kColourMatch && double(best_i) / (map.width - 1) >= kDamagedFrom) damaged.insert({x, y});
    }
  }
  return static_cast<long>(damaged.size());
}

// Whether the overlay's two parts are in the picture: near-white text in the name and time box,
// and a row of the colour legend with many colours (the scene itself, framed beside them, is
// background there).
struct OverlaySeen {
  long text_pixels = 0;
  size_t bar_colours = 0;
  bool box() const { return text_pixels >= kMinTextPixels; }
  bool legend() const { return bar_colours >= kMinBarColours; }
};

OverlaySeen find_overlay(const RgbaImage& image) {
  OverlaySeen seen;
  for (int y = kBoxTop; y < std::min(kBoxBottom, image.height); ++y) {
    for (int x = kBoxLeft; x < std::min(kBoxRight, image.width); ++x) {
      const uint8_t* p = image.at(x, y);
      if (p[0] >= 200 && p[1] >= 200 && p[2] >= 200) ++seen.text_pixels;
    }
  }
  std::set<uint32_t> colours;
  const int y = image.height - kBarFromBottom;
  for (int x = kBarLeft; y >= 0 && x < std::min(kBarRight, image.width); ++x) {
    const uint8_t* p = image.at(x, y);
    colours.insert(uint32_t(p[0]) << 16 | uint32_t(p[1]) << 8 | p[2]);
  }
  seen.bar_colours = colours.size();
  return seen;
}

// How many pixels the lower edge of what is drawn rises and falls over the middle 70 % of its
// width (the ends carry grips, markers and probes). The lowest drawn pixel of each column is
// searched from kEdgeSearchFromBottom pixels above the bottom, clear of the colour legend and
// the scale bar, down to the name and time box at the top (kEdgeSearchTop), which is not counted.
// -1 when nothing is drawn.
constexpr int kEdgeSearchFromBottom = 70, kEdgeSearchTop = 80;

int lower_edge_spread(const RgbaImage& image) {
  const RenderSettings defaults;
  int bg[3];
  for (int c = 0; c < 3; ++c) bg[c] = int(std::lround(defaults.background[c] * 255));
  std::vector<int> edge(image.width, -1);
  for (int x = 0; x < image.width; ++x) {
    for (int y = image.height - kEdgeSearchFromBottom; y >= kEdgeSearchTop; --y) {
      const uint8_t* p = image.at(x, y);
      if (std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]) > 60) {
        edge[x] = y;
        break;
      }
    }
  }
  int first = -1, last = -1;
  for (int x = 0; x < image.width; ++x)
    if (edge[x] >= 0) {
      if (first < 0) first = x;
      last = x;
    }
  if (first < 0) return -1;
  const int margin = (last - first) * 15 / 100;
  int lo = image.height, hi = -1;
  for (int x = first + margin; x <= last - margin; ++x) {
    if (edge[x] < 0) continue;
    lo = std::min(lo, edge[x]);
    hi = std::max(hi, edge[x]);
  }
  std::printf("lower edge between rows %d and %d over columns %d .. %d\n", lo, hi, first + margin, last - margin);
  return hi >= lo ? hi - lo : -1;
}

// Whether the leftmost grip (a virtual body: an orange dashed outline) encloses the particles it
// holds (magenta rings), within 2 pixels, as it does when it is drawn with its magnified
// particles. The held particles are the magenta pixels of the left half of their spread; the
// outline is looked for within 40 pixels of them (clear of the legend's orange).
bool grip_holds_its_particles(const RgbaImage& image) {
  const auto magenta = [](const uint8_t* p) { return p[0] > 170 && p[1] < 140 && p[2] > 170; };
  const auto orange = [](const uint8_t* p) { return p[0] > 200 && p[1] > 140 && p[1] < 200 && p[2] < 110; };
  int lo = image.width, hi = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (magenta(image.at(x, y))) lo = std::min(lo, x), hi = std::max(hi, x);
  if (hi < lo) {
    std::printf("no held particles drawn\n");
    return false;
  }
  int held[4] = {image.width, image.height, -1, -1}, grip[4] = {image.width, image.height, -1, -1};
  for (int y = 0; y < image.height; ++y)
    for (int x = lo; x <= (lo + hi) / 2; ++x)
      if (magenta(image.at(x, y)))
        held[0] = std::min(held[0], x), held[1] = std::min(held[1], y), held[2] = std::max(held[2], x),
        held[3] = std::max(held[3], y);
  for (int y = std::max(0, held[1] - 40); y < std::min(image.height, held[3] + 40); ++y)
    for (int x = std::max(0, held[0] - 40); x < std::min(image.width, held[2] + 40); ++x)
      if (orange(image.at(x, y)))
        grip[0] = std::min(grip[0], x), grip[1] = std::min(grip[1], y), grip[2] = std::max(grip[2], x),
        grip[3] = std::max(grip[3], y);
  std::printf("held particles x %d..%d y %d..%d, grip outline x %d..%d y %d..%d\n", held[0], held[2], held[1],
              held[3], grip[0], grip[2], grip[1], grip[3]);
  return grip[2] >= grip[0] && grip[0] <= held[0] + 2 && grip[2] >= held[2] - 2 && grip[1] <= held[1] + 2 &&
         grip[3] >= held[3] - 2;
}

// Pixels within 40 (summed over r, g, b) of the first series' colour in the lower 60 % of the
// plot's box: the box's background hides the scene under it to a seventh of its brightness, and
// the title in that colour sits at the top, so only the series' line comes near it there.
long plot_line_pixels(const RgbaImage& image) {
  PlotPoint origin, size;
  plot_box(0, image.width, image.height, origin, size);
  const Rgba8 line = plot_colour(0);
  long n = 0;
  for (int y = static_cast<int>(origin.y + 0.4f * size.y); y < static_cast<int>(origin.y + size.y) && y < image.height;
       ++y) {
    for (int x = static_cast<int>(origin.x); x < static_cast<int>(origin.x + size.x) && x < image.width; ++x) {
      const unsigned char* p = &image.pixels[4 * (static_cast<size_t>(y) * image.width + x)];
      if (std::abs(p[0] - line.r) + std::abs(p[1] - line.g) + std::abs(p[2] - line.b) < 40) ++n;
    }
  }
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 5) return usage();
  const std::string mode = argc >= 3 ? argv[2] : "";
  if (mode == "--grip-holds") {
    try {
      const bool ok = argc == 3 && grip_holds_its_particles(read_png(argv[1]));
      std::printf("%s: the grip %s its particles: %s\n", argv[1], ok ? "holds" : "does not hold", ok ? "PASS" : "FAIL");
      return ok ? 0 : 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gui_png_check: %s\n", e.what());
      return 1;
    }
  }
  if (mode == "--plot" || mode == "--no-plot") {
    try {
      const long pixels = argc == 3 ? plot_line_pixels(read_png(argv[1])) : -1;
      const bool ok = pixels >= 0 && (mode == "--plot" ? pixels >= 30 : pixels == 0);
      std::printf("%s: %ld pixels of the plot's line in its box: %s\n", argv[1], pixels, ok ? "PASS" : "FAIL");
      return ok ? 0 : 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gui_png_check: %s\n", e.what());
      return 1;
    }
  }
  if (mode == "--lower-edge-spread") {
    if (argc != 5) return usage();
    try {
      const RgbaImage image = read_png(argv[1]);
      const int spread = lower_edge_spread(image);
      const int lo = std::atoi(argv[3]), hi = std::atoi(argv[4]);
      std::printf("%s: lower edge spread %d px, asked %d .. %d: %s\n", argv[1], spread, lo, hi,
                  spread >= lo && spread <= hi ? "PASS" : "FAIL");
      return spread >= lo && spread <= hi ? 0 : 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gui_png_check: %s\n", e.what());
      return 1;
    }
  }
  const bool scene_mode = mode == "--crack" || mode == "--no-crack";
  const bool overlay_mode = mode == "--overlay" || mode == "--no-overlay";
  if (argc == 5 || (argc == 4 && !scene_mode)) return usage();
  if (argc == 3 && !overlay_mode) return usage();
  try {
    const RgbaImage image = read_png(argv[1]);
    std::printf("%s: %d x %d\n", argv[1], image.width, image.height);
    bool ok = check_not_blank(image);
    if (overlay_mode) {
      const OverlaySeen seen = find_overlay(image);
      std::printf("overlay: %ld text pixels in the name and time box, %zu colours along the legend\n",
                  seen.text_pixels, seen.bar_colours);
      if (mode == "--overlay" && !(seen.box() && seen.legend())) {
        const char* missing = !seen.box() && !seen.legend() ? "the name and time box and the colour legend"
                              : !seen.box()                  ? "the name and time box"
                                                             : "the colour legend";
        std::printf("FAIL: the overlay is missing (%s not found)\n", missing);
        ok = false;
      }
      if (mode == "--no-overlay" && (seen.box() || seen.legend())) {
        std::printf("FAIL: overlay-like pixels in a picture drawn without the overlay\n");
        ok = false;
      }
    }
    if (scene_mode) {
      const long damaged = damaged_pixels_above_notch(image, argv[3]);
      std::printf("%ld damage-coloured pixels in the ligament above the notch\n", damaged);
      if (mode == "--crack" && damaged < kMinDamagedPixels) {
        std::printf("FAIL: no crack drawn above the notch (need %ld)\n", kMinDamagedPixels);
        ok = false;
      }
      if (mode == "--no-crack" && damaged >= kMinDamagedPixels) {
        std::printf("FAIL: damage drawn above the notch before the crack can have grown\n");
        ok = false;
      }
    }
    std::printf("%s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gui_png_check: %s\n", e.what());
    return 1;
  }
}
