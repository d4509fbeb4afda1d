#pragma once
// The main menu bar (File, Edit, View, Help) and the file dialogs the menus and the window's
// shortcuts open (panels.h declares ask_open and the other file actions).

#include "editor.h"
#include "panels.h"

namespace primo::editor {

void draw_menu_bar(Editor& editor, UiState& ui);
// The dialog opened by an ask_* action, and what its answer does.
void draw_file_dialog(Editor& editor, UiState& ui);

}  // namespace primo::editor
