#include "key_map.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "input.h"

namespace primo::editor {
namespace {

constexpr int kCtrl = GLFW_MOD_CONTROL, kShift = GLFW_MOD_SHIFT, kAlt = GLFW_MOD_ALT;
// Caps Lock and Num Lock are states, not part of a chord.
constexpr int kChordMods = GLFW_MOD_CONTROL | GLFW_MOD_SHIFT | GLFW_MOD_ALT | GLFW_MOD_SUPER;

std::vector<ActionInfo> make_actions() {
  const char* view = "View";
  const char* tools = "Tools";
  const char* sel = "Selection and handles";
  const char* files = "Files and history";
  using A = Action;
  std::vector<ActionInfo> a = {
      {A::FrameSelection, "frame_selection", view, "frame the selection or active handle",
       {{GLFW_KEY_F, 0}, {GLFW_KEY_KP_DECIMAL, 0}}},
      {A::FrameAll, "frame_all", view, "frame all", {{GLFW_KEY_HOME, 0}}},
      {A::ViewFront, "view_front", view, "the model's front view", {{GLFW_KEY_KP_1, 0}}},
      {A::ViewBack, "view_back", view, "the model's back view", {{GLFW_KEY_KP_1, kCtrl}}},
      {A::ViewRight, "view_right", view, "the model's right view", {{GLFW_KEY_KP_3, 0}}},
      {A::ViewLeft, "view_left", view, "the model's left view", {{GLFW_KEY_KP_3, kCtrl}}},
      {A::ViewTop, "view_top", view, "the model's top view", {{GLFW_KEY_KP_7, 0}}},
      {A::ViewBottom, "view_bottom", view, "the model's bottom view", {{GLFW_KEY_KP_7, kCtrl}}},
      {A::ToggleProjection, "toggle_projection", view, "perspective / orthographic",
       {{GLFW_KEY_KP_5, 0}}},
      {A::ToggleWireframe, "toggle_wireframe", view, "wireframe overlay", {{GLFW_KEY_4, 0}}},
      {A::ToggleSmooth, "toggle_smooth", view, "smooth / flat shading", {{GLFW_KEY_5, 0}}},
      {A::TogglePrisms, "toggle_prisms", view, "the prism layer", {{GLFW_KEY_6, 0}}},
      {A::ToggleHeatMap, "toggle_heat_map", view, "energy heat map", {{GLFW_KEY_7, 0}}},
      {A::TogglePaintOverlay, "toggle_paint_colours", view, "painted factors in colour",
       {{GLFW_KEY_8, 0}}},
      {A::ToggleGrid, "toggle_grid", view, "ground grid", {{GLFW_KEY_9, 0}}},
      {A::SetFrontFromView, "set_front_from_view", view,
       "the model's front is where the view looks from (Numpad 1 then shows it)",
       {{GLFW_KEY_KP_1, kCtrl | kAlt}}},
      {A::TogglePanels, "toggle_panels", view, "hide or show the panels", {{GLFW_KEY_F10, 0}}},
      {A::ShowControls, "show_controls", view, "this list of controls", {{GLFW_KEY_F1, 0}}},

      {A::ToolSelect, "tool_select", tools, "select tool", {{GLFW_KEY_Q, 0}}},
      {A::ShapeBrush, "select_brush", tools, "select with a brush", {{GLFW_KEY_C, 0}}},
      {A::ShapeBox, "select_box", tools, "select with a box", {{GLFW_KEY_B, 0}}},
      {A::ShapeLasso, "select_lasso", tools, "select with a lasso", {{GLFW_KEY_L, 0}}},
      {A::ToolDrag, "tool_drag", tools, "drag handles in the view plane", {{GLFW_KEY_G, 0}}},
      {A::ToolMove, "tool_move", tools, "move gizmo on the active handle (Ctrl snaps)",
       {{GLFW_KEY_W, 0}}},
      {A::ToolRotate, "tool_rotate", tools, "rotate gizmo on the active handle (Ctrl snaps)",
       {{GLFW_KEY_E, 0}}},
      {A::ToolPaint, "tool_paint", tools, "paint stiffness or width (Ctrl erases)",
       {{GLFW_KEY_P, 0}}},
      {A::BrushSmaller, "brush_smaller", tools, "smaller brush", {{GLFW_KEY_LEFT_BRACKET, 0}}},
      {A::BrushLarger, "brush_larger", tools, "larger brush", {{GLFW_KEY_RIGHT_BRACKET, 0}}},
      {A::ToggleXray, "toggle_xray", tools, "x-ray selection (reach hidden faces)",
       {{GLFW_KEY_Z, kAlt}}},
      {A::CycleGizmoOrientation, "cycle_gizmo_orientation", tools,
       "gizmo axes: global, local, normal, view", {{GLFW_KEY_COMMA, 0}}},
      {A::Cancel, "cancel", tools, "cancel the current drag or stroke, else an open under way",
       {{GLFW_KEY_ESCAPE, 0}}},

      {A::SelectAll, "select_all", sel, "select all", {{GLFW_KEY_A, 0}}},
      {A::SelectNone, "select_none", sel, "select none", {{GLFW_KEY_A, kAlt}}},
      {A::SelectInvert, "select_invert", sel, "invert the selection", {{GLFW_KEY_I, kCtrl}}},
      {A::SelectGrow, "select_grow", sel, "grow the selection by a ring",
       {{GLFW_KEY_EQUAL, kCtrl}, {GLFW_KEY_KP_ADD, kCtrl}}},
      {A::SelectShrink, "select_shrink", sel, "shrink the selection by a ring",
       {{GLFW_KEY_MINUS, kCtrl}, {GLFW_KEY_KP_SUBTRACT, kCtrl}}},
      {A::SelectLinked, "select_linked", sel, "select linked", {{GLFW_KEY_L, kCtrl}}},
      {A::SelectLinkedByAngle, "select_linked_by_angle", sel,
       "select linked up to sharp edges", {{GLFW_KEY_L, kCtrl | kShift}}},
      {A::HideSelected, "hide_selected", sel, "hide the selection (still deforms)",
       {{GLFW_KEY_H, 0}}},
      {A::HideUnselected, "hide_unselected", sel, "hide every face but the selection (isolate)",
       {{GLFW_KEY_H, kShift}}},
      {A::RevealAll, "reveal_all", sel, "show hidden faces again (selected)", {{GLFW_KEY_H, kAlt}}},
      {A::SelectVertexMode, "vertex_mode", sel,
       "vertex mode: pick vertices (a handle takes the faces touching them)", {{GLFW_KEY_1, 0}}},
      {A::SelectFaceMode, "face_mode", sel, "face mode: pick faces", {{GLFW_KEY_3, 0}}},
      {A::ToggleFalloff, "toggle_falloff", sel,
       "soft selection: the active handle's falloff on or off (Alt + wheel: its radius)",
       {{GLFW_KEY_O, 0}}},
      {A::MirrorX, "mirror_x", sel, "mirror across X (select, paint, handles)",
       {{GLFW_KEY_X, kShift}}},
      {A::MirrorY, "mirror_y", sel, "mirror across Y", {{GLFW_KEY_Y, kShift}}},
      {A::MirrorZ, "mirror_z", sel, "mirror across Z", {{GLFW_KEY_Z, kShift}}},
      {A::MakeHandle, "make_handle", sel, "handle from the selection (position + orientation)",
       {{GLFW_KEY_G, kCtrl}}},
      {A::MakeFixedRegion, "make_fixed_region", sel, "fixed region from the selection",
       {{GLFW_KEY_G, kCtrl | kShift}}},
      {A::MakeSpring, "make_spring", sel, "spring from the selection",
       {{GLFW_KEY_G, kCtrl | kAlt}}},
      {A::NextHandle, "next_handle", sel, "next handle", {{GLFW_KEY_TAB, 0}}},
      {A::PreviousHandle, "previous_handle", sel, "previous handle", {{GLFW_KEY_TAB, kShift}}},
      {A::ResetHandle, "reset_handle", sel, "reset the active handle", {{GLFW_KEY_G, kAlt}}},
      {A::ResetAllHandles, "reset_all_handles", sel, "reset all handles",
       {{GLFW_KEY_G, kAlt | kShift}}},
      {A::DeleteHandle, "delete_handle", sel, "delete the active handle",
       {{GLFW_KEY_DELETE, 0}, {GLFW_KEY_X, 0}}},
      {A::PivotToCursor, "pivot_to_cursor", sel,
       "the active handle's pivot to the surface under the cursor (also Ctrl+Shift+right-click)",
       {{GLFW_KEY_S, kShift}}},

      {A::Undo, "undo", files, "undo (one drag, stroke or slider change)", {{GLFW_KEY_Z, kCtrl}}},
      {A::Redo, "redo", files, "redo", {{GLFW_KEY_Z, kCtrl | kShift}, {GLFW_KEY_Y, kCtrl}}},
      {A::UndoGroup, "undo_group", files, "undo a whole group of like steps (five drags of one handle)",
       {{GLFW_KEY_Z, kCtrl | kAlt}}},
      {A::Open, "open", files, "open a mesh or scenario (or drop a file on the window)",
       {{GLFW_KEY_O, kCtrl}}},
      {A::Save, "save", files, "save the scenario", {{GLFW_KEY_S, kCtrl}}},
      {A::SaveAs, "save_as", files, "save the scenario as", {{GLFW_KEY_S, kCtrl | kShift}}},
      {A::Export, "export", files, "export the deformed mesh", {{GLFW_KEY_E, kCtrl}}},
      {A::Screenshot, "screenshot", files, "screenshot (PNG)", {{GLFW_KEY_F12, 0}}},
      {A::Quit, "quit", files, "quit", {{GLFW_KEY_Q, kCtrl}}},
  };
  return a;
}

}  // namespace

const std::vector<ActionInfo>& all_actions() {
  static const std::vector<ActionInfo> actions = [] {
    std::vector<ActionInfo> a = make_actions();
    // Indexable by Action: every action once, in enum order.
    std::sort(a.begin(), a.end(),
              [](const ActionInfo& x, const ActionInfo& y) { return x.action < y.action; });
    if (a.size() != size_t(Action::Count))
      throw std::logic_error("key_map.cpp: an action has no entry");
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i].action != Action(i)) throw std::logic_error("key_map.cpp: an action is listed twice");
    return a;
  }();
  return actions;
}

