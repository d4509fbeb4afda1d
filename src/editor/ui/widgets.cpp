#include "widgets.h"

#include <imgui.h>

#include <string>

#include "view/shown_value.h"

namespace primo::editor {

void help_marker(const char* text) {
  ImGui::SameLine();
  ImGui::TextDisabled("(?)");
  if (ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
    ImGui::TextUnformatted(text);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

bool drag_vec3(const char* label, Vec3& v, float speed, int decimals, const double* lo,
               const double* hi, ImGuiSliderFlags flags) {
  const Vec3 shown(shown_value(v.x(), decimals), shown_value(v.y(), decimals),
                   shown_value(v.z(), decimals));
  Vec3 edited = shown;
  const std::string format = "%." + std::to_string(decimals) + "f";
  if (!ImGui::DragScalarN(label, ImGuiDataType_Double, edited.data(), 3, speed, lo, hi,
                          format.c_str(), flags))
    return false;
  bool changed = false;
  for (int k = 0; k < 3; ++k)
    if (edited[k] != shown[k]) v[k] = edited[k], changed = true;
  return changed;
}

}  // namespace primo::editor
