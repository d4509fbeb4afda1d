#pragma once
// Edit > Preferences: the defaults a new run starts with (preferences.h) and the key map.

#include "editor.h"
#include "input/input.h"
#include "panels.h"

namespace primo::editor {

void draw_preferences_window(Editor& editor, UiState& ui);

// While a command waits for its new key (ui.key_capture), the window hands it every key
// press: the first key that is not a modifier becomes the command's (Esc cancels). Returns
// true when the event was taken.
bool capture_key(const InputEvent& event, Editor& editor, UiState& ui);

}  // namespace primo::editor
