#include "status_bar.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace primo::editor {
namespace {

constexpr float kGap = 20.0f;       // between the message and the right side
constexpr float kRightPad = 16.0f;  // after the right side
const char kEllipsis[] = "...";

float text_width(const std::string& text) {
  return ImGui::CalcTextSize(text.data(), text.data() + text.size()).x;
}

bool starts_a_character(const std::string& text, size_t at) {
  return at == text.size() || (static_cast<unsigned char>(text[at]) & 0xC0) != 0x80;
}

}  // namespace

std::string text_that_fits(const std::string& text, float width) {
  if (text_width(text) <= width) return text;
  const float room = width - text_width(kEllipsis);
  if (room < 0.0f) return "";
  // The longest start that fits: widths grow with the length, so a binary search.
  size_t lo = 0, hi = text.size();
  while (lo < hi) {
    const size_t mid = (lo + hi + 1) / 2;
    if (text_width(text.substr(0, mid)) <= room)
      lo = mid;
    else
      hi = mid - 1;
  }
  while (lo > 0 && !starts_a_character(text, lo)) --lo;
  std::string shown = text.substr(0, lo);
  while (!shown.empty() && shown.back() == ' ') shown.pop_back();
  return shown + kEllipsis;
}

StatusBarLayout status_bar_layout(const std::string& left, const std::string& right, float left_x,
                                  float width, float left_reserved) {
  StatusBarLayout layout;
  layout.right_x = std::max(left_x, width - text_width(right) - kRightPad);
  layout.left = text_that_fits(left, layout.right_x - kGap - left_reserved - left_x);
  layout.cut = layout.left != left;
  layout.left_end = left_x + text_width(layout.left);
  return layout;
}

void draw_status_bar(Editor& e, UiState& ui) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0, display.y - ui.status_height));
  ImGui::SetNextWindowSize(ImVec2(display.x, ui.status_height));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 4));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus);
  const SolverStatus& st = e.solver_status();
  char frame[32];
  if (e.idle())
    std::snprintf(frame, sizeof frame, "idle");
  else
    std::snprintf(frame, sizeof frame, "%.1f ms", e.frame_ms());
  // Where drags show previews, which picture is on screen: the preview follows the hand, the
  // full resolution catches up once it pauses.
  const char* picture = !st.previews             ? ""
                        : st.showing_preview() ? " | preview"
                                               : " | full resolution";
  char right[160];
  std::snprintf(right, sizeof right, "%s | %s%s | E %.4g | %s", tool_label(e.tools.tool),
                phase_label(st.phase), picture, st.energy, frame);

  // While a file opens: what and for how long, and a Cancel (Esc too) that keeps the
  // document open before; else the newest message, or the tool and the F1 hint.
  const bool loading = e.file_task_running();
  const Editor::Message* m = loading ? nullptr : e.current_message();
  std::string left = m ? m->text : std::string(tool_label(e.tools.tool)) + " - F1: controls";
  if (loading) {
    char text[256];
    std::snprintf(text, sizeof text, "%s... %.1f s", e.file_task_label().c_str(),
                  e.file_task_seconds());
    left = text;
  }
  const char* cancel = "Cancel";
  const ImGuiStyle& style = ImGui::GetStyle();
  const float button_width = e.opening() ? ImGui::CalcTextSize(cancel).x +
                                               2 * style.FramePadding.x + style.ItemSpacing.x
                                         : 0.0f;
  const StatusBarLayout layout = status_bar_layout(left, right, ImGui::GetCursorPosX(),
                                                   ImGui::GetWindowWidth(), button_width);
  if (m && m->error)
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1), "%s", layout.left.c_str());
  else if (m || loading)
    ImGui::TextUnformatted(layout.left.c_str());
  else
    ImGui::TextDisabled("%s", layout.left.c_str());
  if (layout.cut && ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(std::min(display.x * 0.8f, 720.0f));
    ImGui::TextUnformatted(left.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
  if (e.opening()) {
    ImGui::SameLine();
    if (ImGui::SmallButton(cancel)) e.cancel_open();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Stop opening (Esc): what is open now stays as it is");
  }
  ImGui::SameLine(layout.right_x);
  ImGui::TextDisabled("%s", right);
  ImGui::End();
  ImGui::PopStyleVar();
}

}  // namespace primo::editor
