#pragma once
// Help > Controls (F1): every mouse gesture, and every keyboard command with the keys the
// user's key map gives it now, so a rebound key shows as it works.

#include <string>
#include <vector>

#include "editor.h"
#include "panels.h"

namespace primo::editor {

struct ControlsRow {
  std::string keys, what;
};
struct ControlsSection {
  std::string title;
  std::vector<ControlsRow> rows;
};
// What the window lists: the mouse, then the key map's sections in its order (commands without
// a key too, as "(no key)").
std::vector<ControlsSection> controls_sections(const KeyMap& keys);

void draw_controls_window(const Editor& editor, UiState& ui);

}  // namespace primo::editor
