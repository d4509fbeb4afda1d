#pragma once
// The editor's panels, drawn with Dear ImGui each frame: main menu, tool strip, the
// properties panel (tool settings, handles, prisms, display, solver), status bar, progress,
// help, error popups and the file dialog. Panels call the Editor's commands; they keep no
// document state of their own.

#include <optional>
#include <string>

#include "user_files/autosave.h"
#include "editor.h"
#include "file_dialog.h"
#include "input/input.h"

namespace primo::editor {

struct UiState {
  bool show_panels = true;  // false: the viewport fills the window (clean screenshots)
  bool show_help = false;
  bool show_preferences = false;
  // Edit > Preferences > Keys: the command waiting for its new key (the next key pressed).
  struct KeyCapture {
    Action action;
    bool replace;  // the key replaces the command's keys; false: one more key
  };
  std::optional<KeyCapture> key_capture;
  FileDialog dialog;
  enum class Purpose {
    None, Open, SaveMesh, SaveScenario, Screenshot, SaveSessionAnimation,
    SaveBeforeDiscard,  // the scenario path for the "Save" answer to Editor::discard_question
  } purpose = Purpose::None;
  // Autosaved work offered for recovery once, at the first frame (autosave.h).
  bool recovery_checked = false;
  std::vector<AutosavedWork> recoverable;
  // A screenshot to take at the end of this frame.
  std::string screenshot_path;
  bool screenshot_with_ui = true;
  // Layout in window coordinates, measured while drawing.
  float menu_height = 0.0f, toolbar_width = 52.0f, panel_width = 340.0f, status_height = 26.0f;
  bool quit_requested = false;
  std::string error_message;  // shown in the error popup
};

// The rectangle left for the 3D view (window coordinates).
ViewportRect viewport_rect(const UiState& ui, float window_width, float window_height, float scale);

void draw_ui(Editor& editor, UiState& ui);

// Window-level shortcuts (files, help, screenshot). Returns true when the key was taken.
bool handle_app_shortcut(const InputEvent& event, Editor& editor, UiState& ui);

// The file-dialog actions, also used by menus.
void ask_open(Editor& editor, UiState& ui);
void ask_save_mesh(Editor& editor, UiState& ui);
void ask_save_scenario(Editor& editor, UiState& ui);
void ask_screenshot(Editor& editor, UiState& ui);
void ask_save_session_animation(Editor& editor, UiState& ui);
// Quit, or ask first when there is unsaved work (menu, Ctrl+Q, the window's close button).
void ask_quit(Editor& editor, UiState& ui);

}  // namespace primo::editor
