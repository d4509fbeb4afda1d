// The main menu bar, the window's own shortcuts (open, save, export, screenshot, panels,
// controls, quit) and the file dialogs they open.

#include "menu_bar.h"

#include <imgui.h>

#include <deque>
#include <filesystem>
#include <string>
#include <vector>

#include "document/model_orientation.h"
#include "paths.h"

namespace primo::editor {
namespace fs = std::filesystem;
namespace {

// What File > Open reads, and what Export writes (FBX, COLLADA and 3MF are read only).
const std::vector<std::string> kMeshExtensions = {".obj", ".off", ".ply",  ".stl", ".om",
                                                  ".gltf", ".glb", ".fbx", ".dae", ".3mf"};
const std::vector<std::string> kExportExtensions = {".obj", ".off", ".ply", ".stl",
                                                    ".om",  ".gltf", ".glb"};

std::string folder_of(const std::string& path) {
  if (path.empty()) return fs::current_path().string();
  return fs::absolute(path).parent_path().string();
}

std::string stem_of(const std::string& path) {
  return path.empty() ? "untitled" : fs::path(path).stem().string();
}

}  // namespace

void draw_menu_bar(Editor& e, UiState& ui) {
  if (!ImGui::BeginMainMenuBar()) return;
  ui.menu_height = ImGui::GetWindowSize().y;
  Document* doc = e.document();
  // Shortcut labels as the user's key map has them (Edit > Preferences > Keys).
  std::deque<std::string> labels;  // stable: ImGui reads the pointers until EndMenu
  auto keys = [&](Action action) {
    labels.push_back(e.key_map().label(action));
    return labels.back().c_str();
  };
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open mesh or scenario...", keys(Action::Open))) ask_open(e, ui);
    if (ImGui::BeginMenu("Open recent", !e.recent_files().entries().empty())) {
      for (const std::string& path : e.recent_files().entries())
        if (ImGui::MenuItem(path.c_str())) e.request_open(path);
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Open the example (Spot)")) e.request_open(default_mesh_path());
    ImGui::Separator();
    if (ImGui::MenuItem("Save scenario", keys(Action::Save), false, doc != nullptr)) {
      if (doc->scenario_path.empty())
        ask_save_scenario(e, ui);
      else
        e.save_scenario(doc->scenario_path);
    }
    if (ImGui::MenuItem("Save scenario as...", keys(Action::SaveAs), false, doc != nullptr)) ask_save_scenario(e, ui);
    if (ImGui::MenuItem("Export deformed mesh...", keys(Action::Export), false, doc != nullptr)) ask_save_mesh(e, ui);
    if (ImGui::MenuItem("Export session animation (.glb)...", nullptr, false,
                        doc != nullptr && e.sessions.has_session() && !e.sessions.exporting()))
      ask_save_session_animation(e, ui);
    if (ImGui::MenuItem("Screenshot...", keys(Action::Screenshot), false, doc != nullptr)) ask_screenshot(e, ui);
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", keys(Action::Quit))) ask_quit(e, ui);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    const std::string undo = doc && doc->history.can_undo() ? "Undo " + doc->history.undo_label() : "Undo";
    const std::string redo = doc && doc->history.can_redo() ? "Redo " + doc->history.redo_label() : "Redo";
    if (ImGui::MenuItem(undo.c_str(), keys(Action::Undo), false, doc && doc->history.can_undo())) e.undo();
    if (ImGui::MenuItem(redo.c_str(), keys(Action::Redo), false, doc && doc->history.can_redo())) e.redo();
    if (doc && doc->history.can_undo()) {
      const UndoStack& h = doc->history;
      const std::size_t steps = h.position() - h.group_of(h.position()).first + 1;
      if (steps > 1) {
        const std::string group = "Undo " + std::to_string(steps) + " x " + h.undo_label();
        if (ImGui::MenuItem(group.c_str(), keys(Action::UndoGroup))) e.undo_group();
      }
    }
    if (ImGui::MenuItem("Preferences...")) ui.show_preferences = true;
    ImGui::Separator();
    const bool vertex_mode = e.selection_mode() == SelectionMode::Vertices;
    if (ImGui::MenuItem("Vertex mode", keys(Action::SelectVertexMode), vertex_mode, doc != nullptr))
      e.set_selection_mode(SelectionMode::Vertices);
    if (ImGui::MenuItem("Face mode", keys(Action::SelectFaceMode), !vertex_mode, doc != nullptr))
      e.set_selection_mode(SelectionMode::Faces);
    if (ImGui::MenuItem("Select all", keys(Action::SelectAll))) e.select_all();
    if (ImGui::MenuItem("Select none", keys(Action::SelectNone))) e.clear_selection();
    if (ImGui::MenuItem("Invert selection", keys(Action::SelectInvert))) e.invert_selection();
    if (ImGui::MenuItem("Grow selection", keys(Action::SelectGrow))) e.grow_selection();
    if (ImGui::MenuItem("Shrink selection", keys(Action::SelectShrink))) e.shrink_selection();
    if (ImGui::MenuItem("Select linked", keys(Action::SelectLinked))) e.select_linked(false);
    if (ImGui::MenuItem("Select linked by angle", keys(Action::SelectLinkedByAngle))) e.select_linked(true);
    ImGui::Separator();
    const bool any_hidden = doc && count_hidden(doc->state.hidden) > 0;
    if (ImGui::MenuItem("Hide selected", keys(Action::HideSelected))) e.hide_selected();
    if (ImGui::MenuItem("Hide unselected", keys(Action::HideUnselected))) e.hide_unselected();
    if (ImGui::MenuItem("Reveal all", keys(Action::RevealAll), false, any_hidden)) e.reveal_all();
    ImGui::Separator();
    for (int axis = 0; axis < 3; ++axis) {
      bool on = e.tools.mirror[size_t(axis)];
      const std::string label = std::string("Mirror ") + axis_name(axis);
      const Action action = axis == 0 ? Action::MirrorX : axis == 1 ? Action::MirrorY : Action::MirrorZ;
      if (ImGui::MenuItem(label.c_str(), keys(action), &on, doc != nullptr)) e.set_mirror(axis, on);
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Handle from selection", keys(Action::MakeHandle))) e.make_handle(HandleMode::Pose);
    if (ImGui::MenuItem("Fixed region from selection", keys(Action::MakeFixedRegion))) e.make_handle(HandleMode::Fixed);
    if (ImGui::MenuItem("Spring from selection", keys(Action::MakeSpring))) e.make_handle(HandleMode::Spring);
    const bool active = doc && doc->state.active >= 0;
    if (ImGui::MenuItem("Reset active handle", keys(Action::ResetHandle), false, active)) e.reset_handle(doc->state.active);
    if (ImGui::MenuItem("Reset all handles", keys(Action::ResetAllHandles), false, doc && !doc->state.handles.empty()))
      e.reset_all_handles();
    if (ImGui::MenuItem("Delete active handle", keys(Action::DeleteHandle), false, active)) e.delete_handle(doc->state.active);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Frame all", keys(Action::FrameAll))) e.frame_all();
    if (ImGui::MenuItem("Frame selection", keys(Action::FrameSelection))) e.frame_selection();
    if (ImGui::MenuItem("Front", keys(Action::ViewFront))) e.camera().view_preset(ViewPreset::Front);
    if (ImGui::MenuItem("Right", keys(Action::ViewRight))) e.camera().view_preset(ViewPreset::Right);
    if (ImGui::MenuItem("Top", keys(Action::ViewTop))) e.camera().view_preset(ViewPreset::Top);
    // Views are the model's: its front and up (docs/editor.md, "Looking around").
    if (ImGui::MenuItem("Set front from view", keys(Action::SetFrontFromView), false, doc != nullptr))
      e.set_front_from_view();
    if (doc) ImGui::TextDisabled("  Model: %s", orientation_label(doc->state.orientation).c_str());
    bool ortho = e.camera().orthographic();
    if (ImGui::MenuItem("Orthographic", keys(Action::ToggleProjection), &ortho)) e.camera().set_orthographic(ortho);
    ImGui::Separator();
    ImGui::MenuItem("Smooth shading", keys(Action::ToggleSmooth), &e.display.smooth);
    ImGui::MenuItem("Wireframe", keys(Action::ToggleWireframe), &e.display.wireframe);
    ImGui::MenuItem("Prism layer", keys(Action::TogglePrisms), &e.display.prisms);
    ImGui::MenuItem("Energy heat map", keys(Action::ToggleHeatMap), &e.display.heat_map);
    ImGui::MenuItem("Paint colours", keys(Action::TogglePaintOverlay), &e.display.paint_overlay);
    ImGui::MenuItem("Ground grid", keys(Action::ToggleGrid), &e.display.grid);
    ImGui::Separator();
    ImGui::MenuItem("Panels", keys(Action::TogglePanels), &ui.show_panels);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    if (ImGui::MenuItem("Controls", keys(Action::ShowControls))) ui.show_help = true;
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void draw_file_dialog(Editor& e, UiState& ui) {
  std::string path;
  if (!ui.dialog.draw(path)) return;
  switch (ui.purpose) {
    case UiState::Purpose::Open: e.request_open(path); break;
    case UiState::Purpose::SaveBeforeDiscard: e.answer_discard(Editor::DiscardAnswer::Save, path); break;
    case UiState::Purpose::SaveMesh: e.save_mesh(path); break;
    case UiState::Purpose::SaveScenario: e.save_scenario(path); break;
    case UiState::Purpose::SaveSessionAnimation: e.sessions.export_animation(e, path); break;
    case UiState::Purpose::Screenshot:
      ui.screenshot_path = path;
      ui.screenshot_with_ui = false;
      break;
    case UiState::Purpose::None: break;
  }
  ui.purpose = UiState::Purpose::None;
}

void ask_quit(Editor& e, UiState& ui) {
  if (e.ask_to_quit()) ui.quit_requested = true;
}

void ask_open(Editor& e, UiState& ui) {
  std::vector<std::string> ext = kMeshExtensions;
  ext.push_back(".json");
  const Document* doc = e.document();
  ui.purpose = UiState::Purpose::Open;
  ui.dialog.open(FileDialog::Mode::Open, "Open a mesh or scenario", ext,
                 doc ? folder_of(doc->mesh_path) : asset_dir() + "/meshes");
}

void ask_save_mesh(Editor& e, UiState& ui) {
  const Document* doc = e.document();
  if (!doc) return;
  ui.purpose = UiState::Purpose::SaveMesh;
  ui.dialog.open(FileDialog::Mode::Save, "Export the deformed mesh", kExportExtensions,
                 fs::current_path().string(), stem_of(doc->mesh_path) + "-deformed.obj");
}

void ask_save_scenario(Editor& e, UiState& ui) {
  const Document* doc = e.document();
  if (!doc) return;
  ui.purpose = UiState::Purpose::SaveScenario;
  ui.dialog.open(FileDialog::Mode::Save, "Save the scenario", {".json"},
                 doc->scenario_path.empty() ? fs::current_path().string() : folder_of(doc->scenario_path),
                 doc->scenario_path.empty() ? stem_of(doc->mesh_path) + "-setup.json"
                                            : fs::path(doc->scenario_path).filename().string());
}

void ask_save_session_animation(Editor& e, UiState& ui) {
  const Document* doc = e.document();
  if (!doc || !e.sessions.has_session()) return;
  ui.purpose = UiState::Purpose::SaveSessionAnimation;
  ui.dialog.open(FileDialog::Mode::Save, "Export the session as an animated glTF", {".glb", ".gltf"},
                 folder_of(doc->mesh_path), stem_of(doc->mesh_path) + "-session.glb");
}

void ask_screenshot(Editor& e, UiState& ui) {
  const Document* doc = e.document();
  ui.purpose = UiState::Purpose::Screenshot;
  ui.dialog.open(FileDialog::Mode::Save, "Save a screenshot", {".png"}, fs::current_path().string(),
                 (doc ? stem_of(doc->mesh_path) : std::string("primo")) + ".png");
}

bool handle_app_shortcut(const InputEvent& ev, Editor& e, UiState& ui) {
  if (ev.type != InputEvent::Type::Key || ev.action != GLFW_PRESS) return false;
  const std::optional<Action> action = e.key_map().action_for(ev.key, ev.mods);
  if (!action) return false;
  switch (*action) {
    case Action::Open: ask_open(e, ui); return true;
    case Action::Save:
      if (!e.document()) return false;
      if (e.document()->scenario_path.empty())
        ask_save_scenario(e, ui);
      else
        e.save_scenario(e.document()->scenario_path);
      return true;
    case Action::SaveAs:
      if (!e.document()) return false;
      ask_save_scenario(e, ui);
      return true;
    case Action::Export: ask_save_mesh(e, ui); return true;
    case Action::Screenshot: ask_screenshot(e, ui); return true;
    case Action::ShowControls: ui.show_help = !ui.show_help; return true;
    case Action::TogglePanels: ui.show_panels = !ui.show_panels; return true;
    case Action::Quit: ask_quit(e, ui); return true;
    default: return false;  // the editor's
  }
}

}  // namespace primo::editor
