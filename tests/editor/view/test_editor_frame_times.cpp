// The times between a gesture's frames: frames a second, median and 90th percentile.

#include <gtest/gtest.h>

#include <limits>

#include "view/frame_times.h"

using primo::editor::FrameTimes;

TEST(EditorFrameTimes, NoFramesGiveZeros) {
  const FrameTimes t;
  EXPECT_EQ(t.count(), 0);
  EXPECT_EQ(t.per_second(), 0.0);
  EXPECT_EQ(t.quantile(0.5), 0.0);
}

TEST(EditorFrameTimes, AFewLongFramesShowInTheNinetiethPercentileNotTheMedian) {
  FrameTimes t;
  for (int i = 0; i < 18; ++i) t.add(20.0);
  t.add(200.0);
  t.add(300.0);
  EXPECT_EQ(t.count(), 20);
  EXPECT_DOUBLE_EQ(t.total_ms(), 18 * 20.0 + 500.0);
  EXPECT_DOUBLE_EQ(t.per_second(), 1000.0 * 20 / 860.0);
  EXPECT_DOUBLE_EQ(t.quantile(0.5), 20.0);
  EXPECT_DOUBLE_EQ(t.quantile(0.9), 20.0);  // the 18th of 20 sorted times
  EXPECT_DOUBLE_EQ(t.quantile(0.95), 200.0);
  EXPECT_DOUBLE_EQ(t.quantile(1.0), 300.0);
}

TEST(EditorFrameTimes, TheMedianOfOddlyManyIsTheMiddleOne) {
  FrameTimes t;
  for (double ms : {50.0, 10.0, 40.0, 20.0, 30.0}) t.add(ms);
  EXPECT_DOUBLE_EQ(t.quantile(0.5), 30.0);
  EXPECT_DOUBLE_EQ(t.quantile(0.0), 10.0);
  EXPECT_DOUBLE_EQ(t.quantile(0.9), 50.0);
}

TEST(EditorFrameTimes, ATimeThatIsNoDurationIsIgnored) {
  FrameTimes t;
  t.add(std::numeric_limits<double>::quiet_NaN());
  t.add(-1.0);
  t.add(std::numeric_limits<double>::infinity());
  t.add(16.0);
  EXPECT_EQ(t.count(), 1);
  EXPECT_DOUBLE_EQ(t.quantile(0.5), 16.0);
}