const ActionInfo& action_info(Action action) { return all_actions()[size_t(action)]; }

std::optional<Action> action_from_id(const std::string& id) {
  for (const ActionInfo& a : all_actions())
    if (id == a.id) return a.action;
  return std::nullopt;
}

std::string chord_label(const KeyChord& chord) {
  std::string text;
  if (chord.mods & GLFW_MOD_CONTROL) text += "Ctrl+";
  if (chord.mods & GLFW_MOD_SHIFT) text += "Shift+";
  if (chord.mods & GLFW_MOD_ALT) text += "Alt+";
  if (chord.mods & GLFW_MOD_SUPER) text += "Super+";
  return text + key_label(chord.key);
}

KeyChord parse_chord(const std::string& text) {
  KeyChord c;
  parse_key_combo(text, c.key, c.mods);
  return c;
}

bool is_reserved(const KeyChord& chord) {
  return modifier_bit(chord.key) != 0 || chord.key == GLFW_KEY_ESCAPE || chord.key <= 0;
}

KeyMap::KeyMap() { reset_all(); }

std::optional<Action> KeyMap::action_for(int key, int mods) const {
  const KeyChord chord{key, mods & kChordMods};
  for (size_t a = 0; a < chords_.size(); ++a)
    if (std::find(chords_[a].begin(), chords_[a].end(), chord) != chords_[a].end())
      return Action(a);
  return std::nullopt;
}

