// The --timeout of scripted and --screenshot editor runs (src/editor/input/run_deadline.h): it runs
// out, and a run stuck past it is ended by the watchdog with one line and status 1. The end to
// end check, a script that waits too long, is EditorE2E.AScriptThatWaitsTooLongEndsAtItsTimeout.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "input/run_deadline.h"

using primo::editor::RunDeadline;

TEST(EditorRunDeadline, RunsOutAfterItsSeconds) {
  RunDeadline deadline(0.05, "s.txt");
  EXPECT_FALSE(deadline.expired());
  EXPECT_EQ("0.05 s", deadline.shown());
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  EXPECT_TRUE(deadline.expired());
}  // and the watchdog stops with it: the test goes on

TEST(EditorRunDeadline, TheWatchdogEndsARunStuckPastItsGrace) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  EXPECT_EXIT(
      {
        RunDeadline deadline(0.05, "stuck.txt", 0.1);
        std::this_thread::sleep_for(std::chrono::seconds(10));  // a frame that never returns
      },
      ::testing::ExitedWithCode(1),
      "^primo edit: error: stuck.txt: still running 0.1 s after the --timeout of 0.05 s; "
      "stopped\n$");
}
