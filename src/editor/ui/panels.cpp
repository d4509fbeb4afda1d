#include "panels.h"

#include <imgui.h>
#include <imgui_internal.h>  // GetActiveID
#include <imgui_stdlib.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>

#include "controls_window.h"
#include "view/euler_angles.h"
#include "view/face_colors.h"
#include "render/gizmo_draw.h"
#include "menu_bar.h"
#include "paths.h"
#include "preferences_window.h"
#include "session_panel.h"
#include "solver_panel.h"
#include "status_bar.h"
#include "widgets.h"
#include "primo/model/turn.h"

namespace primo::editor {
namespace fs = std::filesystem;
namespace {

ImU32 u32(float r, float g, float b, float a = 1.0f) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, a));
}

// The active handle's turn as its Axis and Angle fields hold it while one of them is being
// edited. Read back from the turn at every frame they would come back changed (an axis typed
// as (1, 1, 0) normalised). A field in text mode applies its text at every frame, so the
// handle would be posed anew at every frame and the solver would start over at iteration 0 for
// as long as the field stays open (and a drag past 180 degrees would bounce back).
struct RotationFields {
  const void* handle_faces = nullptr;  // whose rotation they hold (a handle's faces are its own)
  ImGuiID editing = 0;                 // the field being edited in the last frame (0: none)
  Vec3 axis = Vec3::UnitY();
  double angle_deg = 0.0;
  Vec3 euler_deg = Vec3::Zero();  // Euler XYZ (euler_angles.h)
};
RotationFields rotation_fields;

// One widget interaction = one undo step: live while active, committed on release.
void track_edit(Editor& e, bool changed, const std::string& label) {
  if (changed) e.live_edit();
  if (ImGui::IsItemDeactivatedAfterEdit()) e.commit(label);
}

// --- Tool strip ----------------------------------------------------------------------------

