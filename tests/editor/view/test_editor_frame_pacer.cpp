// The editor's frame pacing: 60 frames a second unless slow drawing would starve the solver.

#include <gtest/gtest.h>

#include <limits>

#include "view/frame_pacer.h"

using primo::editor::FramePacer;

TEST(EditorFramePacer, KeepsToSixtyFramesASecondWhenDrawingIsCheap) {
  FramePacer p;
  EXPECT_DOUBLE_EQ(p.interval(true), FramePacer::kFrameSeconds);  // nothing measured yet
  for (int i = 0; i < 20; ++i) p.frame_drawn(0.003);              // a GPU: 3 ms a frame
  EXPECT_DOUBLE_EQ(p.interval(true), FramePacer::kFrameSeconds);
  EXPECT_DOUBLE_EQ(p.interval(false), FramePacer::kFrameSeconds);
}

TEST(EditorFramePacer, LeavesTheSolverHalfTheTimeWhenDrawingIsSlow) {
  FramePacer p;
  for (int i = 0; i < 20; ++i) p.frame_drawn(0.020);  // software drawing of a big mesh
  EXPECT_NEAR(p.interval(true), 0.040, 1e-9);
  EXPECT_DOUBLE_EQ(p.interval(false), FramePacer::kFrameSeconds);  // nothing to leave time to
  for (int i = 0; i < 20; ++i) p.frame_drawn(1.0);  // however slow: 4 frames a second at least
  EXPECT_DOUBLE_EQ(p.interval(true), 0.25);
}

TEST(EditorFramePacer, FollowsAChangeInCostWithinAFewFramesAndIgnoresBadClocks) {
  FramePacer p;
  for (int i = 0; i < 20; ++i) p.frame_drawn(0.020);
  p.frame_drawn(0.2);  // one slow frame (a mesh upload) moves the pace by a fifth of it
  EXPECT_LT(p.interval(true), 0.2);
  for (int i = 0; i < 20; ++i) p.frame_drawn(0.002);
  EXPECT_DOUBLE_EQ(p.interval(true), FramePacer::kFrameSeconds);
  const double before = p.frame_seconds();
  p.frame_drawn(-1.0);
  p.frame_drawn(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(p.frame_seconds(), before);
}
