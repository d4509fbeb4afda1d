// The panels' fingerprint, which lets the window skip a frame that would draw the same
// picture again (view/shown_picture.h): equal for frames that draw the same, different as
// soon as anything drawn changes. Dear ImGui without a window or GL builds the draw lists.

#include <gtest/gtest.h>

#include <imgui.h>

#include <cstdint>

#include "draw_data_fingerprint.h"
#include "editor.h"
#include "support/headless_imgui.h"
#include "panels.h"
#include "view/shown_picture.h"

using namespace primo::editor;

namespace {

// An editor with nothing open and its panels, drawn by a headless Dear ImGui.
struct Panels {
  primo::test::HeadlessImGui imgui;
  Editor e;
  UiState ui;
  Panels() {
    e.set_viewport({0, 0, 900, 760, 1.0});
    e.update(1.0 / 60.0);
    for (int k = 0; k < 3; ++k) fingerprint_of_a_frame();  // the layout settles
  }
  std::uint64_t fingerprint_of_a_frame() {
    ImGui::NewFrame();
    draw_ui(e, ui);
    ImGui::Render();
    return draw_data_fingerprint(*ImGui::GetDrawData());
  }
};

}  // namespace

TEST(EditorDrawDataFingerprint, FramesOfAnEditorWhereNothingChangesDrawTheSamePanels) {
  Panels p;
  const std::uint64_t first = p.fingerprint_of_a_frame();
  // Frames a few milliseconds apart, each a little longer than the last (a busy machine): the
  // frame time the status bar shows is refreshed twice a second, not at every frame.
  for (double ms : {17.0, 23.0, 31.0, 12.0}) {
    p.e.update(ms / 1000.0);
    EXPECT_EQ(p.fingerprint_of_a_frame(), first) << "after a frame of " << ms << " ms";
  }
}

TEST(EditorDrawDataFingerprint, AChangeOfWhatThePanelsShowChangesIt) {
  Panels p;
  const std::uint64_t before = p.fingerprint_of_a_frame();
  p.e.info("Saved a screenshot to shot.png");  // a message in the status bar
  const std::uint64_t with_message = p.fingerprint_of_a_frame();
  EXPECT_NE(with_message, before);
  p.e.update(0.6);  // the status bar's frame time is refreshed
  p.e.update(0.6);
  EXPECT_NE(p.fingerprint_of_a_frame(), with_message);
  ImGui::GetIO().DisplaySize = ImVec2(1000, 700);  // the window's size
  EXPECT_NE(p.fingerprint_of_a_frame(), with_message);
}

TEST(EditorShownPicture, AFrameThatWouldDrawTheShownPictureIsNotDrawn) {
  ShownPicture shown;
  const PictureFingerprint picture{11, 22, 0, 0, 900, 760, 1280, 800};
  EXPECT_TRUE(shown.needs_drawing(picture)) << "nothing shown yet";
  shown.drawn(picture);
  EXPECT_FALSE(shown.needs_drawing(picture));
  PictureFingerprint moved = picture;
  moved.scene = 12;  // the mesh or the camera moved
  EXPECT_TRUE(shown.needs_drawing(moved));
  PictureFingerprint panels = picture;
  panels.panels = 23;
  EXPECT_TRUE(shown.needs_drawing(panels));
  PictureFingerprint resized = picture;
  resized.view_width = 880;
  EXPECT_TRUE(shown.needs_drawing(resized));
  shown.forget();  // the window was exposed: its contents are lost
  EXPECT_TRUE(shown.needs_drawing(picture));
}