void draw_tool_icon(ImDrawList* dl, Tool tool, ImVec2 c, ImU32 col) {
  switch (tool) {
    case Tool::Select:  // a dashed selection circle
      for (int i = 0; i < 12; i += 2)
        dl->PathArcTo(c, 11.0f, float(i) * 0.5236f, float(i + 1) * 0.5236f, 4), dl->PathStroke(col, 0, 2.0f);
      dl->AddCircleFilled(c, 2.5f, col);
      break;
    case Tool::Drag: {  // a hand-like grab: four arrows
      const ImVec2 d[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (const ImVec2& v : d) {
        const ImVec2 tip(c.x + v.x * 12, c.y + v.y * 12);
        dl->AddLine(c, tip, col, 2.0f);
        dl->AddTriangleFilled(ImVec2(tip.x + v.x * 3, tip.y + v.y * 3),
                              ImVec2(tip.x - v.x * 3 - v.y * 4, tip.y - v.y * 3 + v.x * 4),
                              ImVec2(tip.x - v.x * 3 + v.y * 4, tip.y - v.y * 3 - v.x * 4), col);
      }
      break;
    }
    case Tool::Move:  // gizmo arrows
      dl->AddLine(c, ImVec2(c.x + 12, c.y), u32(0.93f, 0.3f, 0.3f), 2.5f);
      dl->AddLine(c, ImVec2(c.x, c.y - 12), u32(0.45f, 0.85f, 0.3f), 2.5f);
      dl->AddLine(c, ImVec2(c.x - 8, c.y + 8), u32(0.3f, 0.55f, 0.98f), 2.5f);
      dl->AddRectFilled(ImVec2(c.x - 2.5f, c.y - 2.5f), ImVec2(c.x + 2.5f, c.y + 2.5f), col);
      break;
    case Tool::Rotate:
      dl->AddCircle(c, 11.0f, u32(0.3f, 0.55f, 0.98f), 24, 2.0f);
      dl->PathArcTo(c, 11.0f, -0.3f, 1.9f, 12);
      dl->PathStroke(u32(0.93f, 0.3f, 0.3f), 0, 2.5f);
      dl->AddTriangleFilled(ImVec2(c.x + 11, c.y - 7), ImVec2(c.x + 6, c.y - 1), ImVec2(c.x + 15, c.y - 1), col);
      break;
    case Tool::Paint:  // a brush stroke
      dl->AddBezierCubic(ImVec2(c.x - 12, c.y + 8), ImVec2(c.x - 4, c.y - 14), ImVec2(c.x + 4, c.y + 14),
                         ImVec2(c.x + 12, c.y - 8), u32(0.3f, 0.5f, 1.0f), 4.0f);
      dl->AddCircleFilled(ImVec2(c.x + 12, c.y - 8), 3.0f, col);
      break;
  }
}

void draw_toolbar(Editor& e, UiState& ui, float top, float height) {
  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(ui.toolbar_width, height));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(6, 8));
  ImGui::Begin("##tools", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  struct Item {
    Tool tool;
    const char* name;
    const char* tip;
  };
  const Item items[] = {
      {Tool::Select, "Select (Q)", "Brush, box (B) or lasso (L) over faces. Shift adds, Ctrl removes. Alt+click: edge loop."},
      {Tool::Drag, "Drag (G)", "Grab a handle and drag it in the view plane; the mesh follows."},
      {Tool::Move, "Move (W)", "Gizmo on the active handle: drag an arrow or the centre square. Ctrl snaps."},
      {Tool::Rotate, "Rotate (E)", "Gizmo on the active handle: drag a ring. Ctrl snaps to 15 degrees."},
      {Tool::Paint, "Paint (P)", "Paint stiffness (prism height) or width factors. Ctrl erases."},
  };
  for (const Item& item : items) {
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const ImVec2 size(40, 40);
    ImGui::PushID(item.name);
    if (ImGui::InvisibleButton("tool", size)) e.set_tool(item.tool);
    const bool hovered = ImGui::IsItemHovered();
    ImGui::PopID();
    const bool on = e.tools.tool == item.tool;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(p, ImVec2(p.x + size.x, p.y + size.y),
                      on ? u32(0.26f, 0.45f, 0.75f) : hovered ? u32(0.3f, 0.32f, 0.36f) : u32(0.2f, 0.21f, 0.24f), 6.0f);
    draw_tool_icon(dl, item.tool, ImVec2(p.x + size.x * 0.5f, p.y + size.y * 0.5f), u32(0.95f, 0.95f, 0.95f));
    if (hovered) {
      ImGui::BeginTooltip();
      ImGui::TextUnformatted(item.name);
      ImGui::TextDisabled("%s", item.tip);
      ImGui::EndTooltip();
    }
    ImGui::Dummy(ImVec2(0, 2));
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

// --- Properties panel -------------------------------------------------------------------

void selection_buttons(Editor& e) {
  const float w = (ImGui::GetContentRegionAvail().x - 2 * ImGui::GetStyle().ItemSpacing.x) / 3;
  const bool vertex_mode = e.selection_mode() == SelectionMode::Vertices;
  if (ImGui::RadioButton("Vertices", vertex_mode)) e.set_selection_mode(SelectionMode::Vertices);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Pick vertices (1); a handle takes every face touching a selected vertex");
  ImGui::SameLine();
  if (ImGui::RadioButton("Faces", !vertex_mode)) e.set_selection_mode(SelectionMode::Faces);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Pick faces (3)");
  if (ImGui::Button("All", ImVec2(w, 0))) e.select_all();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Select all faces (A)");
  ImGui::SameLine();
  if (ImGui::Button("None", ImVec2(w, 0))) e.clear_selection();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Clear the selection (Alt+A)");
  ImGui::SameLine();
  if (ImGui::Button("Invert", ImVec2(w, 0))) e.invert_selection();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Invert the selection (Ctrl+I)");
  const float w2 = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) / 2;
  if (ImGui::Button("Grow", ImVec2(w2, 0))) e.grow_selection();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Add the faces around the selection (Ctrl+=)");
  ImGui::SameLine();
  if (ImGui::Button("Shrink", ImVec2(w2, 0))) e.shrink_selection();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Remove the selection's border faces (Ctrl+-)");
  if (ImGui::Button("Linked", ImVec2(w2, 0))) e.select_linked(false);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Add the whole connected piece (Ctrl+L)");
  ImGui::SameLine();
  if (ImGui::Button("Linked by angle", ImVec2(w2, 0))) e.select_linked(true);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Grow up to edges sharper than %.0f degrees (Ctrl+Shift+L)",
                      e.tools.linked_angle_deg);
  if (ImGui::Button("Hide", ImVec2(w, 0))) e.hide_selected();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Hide the selected faces; they still deform (H)");
  ImGui::SameLine();
  if (ImGui::Button("Isolate", ImVec2(w, 0))) e.hide_unselected();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Hide every face but the selection (Shift+H)");
  ImGui::SameLine();
  if (ImGui::Button("Reveal", ImVec2(w, 0))) e.reveal_all();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Show the hidden faces again, selected (Alt+H)");
  if (const Document* doc = e.document())
    if (const int hidden = count_hidden(doc->state.hidden))
      ImGui::TextDisabled("%d face%s hidden", hidden, hidden == 1 ? "" : "s");
}

// X / Y / Z mirror toggles, for every tool: selecting, painting and making handles.
void symmetry_row(Editor& e) {
  ImGui::TextUnformatted("Mirror");
  help_marker("Symmetry across the mesh's centre plane: selections and paint strokes reach the "
              "twin faces, and a handle made on one side gets a twin that moves as its mirror "
              "image. Twins are matched by topology when the mesh's connectivity is symmetric "
              "(however it is posed), else by position. Shift+X / Shift+Y / Shift+Z.");
  for (int axis = 0; axis < 3; ++axis) {
    ImGui::SameLine();
    bool on = e.tools.mirror[size_t(axis)];
    const std::string label = std::string(axis_name(axis)) + "##mirror";
    if (ImGui::Checkbox(label.c_str(), &on)) e.set_mirror(axis, on);
    if (ImGui::IsItemHovered()) {
      const std::string summary = e.mirror_summary(axis);
      ImGui::SetTooltip("%s", summary.empty() ? (std::string("Mirror across ") + axis_name(axis) +
                                                 " (Shift+" + axis_name(axis) + ")").c_str()
                                              : summary.c_str());
    }
  }
}

