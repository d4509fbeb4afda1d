#pragma once
// Small Dear ImGui pieces shared by the panels and windows.

#include <imgui.h>

#include "primo/util/types.h"

namespace primo::editor {

// A dimmed "(?)" after the last widget that shows `text` as a wrapped tooltip.
void help_marker(const char* text);

// Three doubles dragged or typed, printed with `decimals` places ("%.4f" for 4) and values that
// would print as "-0.0000" shown as 0 (shown_value.h). Only the components the user changed
// are written back, so a tiny value nobody touched stays as it was. True when one changed.
bool drag_vec3(const char* label, Vec3& v, float speed, int decimals, const double* lo = nullptr,
               const double* hi = nullptr, ImGuiSliderFlags flags = 0);

}  // namespace primo::editor
