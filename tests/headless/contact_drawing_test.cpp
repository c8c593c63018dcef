// `periflex run --render --draw-contacts`: the active contacts drawn into the picture, as a user
// asks for them. The slug of scenes/projectile_plate.toml at 10 us is pushing into the glass;
// its screenshot with the flag must hold the contact colour (a dot and a stroke per contact),
// the one without it none, and the rest of the picture must be the same.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../cli/run_program.h"
#include "io/image.h"

namespace periflex {
namespace {

using testing::fresh_directory;
using testing::run_periflex;
using testing::scene;

// Pixels of the contacts' colour (0, 255, 160), within the anti-aliasing of their edges.
long contact_pixels(const RgbaImage& image) {
  long n = 0;
  for (size_t i = 0; i + 3 < image.pixels.size(); i += 4) {
    const int r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
    if (r < 60 && g > 200 && b > 110 && b < 210) ++n;
  }
  return n;
}

TEST(ContactDrawing, DrawContactsFlagDrawsTheActiveContactsAndNothingElse) {
  const auto dir = fresh_directory("contact_drawing");
  const auto shot = [&](const std::string& name, const std::string& extra) {
    const auto png = dir / (name + ".png");
    const auto r = run_periflex("run " + scene("projectile_plate.toml") +
                                " --until 1e-5 --snapshot-at 1e-5 --size 320x240 --camera 0,0,0.02 --screenshot " +
                                png.string() + " --quiet --out " + (dir / name).string() + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return read_png(png.string());
  };
  const RgbaImage plain = shot("plain", "");
  const RgbaImage drawn = shot("drawn", " --draw-contacts");
  ASSERT_EQ(plain.width, drawn.width);
  EXPECT_EQ(contact_pixels(plain), 0);
  EXPECT_GT(contact_pixels(drawn), 20) << "no contact drawn";
  // what differs is the contacts' marks only: a small part of the picture
  long differing = 0;
  for (size_t i = 0; i < plain.pixels.size(); i += 4)
    differing += plain.pixels[i] != drawn.pixels[i] || plain.pixels[i + 1] != drawn.pixels[i + 1] ||
                 plain.pixels[i + 2] != drawn.pixels[i + 2];
  EXPECT_LT(differing, static_cast<long>(plain.pixels.size() / 4 / 10));
}

}  // namespace
}  // namespace periflex