// Which frame the gizmo's axes follow (gizmo_orientation.h).
void gizmo_orientation_combo(Editor& e) {
  int orientation = int(e.tools.gizmo_orientation);
  const char* labels[kGizmoOrientations];
  for (int i = 0; i < kGizmoOrientations; ++i) labels[i] = orientation_label(GizmoOrientation(i));
  ImGui::SetNextItemWidth(-60);
  if (ImGui::Combo("Axes", &orientation, labels, kGizmoOrientations))
    e.tools.gizmo_orientation = GizmoOrientation(orientation);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The gizmo's axes: the world's, the handle's own as it is turned, its "
                      "surface normal (Z) or the view's (%s cycles them)",
                      e.key_map().label(Action::CycleGizmoOrientation).c_str());
}

void tool_section(Editor& e) {
  if (!ImGui::CollapsingHeader("Tool", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ToolSettings& t = e.tools;
  Document* doc = e.document();
  ImGui::Text("%s", tool_label(t.tool));
  symmetry_row(e);
  switch (t.tool) {
    case Tool::Select: {
      int shape = int(t.shape);
      ImGui::RadioButton("Brush (C)", &shape, int(SelectShape::Brush));
      ImGui::SameLine();
      ImGui::RadioButton("Box (B)", &shape, int(SelectShape::Box));
      ImGui::SameLine();
      ImGui::RadioButton("Lasso (L)", &shape, int(SelectShape::Lasso));
      t.shape = SelectShape(shape);
      if (t.shape == SelectShape::Brush) {
        float r = float(t.brush_radius);
        if (ImGui::SliderFloat("Radius", &r, 2.0f, 200.0f, "%.0f px", ImGuiSliderFlags_Logarithmic)) t.brush_radius = r;
        help_marker("[ and ] change the radius; so does Ctrl + mouse wheel.");
      }
      ImGui::Checkbox("X-ray (reach hidden faces)", &t.xray);
      selection_buttons(e);
      const int n = doc ? count_selected(*doc->state.selection) : 0;
      ImGui::Text("%d face%s selected", n, n == 1 ? "" : "s");
      ImGui::Separator();
      ImGui::TextDisabled("Make from the selection");
      const float w = (ImGui::GetContentRegionAvail().x - 2 * ImGui::GetStyle().ItemSpacing.x) / 3;
      if (ImGui::Button("Handle", ImVec2(w, 0))) e.make_handle(HandleMode::Pose);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("A handle you can drag (Ctrl+G)");
      ImGui::SameLine();
      if (ImGui::Button("Fixed", ImVec2(w, 0))) e.make_handle(HandleMode::Fixed);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("A region that never moves (Ctrl+Shift+G)");
      ImGui::SameLine();
      if (ImGui::Button("Spring", ImVec2(w, 0))) e.make_handle(HandleMode::Spring);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("A force pulling the faces where you drag it (Ctrl+Alt+G)");
      break;
    }
    case Tool::Drag:
      ImGui::TextWrapped("Drag a coloured handle; the mesh follows while you drag. Position-only "
                         "handles let their orientation follow; orientation-only handles turn. "
                         "Right click or Esc cancels.");
      break;
    case Tool::Move:
    case Tool::Rotate:
      ImGui::TextWrapped("Click a handle to put the gizmo on it, then drag an %s. Hold Ctrl to snap "
                         "(%.3g units, 15 degrees). Exact values: Handles panel below.",
                         t.tool == Tool::Move ? "arrow or the centre square" : "axis ring or the outer ring",
                         doc ? snap_step_for(doc->topology->bbox_diagonal) : 0.1);
      gizmo_orientation_combo(e);
      break;
    case Tool::Paint: {
      int layer = int(t.paint_layer);
      ImGui::RadioButton("Stiffness", &layer, int(PaintLayer::Height));
      help_marker("Prism height factor. Below 1 the surface is softer there and bends more; above 1 "
                  "it is stiffer.");
      ImGui::SameLine();
      ImGui::RadioButton("Width", &layer, int(PaintLayer::Width));
      help_marker("Prism width factor. Below 1 the surface shrinks there, above 1 it grows.");
      t.paint_layer = PaintLayer(layer);
      double lo = t.paint_layer == PaintLayer::Height ? 0.05 : 0.5;
      double hi = t.paint_layer == PaintLayer::Height ? 4.0 : 1.5;
      double& value = t.paint_layer == PaintLayer::Height ? t.paint_height : t.paint_width;
      ImGui::SliderScalar("Value", ImGuiDataType_Double, &value, &lo, &hi, "x%.2f",
                          t.paint_layer == PaintLayer::Height ? ImGuiSliderFlags_Logarithmic : 0);
      float r = float(t.brush_radius);
      if (ImGui::SliderFloat("Radius", &r, 2.0f, 200.0f, "%.0f px", ImGuiSliderFlags_Logarithmic)) t.brush_radius = r;
      float strength = float(t.paint_strength);
      if (ImGui::SliderFloat("Strength", &strength, 0.05f, 1.0f, "%.2f")) t.paint_strength = strength;
      help_marker("How far one dab moves the faces towards the value: 1 sets it at once, lower "
                  "builds it up over repeated strokes.");
      int falloff = int(t.paint_falloff);
      const char* falloffs[] = {"Constant", "Linear", "Smooth"};
      if (ImGui::Combo("Falloff", &falloff, falloffs, 3)) t.paint_falloff = Falloff(falloff);
      help_marker("How the brush fades from its centre to its rim: Smooth blends painted "
                  "regions softly into their surroundings.");
      ImGui::TextDisabled("Ctrl + drag erases (back to x1)");
      if (doc && ImGui::Button("Smooth this layer")) {
        layer_factors(doc->state, t.paint_layer) =
            smooth_factors(layer_factors(doc->state, t.paint_layer), *doc->topology);
        e.commit(t.paint_layer == PaintLayer::Height ? "Smooth stiffness" : "Smooth width");
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Soften the edges of the painted regions (once per click)");
      ImGui::SameLine();
      if (doc && ImGui::Button("Clear this layer")) {
        layer_factors(doc->state, t.paint_layer) = nullptr;
        e.commit(t.paint_layer == PaintLayer::Height ? "Clear stiffness" : "Clear width");
      }
      break;
    }
  }
}

// The active handle's pivot: its rest coordinates (the scenario's `center`), and where to put
// it. Moving it never moves the faces (pivot.h); a drag of the fields is one undo step.
void pivot_row(Editor& e, int index, float speed) {
  HandleGroup& h = e.document()->state.handles[size_t(index)];
  Vec3 pivot = h.center;
  ImGui::SetNextItemWidth(-60);
  if (drag_vec3("Pivot", pivot, speed, 4) &&
      e.place_pivot(index, pivot))
    e.live_edit();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The point the handle turns about, in rest coordinates; the gizmo is drawn "
                      "where it is now. %s or Ctrl+Shift+right-click puts it on the surface.",
                      e.key_map().label(Action::PivotToCursor).c_str());
  if (ImGui::IsItemDeactivatedAfterEdit()) e.commit("Pivot of '" + h.name + "'");
  const float w = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) / 2;
  if (ImGui::Button("Centre of selection", ImVec2(w, 0))) e.pivot_to_selection(index);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The pivot to the centre of the selected faces (a joint)");
  ImGui::SameLine();
  if (ImGui::Button("Rest centroid", ImVec2(w, 0))) e.pivot_to_rest_centroid(index);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The pivot back to the centre of the handle's faces");
}

void handles_section(Editor& e) {
  Document* doc = e.document();
  if (!ImGui::CollapsingHeader("Handles", ImGuiTreeNodeFlags_DefaultOpen) || !doc) return;
  EditState& s = doc->state;
  if (s.handles.empty()) {
    ImGui::TextWrapped("No handles yet. Select faces (Q), then make a handle (Ctrl+G) or a fixed "
                       "region (Ctrl+Shift+G).");
    return;
  }
  if (ImGui::BeginTable("handles", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                                          ImGuiTableFlags_ScrollY,
                        ImVec2(0, std::min(8.0f, float(s.handles.size()) + 0.6f) * ImGui::GetFrameHeight()))) {
    ImGui::TableSetupColumn("##c", ImGuiTableColumnFlags_WidthFixed, 14);
    ImGui::TableSetupColumn("Name");
    ImGui::TableSetupColumn("Mode", ImGuiTableColumnFlags_WidthFixed, 130);
    for (size_t i = 0; i < s.handles.size(); ++i) {
      const HandleGroup& h = s.handles[i];
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const Rgb c = handle_color(h);
      const ImVec2 p = ImGui::GetCursorScreenPos();
      ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(p.x + 1, p.y + 3), ImVec2(p.x + 12, p.y + 14),
                                                u32(c[0], c[1], c[2]), 3.0f);
      ImGui::TableNextColumn();
      ImGui::PushID(int(i));
      if (ImGui::Selectable(h.name.c_str(), int(i) == s.active, ImGuiSelectableFlags_SpanAllColumns))
        e.set_active_handle(int(i));
      ImGui::PopID();
      ImGui::TableNextColumn();
      ImGui::TextDisabled("%s", mode_label(h.mode));
    }
    ImGui::EndTable();
    if (moves_whole_mesh_rigidly(s)) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1));
      ImGui::TextWrapped("Only one handle holds the mesh, so the whole mesh follows it rigidly. "
                         "Make a fixed region (Ctrl+Shift+G) where it should stay.");
      ImGui::PopStyleColor();
    }
  }
  if (s.active < 0 || s.active >= int(s.handles.size())) return;
  HandleGroup& h = s.handles[s.active];
  ImGui::PushID("active");
  ImGui::SetNextItemWidth(-60);
  track_edit(e, ImGui::InputText("Name", &h.name), "Rename handle");
  int mode = int(h.mode);
  const char* modes[] = {mode_label(HandleMode::Pose), mode_label(HandleMode::Position),
                         mode_label(HandleMode::Orientation), mode_label(HandleMode::Spring),
                         mode_label(HandleMode::Fixed)};
  ImGui::SetNextItemWidth(-60);
  if (ImGui::Combo("Mode", &mode, modes, 5)) e.set_handle_mode(s.active, HandleMode(mode));
  ImGui::TextDisabled("%zu faces", h.faces->size());
  {
    // Soft selection: the radius over which the handle's pull fades (soft_selection.h).
    double radius = h.falloff_radius;
    const double zero = 0.0, most = doc->topology->bbox_diagonal;
    ImGui::SetNextItemWidth(-60);
    if (ImGui::DragScalar("Falloff", ImGuiDataType_Double, &radius,
                          float(0.002 * doc->topology->bbox_diagonal), &zero, &most, "%.4f",
                          ImGuiSliderFlags_AlwaysClamp)) {
      set_falloff(s, *doc->topology, s.active, radius);
      e.live_edit();
    }
    if (ImGui::IsItemDeactivatedAfterEdit()) e.commit("Falloff of '" + h.name + "'");
    ImGui::SameLine();
    help_marker("Soft selection (O, Alt + wheel): the free faces within this distance of the "
                "handle are pulled after it by springs whose weight fades smoothly to 0 at the "
                "radius, so its influence fades instead of ending at its edge. Their strength is "
                "the Stiffness below. 0: off.");
    if (h.falloff) ImGui::TextDisabled("%zu faces in the falloff", h.falloff->size());
  }
  if (h.mode == HandleMode::Spring || h.falloff_radius > 0) {
    double lo = 0.0, hi = 100.0;
    ImGui::SetNextItemWidth(-60);
    track_edit(e, ImGui::SliderScalar("Stiffness", ImGuiDataType_Double, &h.stiffness, &lo, &hi, "%.2f",
                                      ImGuiSliderFlags_Logarithmic),
               "Spring stiffness");
  }
  if (h.mode != HandleMode::Fixed) {
    const float speed = float(0.002 * doc->topology->bbox_diagonal);
    if (uses_translation(h.mode)) {
      ImGui::SetNextItemWidth(-60);
      track_edit(e, drag_vec3(h.mode == HandleMode::Spring ? "Pull" : "Move", h.pose.translate, speed, 4),
                 "Move '" + h.name + "'");
    }
    if (uses_rotation(h.mode)) {
      RotationFields& fields = rotation_fields;
      if (fields.editing == 0 || fields.editing != ImGui::GetActiveID() ||
          fields.handle_faces != h.faces.get()) {
        // Whole turns included: two turns of the gizmo's ring read 720 degrees.
        const AxisAngle shown = axis_angle_of_turn(h.pose.whole_turn());
        fields.angle_deg = shown.angle_deg;
        fields.axis = shown.axis;
        fields.euler_deg = euler_xyz_of_turn(h.pose.whole_turn());
      }
      ImGui::SetNextItemWidth(-60);
      bool changed = drag_vec3("Axis", fields.axis, 0.01f, 3);
      fields.editing = ImGui::IsItemActive() ? ImGui::GetActiveID() : 0;
      const bool axis_done = ImGui::IsItemDeactivatedAfterEdit();
      ImGui::SetNextItemWidth(-60);
      // Turns add up: no clamp to one turn, only a bound far beyond any pose (100 turns).
      const double amin = -36000, amax = 36000;
      changed |= ImGui::DragScalar("Angle", ImGuiDataType_Double, &fields.angle_deg, 0.5f, &amin,
                                   &amax, "%.2f deg", ImGuiSliderFlags_AlwaysClamp);
      if (ImGui::IsItemActive()) fields.editing = ImGui::GetActiveID();
      fields.handle_faces = h.faces.get();
      const bool angle_done = ImGui::IsItemDeactivatedAfterEdit();
      if (changed && fields.axis.norm() > 1e-12) {
        const Vec3 turn = turn_about(fields.axis, fields.angle_deg);
        if (turn != h.pose.whole_turn()) {
          h.pose.set_turn(turn);
          e.live_edit();
        }
      }
      ImGui::SetNextItemWidth(-60);
      const bool euler_changed =
          drag_vec3("Euler", fields.euler_deg, 0.5f, 2, &amin, &amax, ImGuiSliderFlags_AlwaysClamp);
      if (ImGui::IsItemActive()) fields.editing = ImGui::GetActiveID();
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Euler XYZ in degrees: X first, then Y, then Z. One angle alone keeps "
                          "whole turns (720 is two turns about that axis).");
      const bool euler_done = ImGui::IsItemDeactivatedAfterEdit();
      if (euler_changed && fields.euler_deg.allFinite()) {
        const Vec3 turn = turn_of_euler_xyz(fields.euler_deg, h.pose.whole_turn());
        if (turn != h.pose.whole_turn()) {
          h.pose.set_turn(turn);
          e.live_edit();
        }
      }
      if (axis_done || angle_done || euler_done) e.commit("Rotate '" + h.name + "'");
    }
    if (h.mode != HandleMode::Spring) pivot_row(e, s.active, speed);
  }
  const float w = (ImGui::GetContentRegionAvail().x - 2 * ImGui::GetStyle().ItemSpacing.x) / 3;
  if (ImGui::Button("Reset", ImVec2(w, 0))) e.reset_handle(s.active);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Back to the rest pose (Alt+G)");
  ImGui::SameLine();
  if (ImGui::Button("Frame", ImVec2(w, 0))) e.frame_selection();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Frame the handle (F, with nothing selected)");
  ImGui::SameLine();
  if (ImGui::Button("Delete", ImVec2(w, 0))) e.delete_handle(s.active);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Delete the handle (%s)", e.key_map().label(Action::DeleteHandle).c_str());
  if (ImGui::Button("Reset all handles", ImVec2(-1, 0))) e.reset_all_handles();
  ImGui::PopID();
}

