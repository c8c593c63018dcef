// `periflex run --checkpoint-every T` and `--restart FILE`, run as a user types them: a run
// continued from one of its checkpoints writes the rows of the uninterrupted run bit for bit (a
// rigid mechanism, the notched plate while it cracks, the glass plate at one and two threads,
// with steps that do not divide T); files of another scene, version or format, truncated or
// damaged ones are refused with exit 2 naming the file and the reason; an interrupted run leaves
// only whole checkpoints, one of them the state it reached, from which it resumes (into its own
// folder: a series.csv of the whole run).
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "child_run.h"
#include "output/checkpoint_file.h"
#include "run_output_files.h"
#include "run_program.h"

namespace periflex {
namespace {

namespace fs = std::filesystem;
using testing::fresh_directory;
using testing::read_text;
using testing::run_child;
using testing::run_periflex;
using testing::scene;

std::vector<std::string> lines_of(const fs::path& file) {
  std::vector<std::string> lines;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The checkpoint files of a folder, in order.
std::vector<fs::path> checkpoints_in(const fs::path& dir) { return testing::files_with_extension(dir, ".pfstate"); }

double row_time(const std::string& row) { return std::stod(row.substr(0, row.find(','))); }

// Runs `args` with checkpoints every `every`, continues from checkpoint `pick` (1-based) into
// another folder, and expects the continued series to be the rows of the first run from the
// checkpoint's time on, text for text. Returns the continued rows.
std::vector<std::string> expect_restart_repeats(const std::string& name, std::vector<std::string> args,
                                                const std::string& every, size_t pick) {
  const fs::path dir = fresh_directory("checkpoint_" + name);
  std::vector<std::string> first = args;
  first.insert(first.end(), {"--quiet", "--out", (dir / "first").string(), "--checkpoint-every", every});
  const auto a = run_child(first, 120);
  EXPECT_EQ(a.exit_code, 0) << a.output;
  const auto files = checkpoints_in(dir / "first" / "checkpoints");
  EXPECT_GE(files.size(), pick) << a.output;
  if (files.size() < pick) return {};
  std::vector<std::string> again = args;
  again.insert(again.end(), {"--quiet", "--out", (dir / "again").string(), "--restart", files[pick - 1].string()});
  const auto b = run_child(again, 120);
  EXPECT_EQ(b.exit_code, 0) << b.output;

  const auto whole = lines_of(dir / "first" / "series.csv");
  const auto continued = lines_of(dir / "again" / "series.csv");
  EXPECT_GE(continued.size(), 3u);
  if (continued.size() < 2 || whole.empty()) return {};
  EXPECT_EQ(continued[0], whole[0]);  // the same columns
  CheckpointHeader header;
  read_checkpoint(files[pick - 1].string(), header);
  std::vector<std::string> tail;
  for (size_t k = 1; k < whole.size(); ++k)
    if (row_time(whole[k]) >= header.time) tail.push_back(whole[k]);
  const std::vector<std::string> rows(continued.begin() + 1, continued.end());
  EXPECT_EQ(rows.size(), tail.size());
  for (size_t k = 0; k < std::min(rows.size(), tail.size()); ++k) {
    EXPECT_EQ(rows[k], tail[k]) << "row " << k << " after the checkpoint at t = " << header.time;
    if (rows[k] != tail[k]) break;
  }
  return rows;
}

// broken_bonds of the first continued row
long broken_in(const std::vector<std::string>& rows, const std::string& header_line) {
  size_t column = 0, at = 0;
  for (size_t next; (next = header_line.find(',', at)) != std::string::npos; at = next + 1, ++column)
    if (header_line.substr(at, next - at) == "broken_bonds") break;
  std::string row = rows.front();
  for (size_t k = 0; k < column; ++k) row = row.substr(row.find(',') + 1);
  return std::stol(row.substr(0, row.find(',')));
}

TEST(Checkpoint, RigidMechanismContinuesBitForBit) {
  // dt = 7e-4 divides neither T nor the output interval
  expect_restart_repeats("rigid", {"run", scene("slider_crank.toml"), "--until", "1.2", "--dt", "7e-4"}, "0.3337", 2);
}

TEST(Checkpoint, CrackingPlateContinuesBitForBit) {
  const auto rows = expect_restart_repeats(
      "plate", {"run", scene("notched_plate.toml"), "--until", "9e-4"}, "3.53e-4", 2);
  ASSERT_FALSE(rows.empty());
  const fs::path again = fs::current_path() / "cli_test_out_checkpoint_plate" / "again";
  const auto header = lines_of(again / "series.csv")[0];
  EXPECT_GT(broken_in(rows, header), 0) << "the crack has not started by the checkpoint";
  // the summary says where the run came from, and its speed counts the steps it took
  const auto summary = testing::read_summary(again / "summary.json");
  EXPECT_NE(summary["restarted_from"].get<std::string>().find("checkpoint_000002"), std::string::npos);
  const long first = summary["first_step"].get<long>(), steps = summary["steps"].get<long>();
  EXPECT_GT(first, 1000);
  EXPECT_NEAR(summary["steps_per_second"].get<double>(), (steps - first) / summary["solver_time"].get<double>(),
              1e-6 * summary["steps_per_second"].get<double>());
}

TEST(Checkpoint, GlassPlateContinuesBitForBitOnOneAndTwoThreads) {
  for (const char* threads : {"1", "2"}) {
    SCOPED_TRACE(threads);
    const auto rows = expect_restart_repeats(
        std::string("glass") + threads,
        {"run", scene("glass_branching.toml"), "--set", "flex_body.plate.grid_spacing=5e-4", "--set",
         "flex_body.plate.horizon_ratio=3", "--dt", "5e-8", "--until", "1.2e-5", "--threads", threads},
        "4.13e-6", 2);
    ASSERT_FALSE(rows.empty());
    const auto header = lines_of(fs::current_path() / ("cli_test_out_checkpoint_glass" + std::string(threads)) /
                                 "again" / "series.csv")[0];
    EXPECT_GT(broken_in(rows, header), 0);
  }
}

// A checkpoint of the pendulum, written once for the refusal tests.
fs::path pendulum_checkpoint(const fs::path& dir) {
  const auto r = run_periflex("run " + scene("pendulum.toml") + " --until 0.5 --quiet --out " + (dir / "run").string() +
                              " --checkpoint-every 0.2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return dir / "run" / "checkpoints" / "checkpoint_000002_t0.4.pfstate";
}

// Runs the pendulum from `file` with `extra` flags; expects exit 2 and a message naming the
// file and containing `reason`.
void expect_refused(const fs::path& file, const std::string& reason, const std::string& scene_file = "pendulum.toml",
                    const std::string& extra = "") {
  const auto r = run_periflex("run " + scene(scene_file) + " --quiet --out " + (file.parent_path() / "out").string() +
                              " --restart " + file.string() + " " + extra);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(file.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(reason), std::string::npos) << "expected '" << reason << "' in: " << r.output;
  EXPECT_NE(r.output.find("--restart"), std::string::npos) << r.output;
}

fs::path copy_with(const fs::path& from, const fs::path& to, const std::function<void(std::string&)>& edit) {
  std::string bytes = read_text(from);
  edit(bytes);
  std::ofstream(to, std::ios::binary) << bytes;
  return to;
}

TEST(Checkpoint, ForeignTruncatedDamagedAndOtherVersionsAreRefused) {
  const fs::path dir = fresh_directory("checkpoint_refusals");
  const fs::path good = pendulum_checkpoint(dir);
  ASSERT_TRUE(fs::exists(good));
  // the file itself continues
  const auto ok = run_periflex("run " + scene("pendulum.toml") + " --quiet --out " + (dir / "ok").string() +
                               " --restart " + good.string());
  EXPECT_EQ(ok.exit_code, 0) << ok.output;

  // another scene, or the same one with another override
  expect_refused(good, "another scene", "four_bar.toml");
  expect_refused(good, "another scene", "pendulum.toml", "--set solver.dt=5e-4");
  // cut off, damaged, not a checkpoint at all
  expect_refused(copy_with(good, dir / "cut.pfstate", [](std::string& b) { b.resize(b.size() * 2 / 3); }), "truncated");
  expect_refused(copy_with(good, dir / "damaged.pfstate", [](std::string& b) { b[b.size() - 10] ^= 0x20; }), "damaged");
  expect_refused(copy_with(good, dir / "text.pfstate", [](std::string& b) { b = "[scene]\nname = \"x\"\n"; }),
                 "not a periflex checkpoint");
  // another format version (the four bytes after the magic)
  expect_refused(copy_with(good, dir / "format.pfstate", [](std::string& b) { b[8] = 7; }), "format version 7");
  // another program version: the state rewritten under another version's header
  CheckpointHeader header;
  const SimState state = read_checkpoint(good.string(), header);
  header.program_version = "0.0.1";
  write_checkpoint((dir / "old.pfstate").string(), header, state);
  expect_refused(dir / "old.pfstate", "written by periflex 0.0.1");
  // a state after the end asked for: nothing to run, which a run did silently before
  const auto past = run_periflex("run " + scene("pendulum.toml") + " --quiet --out " + (dir / "past").string() +
                                 " --restart " + good.string() + " --until 0.3");
  EXPECT_EQ(past.exit_code, 2) << past.output;
  EXPECT_NE(past.output.find("'--until'"), std::string::npos) << past.output;
  EXPECT_NE(past.output.find("its state is at t = 0.4 s, after the run's end time 0.3 s"), std::string::npos)
      << past.output;
  // a missing file
  const auto missing = run_periflex("run " + scene("pendulum.toml") + " --quiet --restart " + (dir / "none").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("--restart"), std::string::npos) << missing.output;
}

// A scene whose body is read from a point file: its checkpoint continues while the file is the
// same, and is refused, naming the file, once the file has changed (the state's particles may then
// be other ones, or in another order, as here).
TEST(Checkpoint, RefusedWhenTheShapesFileChanged) {
  const fs::path dir = fresh_directory("checkpoint_shape_file");
  fs::create_directories(dir / "specimens");
  fs::copy_file(scene("brazilian_disc_points.toml"), dir / "disc.toml");
  const fs::path points = dir / "specimens" / "brazilian_disc_mm.txt";
  fs::copy_file(scene("specimens/brazilian_disc_mm.txt"), points);
  const std::string run = "run " + (dir / "disc.toml").string() + " --quiet --until 3e-6 ";
  const auto first = run_periflex(run + "--checkpoint-every 1.5e-6 --out " + (dir / "first").string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto files = checkpoints_in(dir / "first" / "checkpoints");
  ASSERT_GE(files.size(), 1u);
  const auto same = run_periflex(run + "--out " + (dir / "same").string() + " --restart " + files[0].string());
  EXPECT_EQ(same.exit_code, 0) << same.output;
  // two points of the file swapped, the scene file untouched: as many particles, each the other's
  copy_with(points, points, [](std::string& text) {
    const std::string a = "-1.7500 -9.7500 1.2500 1\n", b = "-1.2500 -9.7500 1.2500 1\n";
    const size_t at = text.find(a + b);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, a.size() + b.size(), b + a);
  });
  const auto changed = run_periflex(run + "--out " + (dir / "changed").string() + " --restart " + files[0].string());
  EXPECT_EQ(changed.exit_code, 2) << changed.output;
  EXPECT_NE(changed.output.find("--restart"), std::string::npos) << changed.output;
  EXPECT_NE(changed.output.find("brazilian_disc_mm.txt"), std::string::npos) << changed.output;
  EXPECT_NE(changed.output.find("changed since"), std::string::npos) << changed.output;
}

TEST(Checkpoint, BadFlagValuesExitTwoNamingTheFlag) {
  for (const std::string& flags :
       {std::string("--checkpoint-every -1"), std::string("--checkpoint-every nan"), std::string("--checkpoint-every 1e400"),
        std::string("--checkpoint-dir somewhere"), std::string("--checkpoint-every 1e-9")}) {
    const auto r = run_periflex("run " + scene("pendulum.toml") + " --quiet --out cli_test_out_checkpoint_flags " + flags);
    EXPECT_EQ(r.exit_code, 2) << flags << ": " << r.output;
    EXPECT_NE(r.output.find(flags.substr(0, flags.find(' '))), std::string::npos) << r.output;
  }
}

TEST(Checkpoint, InterruptedRunLeavesWholeCheckpointsAndResumesFromWhereItStopped) {
  const fs::path dir = fresh_directory("checkpoint_interrupt");
  const std::vector<std::string> plate = {"run", scene("notched_plate.toml"), "--quiet", "--until", "1e-3",
                                          "--checkpoint-every", "4.1e-6"};
  // checkpoints every ten steps, stopped with Ctrl-C while it writes them
  std::vector<std::string> args = plate;
  args.insert(args.end(), {"--out", (dir / "stopped").string()});
  testing::Child child(args);
  ASSERT_TRUE(child.started());
  const fs::path folder = dir / "stopped" / "checkpoints";
  child.wait_until([&] { return fs::exists(folder) && checkpoints_in(folder).size() >= 20; }, 60);
  child.send(SIGINT);
  const auto result = child.finish(60);
  EXPECT_EQ(result.exit_code, 130) << result.output;
  const auto files = checkpoints_in(folder);
  EXPECT_GE(files.size(), 20u);
  fs::path interrupted;
  for (const auto& file : files) {
    CheckpointHeader header;
    EXPECT_NO_THROW(read_checkpoint(file.string(), header)) << file;
    if (file.filename().string().find("interrupted") != std::string::npos) interrupted = file;
  }
  ASSERT_FALSE(interrupted.empty()) << "no checkpoint of the state the interrupted run reached";
  EXPECT_NE(result.output.find(interrupted.filename().string()), std::string::npos) << result.output;

  // resumed from there, it writes the rows of a run never stopped
  args = plate;
  args.insert(args.end(), {"--out", (dir / "whole").string()});
  ASSERT_EQ(run_child(args, 120).exit_code, 0);
  args = plate;
  args.insert(args.end(), {"--out", (dir / "resumed").string(), "--restart", interrupted.string()});
  const auto resumed = run_child(args, 120);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const auto whole = lines_of(dir / "whole" / "series.csv");
  const auto rows = lines_of(dir / "resumed" / "series.csv");
  ASSERT_GE(rows.size(), 2u);
  const double from = row_time(rows[1]);
  std::vector<std::string> tail;
  for (size_t k = 1; k < whole.size(); ++k)
    if (row_time(whole[k]) >= from) tail.push_back(whole[k]);
  EXPECT_EQ(std::vector<std::string>(rows.begin() + 1, rows.end()), tail);

  // resumed into its own folder, its series.csv is the whole run's: the rows before the
  // interruption kept (the row of the state it stopped in dropped), the rest continued
  args = plate;
  args.insert(args.end(), {"--out", (dir / "stopped").string(), "--restart", interrupted.string()});
  const auto in_place = run_child(args, 120);
  ASSERT_EQ(in_place.exit_code, 0) << in_place.output;
  EXPECT_EQ(lines_of(dir / "stopped" / "series.csv"), whole);
}

}  // namespace
}  // namespace periflex
