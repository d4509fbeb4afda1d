// The Solver section laid out by Dear ImGui without a window or GL: every line reads whole at
// the panel's default width and at narrow ones (no figure runs past the panel's edge).

#include <gtest/gtest.h>

#include <imgui.h>
#include <imgui_internal.h>

#include "support/headless_imgui.h"
#include "solver_panel.h"

using namespace primo::editor;

namespace {

// How far past the right edge of a window `width` wide the figures reach (<= 0: none).
float overflow_at(float width, const SolverStatus& st, const Editor::GestureStats& last) {
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(width, 700));
  ImGui::Begin("Solver figures", nullptr, ImGuiWindowFlags_NoDecoration);
  solver_figures(st, 36.2, last);
  const ImGuiWindow* window = ImGui::GetCurrentWindow();
  const float overflow = window->DC.CursorMaxPos.x - window->WorkRect.Max.x;
  ImGui::End();
  ImGui::Render();
  return overflow;
}

}  // namespace

TEST(EditorSolverPanel, EveryLineFitsTheDefaultAndNarrowWidths) {
  primo::test::HeadlessImGui imgui;
  SolverStatus st;
  st.phase = SolverPhase::Settled;
  st.energy = 1234.56789;
  st.iterations = 1000;
  st.total_iterations = 12345678;
  st.seconds_per_iteration = 0.2051;
  st.build_seconds = 12.5;
  st.previews = true;
  Editor::GestureStats last;
  last.what = "drag 'left front foot'";
  last.frames = 1234;
  last.total_ms = 253000.0;
  last.max_ms = 3350.2;
  last.mesh_updates = 1000;
  for (float width : {340.0f, 260.0f, 200.0f, 150.0f})
    EXPECT_LE(overflow_at(width, st, last), 0.5f)
        << "a line runs past a panel " << width << " wide";
}
