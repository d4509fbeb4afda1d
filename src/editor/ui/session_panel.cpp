#include "session_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <filesystem>
#include <string>

namespace primo::editor {

void session_section(Editor& e, UiState& ui) {
  if (!ImGui::CollapsingHeader("Session")) return;
  SessionControl& s = e.sessions;
  // The path field proposes a file per mesh, again whenever another mesh is opened.
  static std::string path, proposed_for;
  const Document* doc = e.document();
  if (doc && doc->mesh_path != proposed_for) {
    proposed_for = doc->mesh_path;
    path = default_session_path(doc->mesh_path);
  }

  if (!s.recording()) {
    if (ImGui::Button("Record")) s.start_recording(e);
  } else {
    if (ImGui::Button("Stop")) s.stop_recording(e);
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(0.95f, 0.3f, 0.3f, 1.0f), "REC %zu events",
                       s.recording_session().events.size());
  }
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##session_path", &path);
  ImGui::BeginDisabled(!s.has_recording());
  if (ImGui::Button("Save recording")) s.save(e, path);
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Open for playback")) s.open_playback(e, path);
  ImGui::BeginDisabled(!s.has_session() || s.exporting());
  if (ImGui::Button(s.exporting() ? "Exporting animation..." : "Export animation (.glb)..."))
    ask_save_session_animation(e, ui);
  ImGui::EndDisabled();

  if (!s.has_playback()) return;
  if (s.playing()) {
    if (ImGui::Button("Pause")) s.pause(e);
  } else if (ImGui::Button("Play")) {
    s.play(e);
  }
  ImGui::SameLine();
  float t = float(s.time());
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderFloat("##timeline", &t, 0.0f, float(s.duration()), "%.2f s")) {
    if (s.playing()) s.pause(e);
    s.seek(e, double(t));
  }
  ImGui::TextDisabled("%zu events, %d frames", s.playback_session().events.size(),
                      s.playback_session().frames());
}

}  // namespace primo::editor
