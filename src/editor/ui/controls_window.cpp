#include "controls_window.h"

#include <imgui.h>

#include <string>
#include <vector>

namespace primo::editor {
namespace {

void table(const char* id, const std::vector<ControlsRow>& rows) {
  if (!ImGui::BeginTable(id, 2, ImGuiTableFlags_RowBg)) return;
  ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed, 190);
  for (const ControlsRow& r : rows) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextWrapped("%s", r.keys.c_str());  // long key lists wrap instead of being cut off
    ImGui::TableNextColumn();
    ImGui::TextWrapped("%s", r.what.c_str());
  }
  ImGui::EndTable();
}

}  // namespace

std::vector<ControlsSection> controls_sections(const KeyMap& keys) {
  std::vector<ControlsSection> sections = {
      {"Mouse",
       {{"Middle drag / Right drag", "orbit"},
        {"Shift + middle or right drag", "pan"},
        {"Wheel, Ctrl + middle drag", "zoom (towards the cursor)"},
        {"Alt + left / middle / right", "orbit / pan / zoom (Maya style)"},
        {"Left drag", "the tool: select, drag a handle, use the gizmo, paint"},
        {"Shift / Ctrl + select", "add to / remove from the selection"},
        {"Ctrl + wheel", "brush radius"},
        {"Alt + click / Shift + Alt + click", "the loop of quads across an edge / add it"},
        {"Alt + wheel", "the active handle's falloff radius"},
        {"Ctrl + Shift + right click", "the active handle's pivot to the surface there"},
        {"Right click", "cancel the current drag or stroke"}}}};
  for (const ActionInfo& a : all_actions()) {
    if (sections.back().title != a.section) sections.push_back({a.section, {}});
    const std::string label = keys.label(a.action);
    sections.back().rows.push_back({label.empty() ? "(no key)" : label, a.label});
  }
  return sections;
}

void draw_controls_window(const Editor& e, UiState& ui) {
  if (!ui.show_help) return;
  ImGui::SetNextWindowSize(ImVec2(560, 600), ImGuiCond_FirstUseEver);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_FirstUseEver,
                          ImVec2(0.5f, 0.5f));
  if (!ImGui::Begin("Controls", &ui.show_help)) return ImGui::End();
  for (const ControlsSection& section : controls_sections(e.key_map())) {
    ImGui::TextDisabled("%s", section.title.c_str());
    table(section.title.c_str(), section.rows);
  }
  ImGui::TextDisabled("Keys are changed in Edit > Preferences > Keys.");
  ImGui::End();
}

}  // namespace primo::editor
