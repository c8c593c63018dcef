// Scripts of timed GUI actions: parsing, ordering by frame, and clear errors for bad actions.
#include "app/gui_script.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace periflex {
namespace {

TEST(GuiScript, ParsesTheDocumentedExample) {
  const auto actions =
      parse_script("pause@5; step@6; set bond_damping=0.1@7; resume@8; colormap viridis@9");
  ASSERT_EQ(actions.size(), 5u);
  EXPECT_EQ(actions[0].verb, "pause");
  EXPECT_EQ(actions[0].frame, 5);
  EXPECT_EQ(actions[1].verb, "step");
  EXPECT_TRUE(actions[1].args.empty());
  EXPECT_EQ(actions[2].verb, "set");
  ASSERT_EQ(actions[2].args.size(), 1u);
  EXPECT_EQ(actions[2].args[0], "bond_damping=0.1");
  EXPECT_EQ(actions[3].verb, "resume");
  EXPECT_EQ(actions[4].args[0], "viridis");
  EXPECT_EQ(actions[4].frame, 9);
}

TEST(GuiScript, SortsByFrameKeepingWrittenOrderWithinAFrame) {
  const auto actions = parse_script("quit@9\nspeed max@0 # as fast as possible\nrun@0; step 3@2; pause@0");
  ASSERT_EQ(actions.size(), 5u);
  EXPECT_EQ(actions[0].verb, "speed");
  EXPECT_EQ(actions[1].verb, "run");
  EXPECT_EQ(actions[2].verb, "pause");
  EXPECT_EQ(actions[3].verb, "step");
  EXPECT_EQ(actions[3].args[0], "3");
  EXPECT_EQ(actions[4].verb, "quit");
}

TEST(GuiScript, ReadsAScriptFile) {
  const std::string path = ::testing::TempDir() + "gui_script_test.txt";
  {
    std::ofstream out(path);
    out << "# a comment line\nwait 1e-4@1\nexpect paused@2\n";
  }
  const auto actions = parse_script(path);
  std::remove(path.c_str());
  ASSERT_EQ(actions.size(), 2u);
  EXPECT_EQ(actions[0].verb, "wait");
  EXPECT_EQ(actions[1].args[0], "paused");
}

TEST(GuiScript, RejectsBadActionsNamingThem) {
  const char* bad[] = {"jump@3",           // unknown verb
                       "pause",            // no frame (and no such file)
                       "pause@x",          // frame not a number
                       "step 0@1",         // step count below one
                       "set bond_damping@1",  // set without =
                       "speed fast@1",     // not a number
                       "field colour@1",   // unknown field
                       "show bonds maybe@1",  // not on/off
                       "range 1@2",        // range needs auto or two numbers
                       "pause now@1",      // pause takes no argument
                       "grab 0.1@1",       // grab needs X and Y
                       "drag x y@1",       // not numbers
                       "cut 0 0 1@1",      // the knife needs two points
                       "cut 0 0 1 y@1",    // not a number
                       "plot@1",           // plot needs a column
                       "plot a b c@1",     // at most Y and X
                       "inspect@1",        // inspect needs a body (or none)
                       "history@1",        // history needs an interval
                       "history 0.01 x@1", // not a number
                       "back two@1",       // not a number
                       "scrub@1"};         // scrub needs a time
  for (const char* script : bad) {
    try {
      parse_script(script);
      ADD_FAILURE() << "accepted: " << script;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().key, "--script") << script;
    }
  }
}

TEST(GuiScript, ParsesThePlotKnifeAndInspectorActions) {
  const std::vector<ScriptAction> a =
      parse_script("plot probe.bob.y probe.bob.x@2; cut 0.3 0.05 0.3 -0.05@3; inspect bob@4; plot kinetic@5");
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a[0].verb, "plot");
  EXPECT_EQ(a[0].args, (std::vector<std::string>{"probe.bob.y", "probe.bob.x"}));
  EXPECT_EQ(a[1].args.size(), 4u);
  EXPECT_EQ(a[2].args, (std::vector<std::string>{"bob"}));
  EXPECT_EQ(a[3].args.size(), 1u);
}

TEST(GuiScript, ParsesTheHistoryActions) {
  const std::vector<ScriptAction> a = parse_script("history 0.0333 64@1; back@2; back 3@3; scrub 0.5@4; resume@5");
  ASSERT_EQ(a.size(), 5u);
  EXPECT_EQ(a[0].args, (std::vector<std::string>{"0.0333", "64"}));
  EXPECT_TRUE(a[1].args.empty());
  EXPECT_EQ(a[2].args, (std::vector<std::string>{"3"}));
  EXPECT_EQ(a[3].verb, "scrub");
}

}  // namespace
}  // namespace periflex
