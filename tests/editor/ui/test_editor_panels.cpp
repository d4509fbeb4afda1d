// The properties panel drawn by Dear ImGui without a window or GL (ImGui only builds draw
// lists): no two widgets may share an ID, or using one drives the other (the Paint tool's
// "Width" layer button moved the material's width slider).

#include <gtest/gtest.h>

#include <imgui.h>
#include <imgui_internal.h>

#include <map>
#include <string>

#include "document/edit_state.h"
#include "support/headless_imgui.h"
#include "editor.h"
#include "panels.h"
#include "primo/mesh/mesh_generators.h"
#include "view/shown_value.h"
#include "widgets.h"

using namespace primo;
using namespace primo::editor;

namespace {

struct HeadlessImGui : primo::test::HeadlessImGui {
  // One frame with the mouse at (x, y); returns the ID of the widget under it (0: none).
  ImGuiID frame(Editor& e, UiState& ui, float x, float y) {
    ImGui::GetIO().MousePos = ImVec2(x, y);
    ImGui::NewFrame();
    draw_ui(e, ui);
    ImGui::Render();
    return ImGui::GetCurrentContext()->HoveredId;
  }
};

struct Extent {
  float y_min = 1e9f, y_max = -1e9f;
};

// Hovers over the whole properties panel and returns, for every widget ID, the vertical extent
// of the places where it is the widget under the mouse.
std::map<ImGuiID, Extent> hover_map(HeadlessImGui& imgui, Editor& e, UiState& ui) {
  for (int k = 0; k < 3; ++k) imgui.frame(e, ui, -1, -1);  // settle the layout
  std::map<ImGuiID, Extent> extents;
  const float x0 = 1280 - ui.panel_width;
  for (float y = 0; y < 800; y += 4)
    for (float x = x0 + 2; x < 1280; x += 12) {
      const ImGuiID id = imgui.frame(e, ui, x, y);
      if (id == 0) continue;
      Extent& ex = extents[id];
      ex.y_min = std::min(ex.y_min, y);
      ex.y_max = std::max(ex.y_max, y);
    }
  return extents;
}

}  // namespace

TEST(EditorPanels, NoTwoWidgetsOfThePropertiesPanelShareAnId) {
  HeadlessImGui imgui;
  Editor e;
  e.set_viewport({0, 0, 900, 760, 1.0});
  auto doc = make_document(make_cylinder(0.25, 1.0, 8, 10, FaceShape::Quads), "tube.obj");
  const MeshTopology& t = *doc->topology;
  add_handle(doc->state, t, t.rest_points, {0, 1, 2}, HandleMode::Spring);
  // A posed handle, active: its rotation fields (axis-angle and Euler) and its Pivot row.
  add_handle(doc->state, t, t.rest_points, {3, 4, 5}, HandleMode::Pose);
  e.adopt(std::move(doc));
  UiState ui;
  for (Tool tool : {Tool::Select, Tool::Paint, Tool::Move}) {
    for (PaintLayer layer : {PaintLayer::Height, PaintLayer::Width}) {
      e.tools.tool = tool;
      e.tools.paint_layer = layer;
      for (const auto& [id, extent] : hover_map(imgui, e, ui))
        // One widget is at most a couple of rows tall; an ID found far apart is two widgets.
        EXPECT_LT(extent.y_max - extent.y_min, 48.0f)
            << "an ID is shared by widgets at y " << extent.y_min << " and " << extent.y_max
            << " (tool " << int(tool) << ")";
      if (tool != Tool::Paint) break;
    }
  }
  // Hovering only: nothing was changed.
  EXPECT_EQ(e.document()->state.prisms.width, 1.0);
}

TEST(EditorPanels, NumberFieldsPutNoSignOnNothing) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", shown_value(-1e-17, 4));
  EXPECT_STREQ(text, "0.0000") << "not -0.0000";
  std::snprintf(text, sizeof text, "%.4f", shown_value(-0.00006, 4));
  EXPECT_STREQ(text, "-0.0001");
  EXPECT_EQ(shown_value(0.3, 4), 0.3);
  EXPECT_EQ(shown_value(-2e-3, 2), 0.0);
  // A field drawn without being touched changes nothing, the tiny value included.
  HeadlessImGui imgui;
  Vec3 v(-1e-17, 0.5, 0.0);
  ImGui::NewFrame();
  ImGui::Begin("fields");
  EXPECT_FALSE(drag_vec3("Move", v, 0.01f, 4));
  ImGui::End();
  ImGui::Render();
  EXPECT_EQ(v, Vec3(-1e-17, 0.5, 0.0));
}