const std::vector<KeyChord>& KeyMap::chords(Action action) const {
  return chords_[size_t(action)];
}

std::string KeyMap::label(Action action) const {
  std::string text;
  for (const KeyChord& c : chords(action)) text += (text.empty() ? "" : ", ") + chord_label(c);
  return text;
}

std::optional<Action> KeyMap::bind(Action action, const KeyChord& chord, bool replace) {
  const KeyChord c{chord.key, chord.mods & kChordMods};
  std::optional<Action> taken_from;
  for (size_t a = 0; a < chords_.size(); ++a) {
    auto& list = chords_[a];
    const auto it = std::find(list.begin(), list.end(), c);
    if (it == list.end()) continue;
    if (Action(a) != action) taken_from = Action(a);
    list.erase(it);
  }
  auto& mine = chords_[size_t(action)];
  if (replace) mine.clear();
  mine.push_back(c);
  return taken_from;
}

void KeyMap::unbind(Action action) { chords_[size_t(action)].clear(); }

void KeyMap::reset(Action action) {
  // The defaults come back, taken from whichever action holds them now.
  unbind(action);
  for (const KeyChord& c : action_info(action).defaults) bind(action, c, false);
}

void KeyMap::reset_all() {
  chords_.clear();
  for (const ActionInfo& a : all_actions()) chords_.push_back(a.defaults);
}