// The undo history as a list: the current step highlighted, undone steps dimmed; a click goes
// there (Editor::go_to_history).
void history_section(Editor& e) {
  Document* doc = e.document();
  if (!ImGui::CollapsingHeader("History") || !doc) return;
  const UndoStack& h = doc->history;
  const std::vector<UndoStack::Group> groups = h.groups();
  const float rows = std::min(10.0f, float(groups.size()));
  if (!ImGui::BeginListBox("##history", ImVec2(-1, rows * ImGui::GetTextLineHeightWithSpacing() + 6)))
    return;
  auto step = [&](std::size_t i, const char* label) {
    const bool undone = i > h.position();
    if (undone) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::PushID(int(i));
    if (ImGui::Selectable(label, i == h.position())) e.go_to_history(i);
    if (i == h.position() && ImGui::IsWindowAppearing()) ImGui::SetScrollHereY();
    ImGui::PopID();
    if (undone) ImGui::PopStyleColor();
  };
  for (const UndoStack::Group& g : groups) {
    if (g.size() == 1) {
      step(g.first, g.first == 0 ? "(as opened)" : h.label(g.first).c_str());
      continue;
    }
    // A run of like steps, folded as in Maya: the header goes to the run's last step.
    const bool inside = h.position() >= g.first && h.position() <= g.last;
    const bool undone = g.first > h.position();
    if (undone) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    const std::string header = h.label(g.first) + "  x" + std::to_string(g.size());
    ImGui::PushID(int(g.first));
    const bool open = ImGui::TreeNodeEx("##group", ImGuiTreeNodeFlags_OpenOnArrow |
                                           ImGuiTreeNodeFlags_SpanAvailWidth |
                                           (inside ? ImGuiTreeNodeFlags_Selected : 0),
                                       "%s", header.c_str());
    if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) e.go_to_history(g.last);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%zu steps; click to go to the last, open to pick one (%s undoes them all)",
                        g.size(), e.key_map().label(Action::UndoGroup).c_str());
    ImGui::PopID();
    if (undone) ImGui::PopStyleColor();
    if (!open) continue;
    for (std::size_t i = g.first; i <= g.last; ++i) {
      const std::string label = std::to_string(i - g.first + 1) + ". " + h.label(i);
      step(i, label.c_str());
    }
    ImGui::TreePop();
  }
  ImGui::EndListBox();
}

