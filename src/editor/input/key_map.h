#pragma once
// Which key does what: every keyboard command of the editor is an Action with default chords
// (Blender and Maya habits), and the user may rebind any of them in Edit > Preferences
// (saved as the `keys` object of preferences.json: only the actions that differ from the
// defaults). The editor and the window look their shortcuts up here, and the Controls window
// (F1) and the menus print them from here, so what is shown is what works.
//
// A chord is a key with exact modifiers (Ctrl, Shift, Alt, Super; lock keys ignored), so
// E (rotate tool) and Ctrl+E (export) never collide. A chord belongs to one action at most:
// binding it to one takes it from the other.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

namespace primo::editor {

enum class Action {
  // View
  FrameSelection, FrameAll, ViewFront, ViewBack, ViewRight, ViewLeft, ViewTop, ViewBottom,
  ToggleProjection, ToggleWireframe, ToggleSmooth, TogglePrisms, ToggleHeatMap,
  TogglePaintOverlay, ToggleGrid, SetFrontFromView, TogglePanels, ShowControls,
  // Tools
  ToolSelect, ShapeBrush, ShapeBox, ShapeLasso, ToolDrag, ToolMove, ToolRotate, ToolPaint,
  BrushSmaller, BrushLarger, ToggleXray, CycleGizmoOrientation, Cancel,
  // Selection and handles
  SelectAll, SelectNone, SelectInvert, SelectGrow, SelectShrink, SelectLinked,
  SelectLinkedByAngle, HideSelected, HideUnselected, RevealAll, SelectVertexMode,
  SelectFaceMode, ToggleFalloff, MirrorX, MirrorY, MirrorZ, MakeHandle, MakeFixedRegion, MakeSpring,
  NextHandle, PreviousHandle, ResetHandle, ResetAllHandles, DeleteHandle, PivotToCursor,
  // Files and history
  Undo, Redo, UndoGroup, Open, Save, SaveAs, Export, Screenshot, Quit,
  Count
};

struct KeyChord {
  int key = 0;   // GLFW_KEY_*
  int mods = 0;  // GLFW_MOD_CONTROL | GLFW_MOD_SHIFT | GLFW_MOD_ALT | GLFW_MOD_SUPER
  bool operator==(const KeyChord& o) const { return key == o.key && mods == o.mods; }
  bool operator!=(const KeyChord& o) const { return !(*this == o); }
};

struct ActionInfo {
  Action action;
  const char* id;       // the name in preferences.json ("undo", "view_front")
  const char* section;  // "View", "Tools", "Selection and handles", "Files and history"
  const char* label;    // what it does, for the Controls window and the preferences
  std::vector<KeyChord> defaults;
};

// Every action in the order the Controls window lists them.
const std::vector<ActionInfo>& all_actions();
const ActionInfo& action_info(Action action);
std::optional<Action> action_from_id(const std::string& id);

// "Ctrl+Shift+Z", "Numpad 1", "Delete", "[": what menus and the Controls window print, and
// what parse_chord reads back (it also reads the script syntax: "ctrl+shift+z", "kp_1").
std::string chord_label(const KeyChord& chord);
// Throws std::invalid_argument naming what it could not read.
KeyChord parse_chord(const std::string& text);
// True for chords that cannot be bound: a lone modifier key, or Esc (it always cancels).
bool is_reserved(const KeyChord& chord);

class KeyMap {
 public:
  KeyMap();  // the defaults

  std::optional<Action> action_for(int key, int mods) const;
  const std::vector<KeyChord>& chords(Action action) const;
  // "Ctrl+Shift+Z, Ctrl+Y"; "" when unbound.
  std::string label(Action action) const;

  // Makes `chord` one of `action`'s chords (the only one with `replace`). Returns the action
  // the chord was taken from, if any.
  std::optional<Action> bind(Action action, const KeyChord& chord, bool replace);
  void unbind(Action action);
  void reset(Action action);
  void reset_all();
  bool is_default(Action action) const;
  bool all_default() const;

  // The actions whose chords differ from the defaults: {"undo": ["Ctrl+U"], "quit": []}.
  nlohmann::json overrides() const;
  // Applies what overrides() wrote. Unknown actions, unreadable chords and chords claimed
  // twice are skipped; each gives one message naming the key ("keys.undo: unknown key
  // 'hyper'") for the caller to report with the file's name.
  std::vector<std::string> apply_overrides(const nlohmann::json& keys);

  bool operator==(const KeyMap& o) const { return chords_ == o.chords_; }

 private:
  std::vector<std::vector<KeyChord>> chords_;  // per action
};

}  // namespace primo::editor