bool KeyMap::is_default(Action action) const {
  return chords(action) == action_info(action).defaults;
}

bool KeyMap::all_default() const {
  for (const ActionInfo& a : all_actions())
    if (!is_default(a.action)) return false;
  return true;
}

nlohmann::json KeyMap::overrides() const {
  nlohmann::json keys = nlohmann::json::object();
  for (const ActionInfo& a : all_actions()) {
    if (is_default(a.action)) continue;
    nlohmann::json list = nlohmann::json::array();
    for (const KeyChord& c : chords(a.action)) list.push_back(chord_label(c));
    keys[a.id] = std::move(list);
  }
  return keys;
}

std::vector<std::string> KeyMap::apply_overrides(const nlohmann::json& keys) {
  std::vector<std::string> problems;
  if (!keys.is_object()) {
    problems.push_back("keys: expected an object of action: [\"Ctrl+Z\", ...]");
    return problems;
  }
  std::vector<KeyChord> claimed;  // by an earlier entry of this file
  for (const auto& [id, value] : keys.items()) {
    const std::string at = "keys." + id;
    const std::optional<Action> action = action_from_id(id);
    if (!action) {
      problems.push_back(at + ": no such action");
      continue;
    }
    if (!value.is_array()) {
      problems.push_back(at + ": expected a list of keys such as [\"Ctrl+Z\"]");
      continue;
    }
    std::vector<KeyChord> chords;
    for (const auto& item : value) {
      try {
        if (!item.is_string()) throw std::invalid_argument("expected a string such as \"Ctrl+Z\"");
        const KeyChord c = parse_chord(item.get<std::string>());
        if (is_reserved(c)) throw std::invalid_argument("'" + chord_label(c) + "' cannot be bound");
        if (std::find(claimed.begin(), claimed.end(), c) != claimed.end())
          throw std::invalid_argument("'" + chord_label(c) + "' is bound to another action too");
        chords.push_back(c);
      } catch (const std::invalid_argument& e) {
        problems.push_back(at + ": " + e.what());
      }
    }
    if (chords.empty() && !value.empty()) continue;  // nothing readable: the defaults stay
    unbind(*action);
    for (const KeyChord& c : chords) {
      bind(*action, c, false);
      claimed.push_back(c);
    }
  }
  return problems;
}

}  // namespace primo::editor