void prisms_section(Editor& e) {
  Document* doc = e.document();
  if (!ImGui::CollapsingHeader("Material (prisms)", ImGuiTreeNodeFlags_DefaultOpen) || !doc) return;
  PrismSettings& p = doc->state.prisms;
  if (p.height_unit == HeightUnit::Diagonal) {
    // Shown in percent of the bounding-box diagonal, stored as a fraction.
    double percent = p.height * 100.0, lo = 0.0, hi = 20.0;
    ImGui::SetNextItemWidth(-90);
    const bool changed =
        ImGui::SliderScalar("Thickness", ImGuiDataType_Double, &percent, &lo, &hi, "%.2f %%");
    if (changed) p.height = percent / 100.0;
    track_edit(e, changed, "Prism thickness");
    help_marker("Half-thickness of the prism layer in percent of the bounding-box diagonal, the "
                "same material at every mesh resolution: thicker is stiffer against bending and "
                "bends round; 0 is a membrane.");
  } else {
    double lo = 0.0, hi = 3.0;
    ImGui::SetNextItemWidth(-90);
    track_edit(e, ImGui::SliderScalar("Height", ImGuiDataType_Double, &p.height, &lo, &hi, "%.3f"),
               "Prism height");
    help_marker("Half-thickness of the prism layer in mean edge lengths (prisms.height, as the "
                "scenario set it): a finer mesh is a thinner, softer layer. Defaults switches to "
                "the resolution-independent thickness.");
  }
  double wlo = 0.5, whi = 1.5;
  ImGui::SetNextItemWidth(-90);
  track_edit(e, ImGui::SliderScalar("Width", ImGuiDataType_Double, &p.width, &wlo, &whi, "%.3f"),
             "Prism width");
  help_marker("Scale of every prism about its face centre: below 1 the surface shrinks, above 1 "
              "it grows.");
  double blo = -0.5, bhi = 1.5;
  ImGui::SetNextItemWidth(-90);
  track_edit(e, ImGui::SliderScalar("Shell/plate", ImGuiDataType_Double, &p.normal_blend, &blo, &bhi, "%.2f"),
             "Shell/plate blend");
  help_marker("0: thin shell (prisms extruded along vertex normals); 1: thin plate (face normals); "
              "below 0 enhances detail.");
  if (ImGui::Button("Defaults")) {
    p = PrismSettings{};
    e.commit("Default material");
  }
}

