#pragma once
// Small Dear ImGui pieces shared by the panels and windows.

namespace primo::editor {

// A dimmed "(?)" after the last widget that shows `text` as a wrapped tooltip.
void help_marker(const char* text);

}  // namespace primo::editor
