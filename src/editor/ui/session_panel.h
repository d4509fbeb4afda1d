#pragma once
// The "Session" section of the properties panel: record / stop / save a posing session, open
// one and play it back with play / pause and a timeline slider, export it as an animated glTF
// (docs/sessions.md).

#include "editor.h"
#include "panels.h"

namespace primo::editor {

void session_section(Editor& editor, UiState& ui);

}  // namespace primo::editor