void display_section(Editor& e) {
  if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
  DisplaySettings& d = e.display;
  int smooth = d.smooth ? 1 : 0;
  ImGui::RadioButton("Smooth", &smooth, 1);
  ImGui::SameLine();
  ImGui::RadioButton("Flat (5)", &smooth, 0);
  d.smooth = smooth == 1;
  ImGui::Checkbox("Wireframe (4)", &d.wireframe);
  ImGui::SameLine(ImGui::GetContentRegionAvail().x * 0.5f);
  ImGui::Checkbox("Prisms (6)", &d.prisms);
  ImGui::Checkbox("Energy heat map (7)", &d.heat_map);
  ImGui::SameLine(ImGui::GetContentRegionAvail().x * 0.5f);
  ImGui::Checkbox("Paint colours (8)", &d.paint_overlay);
  ImGui::Checkbox("Ground grid", &d.grid);
  if (d.heat_map) {
    const auto g = e.geometry();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = ImGui::GetContentRegionAvail().x, h = 10;
    for (int i = 0; i < 64; ++i) {
      const Rgb c = heat_color(i / 63.0);
      dl->AddRectFilled(ImVec2(p.x + w * i / 64, p.y), ImVec2(p.x + w * (i + 1) / 64 + 1, p.y + h),
                        u32(c[0], c[1], c[2]));
    }
    ImGui::Dummy(ImVec2(w, h));
    ImGui::TextDisabled("joint energy per area: 0 .. %.3g", g && !g->face_energy.empty() ? g->energy_scale : 0.0);
  }
}

