#include "preferences_window.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "widgets.h"

namespace primo::editor {
namespace {

bool contains_ignoring_case(const std::string& text, const std::string& part) {
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
  };
  return lower(text).find(lower(part)) != std::string::npos;
}

void display_and_brushes(Preferences& p) {
  ImGui::TextDisabled("Display");
  ImGui::Checkbox("Smooth shading", &p.smooth);
  ImGui::SameLine();
  ImGui::Checkbox("Wireframe", &p.wireframe);
  ImGui::Checkbox("Prisms", &p.prisms);
  ImGui::SameLine();
  ImGui::Checkbox("Energy heat map", &p.heat_map);
  ImGui::SameLine();
  ImGui::Checkbox("Paint colours", &p.paint_overlay);
  ImGui::Checkbox("Ground grid", &p.grid);
  ImGui::Separator();
  ImGui::TextDisabled("Brushes");
  float radius = float(p.brush_radius), strength = float(p.paint_strength);
  if (ImGui::SliderFloat("Radius", &radius, 2.0f, 200.0f, "%.0f px", ImGuiSliderFlags_Logarithmic))
    p.brush_radius = radius;
  if (ImGui::SliderFloat("Paint strength", &strength, 0.05f, 1.0f, "%.2f")) p.paint_strength = strength;
  int falloff = int(p.paint_falloff);
  const char* falloffs[] = {"Constant", "Linear", "Smooth"};
  if (ImGui::Combo("Paint falloff", &falloff, falloffs, 3)) p.paint_falloff = Falloff(falloff);
}

void work_and_solver(Preferences& p) {
  ImGui::TextDisabled("Work");
  float minutes = float(p.autosave_minutes);
  if (ImGui::SliderFloat("Autosave every", &minutes, 0.0f, 30.0f, minutes == 0 ? "never" : "%.1f min"))
    p.autosave_minutes = minutes;
  ImGui::Separator();
  ImGui::TextDisabled("Solver (meshes opened without a scenario)");
  double lo = 1e-12, hi = 1e-3;
  ImGui::SliderScalar("Tolerance", ImGuiDataType_Double, &p.tolerance, &lo, &hi, "%.0e",
                      ImGuiSliderFlags_Logarithmic);
  help_marker("The relative energy change at which the solver has settled (a scenario keeps "
              "its own solver.tolerance).");
  int limit = p.max_iterations;
  if (ImGui::SliderInt("Batch iteration limit", &limit, 10, 10000, "%d", ImGuiSliderFlags_Logarithmic))
    p.max_iterations = std::clamp(limit, 1, 100000);
  help_marker("solver.max_iterations of the scenarios you save: where primo deform and primo "
              "replay stop if they have not converged. The editor itself settles until "
              "converged.");
  float settle = float(p.settle_seconds);
  if (ImGui::SliderFloat("Settle at most", &settle, 0.0f, 600.0f, settle == 0 ? "until converged" : "%.0f s",
                         ImGuiSliderFlags_Logarithmic))
    p.settle_seconds = std::clamp(double(settle), 0.0, 3600.0);
  help_marker("How long the editor keeps settling after an edit before it stops by itself "
              "(Continue in the Solver panel solves on). For very large meshes on slow "
              "machines; 0 settles until converged.");
}

void keys_section(Editor& e, UiState& ui) {
  static std::string filter;  // what the user typed: kept while the window is open
  KeyMap& keys = e.preferences().keys;
  ImGui::TextDisabled("Keys (changes take effect at once)");
  ImGui::SetNextItemWidth(200);
  ImGui::InputTextWithHint("##key filter", "Filter commands or keys", &filter);
  ImGui::SameLine();
  if (ImGui::Button("Reset all keys")) {
    keys.reset_all();
    ui.key_capture.reset();
  }
  if (ui.key_capture)
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "Press the new key for '%s' (Esc cancels)",
                       action_info(ui.key_capture->action).label);
  // The list takes the height left above the buttons, and scrolls.
  const float below = ImGui::GetFrameHeightWithSpacing() + ImGui::GetStyle().ItemSpacing.y * 2;
  const float height = std::max(120.0f, ImGui::GetContentRegionAvail().y - below);
  if (!ImGui::BeginTable("keys", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY,
                         ImVec2(0, height)))
    return;
  ImGui::TableSetupColumn("command", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableSetupColumn("keys", ImGuiTableColumnFlags_WidthFixed, 150);
  ImGui::TableSetupColumn("change", ImGuiTableColumnFlags_WidthFixed, 170);
  for (const ActionInfo& a : all_actions()) {
    const std::string label = keys.label(a.action);
    if (!filter.empty() && !contains_ignoring_case(a.label, filter) &&
        !contains_ignoring_case(label, filter) && !contains_ignoring_case(a.id, filter))
      continue;
    ImGui::PushID(a.id);
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextWrapped("%s", a.label);
    ImGui::TableNextColumn();
    if (keys.is_default(a.action))
      ImGui::TextWrapped("%s", label.empty() ? "-" : label.c_str());
    else
      ImGui::TextColored(ImVec4(0.5f, 0.8f, 1.0f, 1.0f), "%s", label.empty() ? "(none)" : label.c_str());
    ImGui::TableNextColumn();
    if (ImGui::SmallButton("Set")) ui.key_capture = UiState::KeyCapture{a.action, true};
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Replace its keys with the next key you press");
    ImGui::SameLine();
    if (ImGui::SmallButton("+")) ui.key_capture = UiState::KeyCapture{a.action, false};
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Add the next key you press");
    ImGui::SameLine();
    if (ImGui::SmallButton("x")) keys.unbind(a.action);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("No key");
    ImGui::SameLine();
    ImGui::BeginDisabled(keys.is_default(a.action));
    if (ImGui::SmallButton("Reset")) keys.reset(a.action);
    ImGui::EndDisabled();
    ImGui::PopID();
  }
  ImGui::EndTable();
}

}  // namespace

