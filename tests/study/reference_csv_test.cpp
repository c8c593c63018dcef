// A reference trajectory from a CSV file: the interpolation between samples, and the files it
// refuses (each with the file, line, column and the column's name). The command as a user types
// it is in study_csv_reference_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "study/reference_csv.h"

namespace periflex {
namespace {

const SourceLocation kStudyKey{"s.toml", 4, 1, "study.reference_file"};

// Samples of f at irregular times from 0 to `end`, as text.
template <class F>
std::string sampled(F f, double end, double h) {
  std::ostringstream out;
  out.precision(17);
  out << "# a comment line\nt, probe.p.x ,other\n";
  for (int k = 0; k * h < end + h; ++k) {
    const double t = k == 0 ? 0.0 : k * h + 0.3 * h * std::sin(7.0 * k);  // increasing, uneven
    out << t << "," << f(t) << ",1\n";
  }
  return out.str();
}

TEST(ReferenceCsv, ReproducesAQuinticAndInterpolatesASineToItsBound) {
  const auto quintic = [](double t) { return 1.0 - 2.0 * t + 0.5 * t * t * t - 0.1 * std::pow(t, 5); };
  const ReferenceCsv poly = parse_reference_csv(sampled(quintic, 2.0, 0.1), "q.csv", "t", {"probe.p.x"}, kStudyKey);
  for (double t = 0.0; t <= 2.0; t += 0.0137) EXPECT_NEAR(poly.values(t)[0], quintic(t), 1e-12) << t;

  // sin(omega t) at omega h = 0.03: error below (omega h)^6 / 200 (with room for the uneven
  // spacing, whose widest gaps are 1.6 h)
  const double omega = 3.0, h = 0.01;
  const auto wave = [&](double t) { return std::sin(omega * t); };
  const ReferenceCsv sine = parse_reference_csv(sampled(wave, 5.0, h), "s.csv", "t", {"probe.p.x"}, kStudyKey);
  double worst = 0.0;
  for (double t = 0.0; t <= 5.0; t += 0.00731) worst = std::max(worst, std::abs(sine.values(t)[0] - wave(t)));
  std::printf("degree-5 interpolation of sin at omega h = 0.03: max error %.3g\n", worst);
  EXPECT_LT(worst, std::pow(1.6 * omega * h, 6) / 200.0);
  // a cubic through four points would miss by far more: the order is really six
  EXPECT_GT(worst, 0.0);
}

// The InputError a text raises, or an empty location when it raises none.
SourceLocation refusal(const std::string& text, std::string* message = nullptr) {
  try {
    parse_reference_csv(text, "ref.csv", "t", {"probe.p.x", "probe.p.y"}, kStudyKey);
  } catch (const InputError& e) {
    if (message) *message = e.what();
    return e.where();
  }
  return {};
}

TEST(ReferenceCsv, RefusesHostileFilesAtTheirLineAndColumn) {
  std::string message;
  // a missing column: named, with the columns the file has
  SourceLocation w = refusal("t,probe.p.x\n0,1\n1,2\n", &message);
  EXPECT_EQ(w.file, "ref.csv");
  EXPECT_EQ(w.line, 1);
  EXPECT_EQ(w.key, "probe.p.y");
  EXPECT_NE(message.find("its columns: t, probe.p.x"), std::string::npos) << message;
  // a word, a NaN, an infinity, an empty cell: line and column of the cell
  w = refusal("t,probe.p.x,probe.p.y\n0,1,2\n0.1,abc,2\n");
  EXPECT_EQ(w.line, 3);
  EXPECT_EQ(w.column, 5);
  EXPECT_EQ(w.key, "probe.p.x");
  EXPECT_EQ(refusal("t,probe.p.x,probe.p.y\n0,1,nan\n").line, 2);
  EXPECT_EQ(refusal("t,probe.p.x,probe.p.y\n0,1,2\n1,inf,2\n").line, 3);
  EXPECT_EQ(refusal("t,probe.p.x,probe.p.y\n0,1,2\n1,,2\n").column, 3);
  EXPECT_EQ(refusal("t,probe.p.x,probe.p.y\n0,1,2\n1,1e999,2\n").line, 3);
  EXPECT_EQ(refusal("t,probe.p.x,probe.p.y\n0,1,2\n1,1 2,2\n").line, 3);
  // times that stand still or go back
  w = refusal("t,probe.p.x,probe.p.y\n0,1,2\n0.5,1,2\n0.5,1,2\n", &message);
  EXPECT_EQ(w.line, 4);
  EXPECT_EQ(w.key, "t");
  EXPECT_NE(message.find("increase"), std::string::npos) << message;
  EXPECT_EQ(refusal("t,probe.p.x,probe.p.y\n0,1,2\n1,1,2\n0.9,1,2\n").line, 4);
  // a short row, an empty file, a single sample
  EXPECT_EQ(refusal("t,probe.p.x,probe.p.y\n0,1,2\n1,1\n").line, 3);
  EXPECT_EQ(refusal("").file, "ref.csv");
  EXPECT_EQ(refusal("# nothing\n\n").file, "ref.csv");
  EXPECT_EQ(refusal("t,probe.p.x,probe.p.y\n0,1,2\n").file, "ref.csv");
  // a file that holds a valid trajectory raises nothing
  EXPECT_TRUE(refusal("t,probe.p.x,probe.p.y\n0,1,2\n1,1,2\n").file.empty());
}

TEST(ReferenceCsv, RefusesAFileThatDoesNotCoverTheStudy) {
  const ReferenceCsv ref =
      parse_reference_csv("t,probe.p.x\n0.1,1\n0.5,1\n1.9,1\n", "ref.csv", "t", {"probe.p.x"}, kStudyKey);
  EXPECT_NO_THROW(ref.require_span(0.1, 1.9, kStudyKey));
  try {
    ref.require_span(0.0, 2.0, kStudyKey);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().key, "study.reference_file");
    EXPECT_NE(std::string(e.what()).find("covers t = 0.1 to 1.9 s, not the study's 0 to 2 s"), std::string::npos)
        << e.what();
  }
}

TEST(ReferenceCsv, RefusesFilesThatAreNotThere) {
  EXPECT_THROW(load_reference_csv("/nonexistent/ref.csv", "t", {"x"}, kStudyKey), InputError);
  EXPECT_THROW(load_reference_csv("/tmp", "t", {"x"}, kStudyKey), InputError);
  EXPECT_THROW(load_reference_csv("/dev/null", "t", {"x"}, kStudyKey), InputError);
}

}  // namespace
}  // namespace periflex