void draw_properties(Editor& e, UiState& ui, float top, float height) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x - ui.panel_width, top));
  ImGui::SetNextWindowSize(ImVec2(ui.panel_width, height));
  ImGui::Begin("Properties", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                   ImGuiWindowFlags_NoTitleBar);
  if (const Document* doc = e.document()) {
    const std::string& name = doc->scenario_path.empty() ? doc->mesh_path : doc->scenario_path;
    ImGui::TextUnformatted(fs::path(name).filename().string().c_str());
    ImGui::TextDisabled("%d vertices, %d faces", doc->topology->n_vertices, doc->n_faces());
  } else {
    ImGui::TextDisabled("No mesh: File > Open (Ctrl+O) or drop a file here");
  }
  // Each section its own ID scope: widgets of different sections may share a label (the
  // Paint tool's "Width" layer and the material's "Width" slider did, so clicking the first
  // moved the second).
  const std::pair<const char*, void (*)(Editor&)> sections[] = {
      {"tool", tool_section},       {"handles", handles_section}, {"prisms", prisms_section},
      {"history", history_section}, {"display", display_section}, {"solver", solver_section}};
  for (const auto& [id, draw] : sections) {
    ImGui::PushID(id);
    draw(e);
    ImGui::PopID();
  }
  ImGui::PushID("session");
  session_section(e, ui);  // its export asks for a file through the window's dialog
  ImGui::PopID();
  ImGui::End();
}

// --- Menu, status, progress, help -------------------------------------------------------

void draw_progress(Editor& e, const ViewportRect& vp) {
  const SolverStatus& st = e.solver_status();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - st.phase_start).count();
  std::string text;
  float fraction = -1.0f;
  if (e.file_task_running()) {
    char t[256];
    std::snprintf(t, sizeof t, "%s... %.1f s", e.file_task_label().c_str(), e.file_task_seconds());
    text = t;
  } else if (st.phase == SolverPhase::Building && seconds > 0.2) {
    char t[128];
    std::snprintf(t, sizeof t, "Building prisms... %.1f s", seconds);
    text = t;
  } else if (st.phase == SolverPhase::Solving && !st.detail.empty() && seconds > 0.2) {
    char t[160];
    std::snprintf(t, sizeof t, "Preparing the solver: %s... %.1f s", st.detail.c_str(), seconds);
    text = t;
  } else if (st.phase == SolverPhase::Solving && seconds > 0.4) {
    char t[160];
    if (st.showing_preview())
      std::snprintf(t, sizeof t, "Preview: coarse levels, energy %.4g (full resolution when the hand pauses)",
                    st.energy);
    else
      std::snprintf(t, sizeof t, "Converging: iteration %d, energy %.4g", st.iterations, st.energy);
    text = t;
    fraction = float(st.progress);
  }
  if (text.empty()) return;
  const float w = 360;
  ImGui::SetNextWindowPos(ImVec2(float(vp.x + vp.width * 0.5 - w * 0.5), float(vp.y + vp.height - 70)));
  ImGui::SetNextWindowSize(ImVec2(w, 0));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##progress", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                          ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                          ImGuiWindowFlags_NoInputs);
  ImGui::TextUnformatted(text.c_str());
  if (fraction < 0) {  // indeterminate: a sliding block
    const float t = float(std::fmod(ImGui::GetTime() * 0.8, 1.0));
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float bw = ImGui::GetContentRegionAvail().x, h = 6;
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(p, ImVec2(p.x + bw, p.y + h), u32(0.2f, 0.2f, 0.22f), 3);
    const float a = p.x + bw * std::max(0.0f, t * 1.3f - 0.3f), b = p.x + bw * std::min(1.0f, t * 1.3f);
    dl->AddRectFilled(ImVec2(a, p.y), ImVec2(b, p.y + h), u32(0.35f, 0.6f, 0.95f), 3);
    ImGui::Dummy(ImVec2(bw, h));
  } else {
    ImGui::ProgressBar(fraction, ImVec2(-1, 6), "");
  }
  ImGui::End();
}