void draw_preferences_window(Editor& e, UiState& ui) {
  if (!ui.show_preferences) {
    ui.key_capture.reset();
    return;
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(60, 40), ImGuiCond_Appearing);
  ImGui::SetNextWindowSize(ImVec2(580, std::min(760.0f, display.y - 60)), ImGuiCond_Appearing);
  if (!ImGui::Begin("Preferences", &ui.show_preferences, ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    return;
  }
  Preferences& p = e.preferences();
  display_and_brushes(p);
  ImGui::Separator();
  work_and_solver(p);
  ImGui::Separator();
  keys_section(e, ui);
  ImGui::Separator();
  if (ImGui::Button("Use now")) e.apply_preferences();
  ImGui::SameLine();
  if (ImGui::Button("Save as defaults")) {
    e.apply_preferences();
    if (save_preferences(p))
      e.info("Saved the preferences to " + preferences_path());
    else
      e.error("Could not write " + preferences_path());
  }
  ImGui::End();
}

bool capture_key(const InputEvent& ev, Editor& e, UiState& ui) {
  if (!ui.key_capture || ev.type != InputEvent::Type::Key) return false;
  if (ev.action != GLFW_PRESS || modifier_bit(ev.key)) return true;  // wait for the key itself
  const UiState::KeyCapture capture = *ui.key_capture;
  ui.key_capture.reset();
  if (ev.key == GLFW_KEY_ESCAPE) return true;
  const KeyChord chord{ev.key, ev.mods};
  if (is_reserved(chord)) {
    e.error(chord_label(chord) + " cannot be bound: it always cancels");
    return true;
  }
  KeyMap& keys = e.preferences().keys;
  const std::optional<Action> taken = keys.bind(capture.action, chord, capture.replace);
  const std::string label = chord_label(keys.chords(capture.action).back());
  std::string text = label + " now does '" + action_info(capture.action).label + "'";
  if (taken)
    text += "; it was '" + std::string(action_info(*taken).label) + "'" +
            (keys.chords(*taken).empty() ? ", which has no key now" : "");
  e.info(text);
  return true;
}

}  // namespace primo::editor
