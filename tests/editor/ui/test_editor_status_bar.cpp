// The status bar laid out by Dear ImGui without a window or GL: a long message is cut with
// "..." before the solver's state on the right, never drawn over it.

#include <gtest/gtest.h>

#include <imgui.h>

#include <string>

#include "support/headless_imgui.h"
#include "status_bar.h"

using namespace primo::editor;

namespace {

float width_of(const std::string& text) { return ImGui::CalcTextSize(text.c_str()).x; }

// What the right side says while a drag shows previews: the longest it gets.
const std::string kRight = "Rotate | solving | preview | E 0.01743 | 21.2 ms";

}  // namespace

TEST(EditorStatusBar, TextThatFitsCutsAtACharacterWithAnEllipsis) {
  primo::test::HeadlessImGui imgui;
  ImGui::NewFrame();
  EXPECT_EQ(text_that_fits("Saved a screenshot", 1000.0f), "Saved a screenshot");
  const std::string long_text(400, 'x');
  const std::string cut = text_that_fits(long_text, 200.0f);
  EXPECT_LE(width_of(cut), 200.0f);
  EXPECT_GT(width_of(cut), 150.0f) << "as much as fits";
  ASSERT_GE(cut.size(), 3u);
  EXPECT_EQ(cut.substr(cut.size() - 3), "...");
  EXPECT_EQ(long_text.compare(0, cut.size() - 3, cut, 0, cut.size() - 3), 0) << "its start";
  // Two-byte characters are never split.
  std::string accented;
  for (int i = 0; i < 200; ++i) accented += "\xc3\xa9";  // e acute
  const std::string shown = text_that_fits(accented, 120.0f);
  EXPECT_EQ((shown.size() - 3) % 2, 0u) << shown;
  EXPECT_EQ(text_that_fits(long_text, 1.0f), "") << "not even the ellipsis fits";
  ImGui::EndFrame();
}

TEST(EditorStatusBar, ALongMessageStopsBeforeTheSolverState) {
  primo::test::HeadlessImGui imgui;
  ImGui::NewFrame();
  const std::string message =
      "Could not open /home/user/meshes/a folder with a long name/armadillo_86k_cleaned.obj: "
      "line 81234: a face refers to vertex 90211, but the file has 86012 vertices";
  for (float width : {1280.0f, 900.0f, 640.0f}) {
    const StatusBarLayout layout = status_bar_layout(message, kRight, 8.0f, width);
    EXPECT_TRUE(layout.cut) << width;
    EXPECT_LE(layout.left_end + 10.0f, layout.right_x) << "text on text at width " << width;
    EXPECT_LE(layout.right_x + width_of(kRight), width) << "the solver's state is whole";
  }
  // A short message is shown whole.
  const StatusBarLayout layout = status_bar_layout("Opened spot.obj", kRight, 8.0f, 1280.0f);
  EXPECT_FALSE(layout.cut);
  EXPECT_EQ(layout.left, "Opened spot.obj");
  ImGui::EndFrame();
}