void draw_error_popup(Editor& e, UiState& ui) {
  const std::string next = e.take_error_popup();
  if (!next.empty()) {
    ui.error_message = next;
    ImGui::OpenPopup("Problem");
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.4f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(460, 0), ImGuiCond_Appearing);
  if (ImGui::BeginPopupModal("Problem", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::PushTextWrapPos(440);
    ImGui::TextUnformatted(ui.error_message.c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::Button("OK", ImVec2(120, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
        ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
      ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

// Save / Discard / Cancel before unsaved work would be lost (Editor::discard_question).
void draw_discard_question(Editor& e, UiState& ui) {
  const auto& question = e.discard_question();
  if (!question) return;
  if (ui.dialog.is_open()) return;  // choosing where to save it
  if (!ImGui::IsPopupOpen("Unsaved changes")) ImGui::OpenPopup("Unsaved changes");
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.4f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  const Document* doc = e.document();
  const std::string name = doc ? fs::path(doc->scenario_path.empty() ? doc->mesh_path : doc->scenario_path)
                                     .filename()
                                     .string()
                               : std::string();
  const std::string then = question->then == Editor::DiscardQuestion::Then::Quit
                               ? "before quitting"
                               : "before opening " + fs::path(question->path).filename().string();
  ImGui::Text("Save the handles, poses, material and painting of %s %s?", name.c_str(), then.c_str());
  ImGui::TextDisabled("Discarding loses them and the undo history.");
  if (ImGui::Button("Save", ImVec2(110, 0))) {
    ImGui::CloseCurrentPopup();
    if (doc && !doc->scenario_path.empty()) {
      e.answer_discard(Editor::DiscardAnswer::Save);
    } else {
      ask_save_scenario(e, ui);
      ui.purpose = UiState::Purpose::SaveBeforeDiscard;
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Discard", ImVec2(110, 0))) {
    ImGui::CloseCurrentPopup();
    e.answer_discard(Editor::DiscardAnswer::Discard);
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(110, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
    ImGui::CloseCurrentPopup();
    e.answer_discard(Editor::DiscardAnswer::Cancel);
  }
  ImGui::EndPopup();
}

// Autosaved work left by a run that did not end cleanly, offered once at the start.
void draw_recovery(Editor& e, UiState& ui) {
  if (!ui.recovery_checked) {
    ui.recovery_checked = true;
    ui.recoverable = list_autosaved_work();
    if (!ui.recoverable.empty()) ImGui::OpenPopup("Recover unsaved work");
  }
  if (!ImGui::BeginPopupModal("Recover unsaved work", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::TextUnformatted("PriMo kept this work when it last closed without saving it:");
  for (size_t i = 0; i < ui.recoverable.size(); ++i) {
    const AutosavedWork& w = ui.recoverable[i];
    ImGui::PushID(int(i));
    ImGui::BulletText("%s", w.label.c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("Recover")) {
      e.recover(w.path);
      ui.recoverable.clear();
    } else {
      ImGui::SameLine();
      if (ImGui::SmallButton("Delete")) {
        remove_autosave(w.path);
        ui.recoverable.erase(ui.recoverable.begin() + long(i));
      }
    }
    ImGui::PopID();
  }
  if (ui.recoverable.empty() || ImGui::Button("Later", ImVec2(110, 0)))
    ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

}  // namespace

ViewportRect viewport_rect(const UiState& ui, float window_width, float window_height, float scale) {
  ViewportRect r;
  r.scale = scale;
  if (!ui.show_panels) {
    r.width = window_width;
    r.height = window_height;
    return r;
  }
  r.x = ui.toolbar_width;
  r.y = ui.menu_height;
  r.width = std::max(1.0f, window_width - ui.toolbar_width - ui.panel_width);
  r.height = std::max(1.0f, window_height - ui.menu_height - ui.status_height);
  return r;
}

void draw_ui(Editor& e, UiState& ui) {
  draw_viewport_overlays(e, ImGui::GetBackgroundDrawList());
  if (ui.show_panels) {
    draw_menu_bar(e, ui);
    const float top = ui.menu_height;
    const float height = ImGui::GetIO().DisplaySize.y - top - ui.status_height;
    draw_toolbar(e, ui, top, height);
    draw_properties(e, ui, top, height);
    draw_status_bar(e, ui);
    draw_progress(e, e.viewport());
  }
  draw_controls_window(e, ui);
  draw_error_popup(e, ui);
  draw_recovery(e, ui);
  draw_preferences_window(e, ui);
  draw_discard_question(e, ui);
  draw_file_dialog(e, ui);
}

}  // namespace primo::editor
