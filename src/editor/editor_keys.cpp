// Keyboard commands: a key press is looked up in the user's key map (key_map.h) and runs its
// action, so that rebinding a key in the preferences changes what it does everywhere.

#include "editor.h"

#include <algorithm>

namespace primo::editor {

void Editor::on_key(const InputEvent& e) {
  if (const std::optional<Action> action = key_map().action_for(e.key, e.mods)) run_action(*action);
}

bool Editor::run_action(Action action) {
  auto toggle = [](bool& flag) { flag = !flag; };
  auto select_shape = [this](SelectShape shape) {
    tools.shape = shape;
    set_tool(Tool::Select);
  };
  switch (action) {
    case Action::FrameSelection: frame_selection(); return true;
    case Action::FrameAll: frame_all(); return true;
    case Action::ViewFront: camera_.view_preset(ViewPreset::Front); return true;
    case Action::ViewBack: camera_.view_preset(ViewPreset::Back); return true;
    case Action::ViewRight: camera_.view_preset(ViewPreset::Right); return true;
    case Action::ViewLeft: camera_.view_preset(ViewPreset::Left); return true;
    case Action::ViewTop: camera_.view_preset(ViewPreset::Top); return true;
    case Action::ViewBottom: camera_.view_preset(ViewPreset::Bottom); return true;
    case Action::ToggleProjection: camera_.set_orthographic(!camera_.orthographic()); return true;
    case Action::ToggleWireframe: toggle(display.wireframe); return true;
    case Action::ToggleSmooth: toggle(display.smooth); return true;
    case Action::TogglePrisms: toggle(display.prisms); return true;
    case Action::ToggleHeatMap: toggle(display.heat_map); return true;
    case Action::TogglePaintOverlay: toggle(display.paint_overlay); return true;
    case Action::ToggleGrid: toggle(display.grid); return true;
    case Action::SetFrontFromView: set_front_from_view(); return true;

    case Action::ToolSelect: set_tool(Tool::Select); return true;
    case Action::ShapeBrush: select_shape(SelectShape::Brush); return true;
    case Action::ShapeBox: select_shape(SelectShape::Box); return true;
    case Action::ShapeLasso: select_shape(SelectShape::Lasso); return true;
    case Action::ToolDrag: set_tool(Tool::Drag); return true;
    case Action::ToolMove: set_tool(Tool::Move); return true;
    case Action::ToolRotate: set_tool(Tool::Rotate); return true;
    case Action::ToolPaint: set_tool(Tool::Paint); return true;
    case Action::BrushSmaller: tools.brush_radius = std::max(2.0, tools.brush_radius / 1.2); return true;
    case Action::BrushLarger: tools.brush_radius = std::min(400.0, tools.brush_radius * 1.2); return true;
    case Action::ToggleXray:
      toggle(tools.xray);
      info(tools.xray ? "X-ray selection on: hidden faces are selected too" : "X-ray selection off");
      return true;
    case Action::CycleGizmoOrientation:
      tools.gizmo_orientation = next_orientation(tools.gizmo_orientation);
      info(std::string("Gizmo axes: ") + orientation_label(tools.gizmo_orientation));
      return true;
    case Action::Cancel:  // a drag or stroke first, else an open under way
      if (gesture_ == Gesture::None && cancel_open()) return true;
      cancel_gesture();
      return true;

    case Action::SelectAll: select_all(); return true;
    case Action::SelectNone: clear_selection(); return true;
    case Action::SelectInvert: invert_selection(); return true;
    case Action::SelectGrow: grow_selection(); return true;
    case Action::SelectShrink: shrink_selection(); return true;
    case Action::SelectLinked: select_linked(false); return true;
    case Action::SelectLinkedByAngle: select_linked(true); return true;
    case Action::HideSelected: hide_selected(); return true;
    case Action::HideUnselected: hide_unselected(); return true;
    case Action::RevealAll: reveal_all(); return true;
    case Action::SelectVertexMode: set_selection_mode(SelectionMode::Vertices); return true;
    case Action::SelectFaceMode: set_selection_mode(SelectionMode::Faces); return true;
    case Action::ToggleFalloff: toggle_falloff(); return true;
    case Action::MirrorX: set_mirror(0, !tools.mirror[0]); return true;
    case Action::MirrorY: set_mirror(1, !tools.mirror[1]); return true;
    case Action::MirrorZ: set_mirror(2, !tools.mirror[2]); return true;
    case Action::MakeHandle: make_handle(HandleMode::Pose); return true;
    case Action::MakeFixedRegion: make_handle(HandleMode::Fixed); return true;
    case Action::MakeSpring: make_handle(HandleMode::Spring); return true;
    case Action::NextHandle:
    case Action::PreviousHandle:
      if (doc_ && !doc_->state.handles.empty()) {
        const int n = int(doc_->state.handles.size());
        set_active_handle((doc_->state.active + (action == Action::PreviousHandle ? n - 1 : 1)) % n);
      }
      return true;
    case Action::ResetHandle:
      if (doc_) reset_handle(doc_->state.active);
      return true;
    case Action::ResetAllHandles: reset_all_handles(); return true;
    case Action::DeleteHandle:
      if (doc_) delete_handle(doc_->state.active);
      return true;
    case Action::PivotToCursor: pivot_to_cursor(); return true;

    case Action::Undo: undo(); return true;
    case Action::Redo: redo(); return true;
    case Action::UndoGroup: undo_group(); return true;
    case Action::Quit: request_quit(); return true;

    // The window's: it draws their dialogs and panels.
    case Action::TogglePanels:
    case Action::ShowControls:
    case Action::Open:
    case Action::Save:
    case Action::SaveAs:
    case Action::Export:
    case Action::Screenshot:
    case Action::Count: return false;
  }
  return false;
}

}  // namespace primo::editor
