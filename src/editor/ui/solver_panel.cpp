#include "solver_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

namespace primo::editor {
namespace {

// Below this room for a value beside its label, values go under their labels.
constexpr float kLeastValueWidth = 130.0f;

std::string format(const char* fmt, ...) IM_FMTARGS(1);
std::string format(const char* fmt, ...) {
  char text[256];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(text, sizeof text, fmt, args);
  va_end(args);
  return text;
}

void wrapped_disabled(const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

}  // namespace

void solver_figures(const SolverStatus& st, double frame_ms, const Editor::GestureStats& d) {
  struct Row {
    const char* label;
    std::string value;
  };
  std::vector<Row> rows = {
      {"Energy", format("%.6g", st.energy)},
      {"Iterations", format("%d (total %ld)", st.iterations, st.total_iterations)},
      {"Per iteration", format("%.1f ms", 1000.0 * st.seconds_per_iteration)},
      {"Build", format("%.0f ms", 1000.0 * st.build_seconds)},
      {"Frame", format("%.1f ms (%.0f fps)", frame_ms, frame_ms > 0 ? 1000.0 / frame_ms : 0.0)},
  };
  if (d.frames > 0)
    rows.push_back({"Last gesture", format("%s: %d frames, %.1f ms mean, %.1f ms max, mesh %.1f/s",
                                           d.what.c_str(), d.frames, d.total_ms / d.frames,
                                           d.max_ms, d.updates_per_second())});
  float label_width = 0.0f;
  for (const Row& r : rows) label_width = std::max(label_width, ImGui::CalcTextSize(r.label).x);
  label_width += ImGui::GetStyle().ItemSpacing.x;
  const bool stacked = ImGui::GetContentRegionAvail().x - label_width < kLeastValueWidth;
  const float start_x = ImGui::GetCursorPosX();
  for (const Row& r : rows) {
    ImGui::TextDisabled("%s", r.label);
    if (!stacked) ImGui::SameLine(start_x + label_width);
    ImGui::TextWrapped("%s", r.value.c_str());
  }
  if (st.previews)
    wrapped_disabled(st.showing_preview()
                         ? "Showing a preview (coarse levels); full resolution when the hand pauses"
                         : "Full resolution (drags show a preview: a full cycle outlasts 0.1 s)");
}

void solver_section(Editor& e) {
  if (!ImGui::CollapsingHeader("Solver", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const SolverStatus& st = e.solver_status();
  const ImVec4 col = st.phase == SolverPhase::Failed    ? ImVec4(1.0f, 0.45f, 0.4f, 1)
                     : st.phase == SolverPhase::Settled ? ImVec4(0.5f, 0.9f, 0.5f, 1)
                     : st.phase == SolverPhase::Stopped ? ImVec4(1.0f, 0.8f, 0.3f, 1)
                                                        : ImVec4(0.9f, 0.9f, 0.9f, 1);
  ImGui::TextColored(col, "%s", phase_label(st.phase));
  if (st.phase == SolverPhase::Failed) ImGui::TextWrapped("%s", st.error.c_str());
  if (st.phase == SolverPhase::Stopped) {
    ImGui::SameLine();
    if (ImGui::SmallButton("Continue")) e.continue_solving();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Solve on from here until converged");
  } else if (st.busy() && st.phase != SolverPhase::Building) {
    ImGui::SameLine();
    if (ImGui::SmallButton("Stop")) e.stop_solving();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Stop converging and keep the shape shown (Continue solves on)");
  }
  ImGui::ProgressBar(float(st.progress), ImVec2(-1, 0),
                     st.phase == SolverPhase::Building ? "building prisms"
                     : !st.detail.empty()               ? st.detail.c_str()
                     : st.busy()                        ? "converging"
                                                        : "");
  solver_figures(st, e.frame_ms(), e.last_gesture_stats());
}

}  // namespace primo::editor
