#pragma once
// Input events into Dear ImGui and the editor, one panel frame at a time.
//
// Dear ImGui 1.86 (Debian's) reads keys, buttons and the pointer as they are when a frame
// starts. GLFW's callbacks append every event to the window's queue instead; each panel frame
// takes the events up to the next change Dear ImGui could not see in order
// (one_ui_frame_of_input in input.h), feeds them to Dear ImGui here, and routes each one, in
// order, to whoever takes it at that moment (route_input). A displayed frame runs as many panel
// frames as its queue needs and draws only the last, so a quick key tap at 4 frames a second
// is still a press, and what follows it waits for nothing.

#include <imgui.h>
#include <imgui_internal.h>

#include <glm/vec2.hpp>

#include "editor.h"
#include "input/input.h"
#include "panels.h"
#include "preferences_window.h"

namespace primo::editor {

class UiInput {
 public:
  // Keys, characters and the wheel of one frame's events into Dear ImGui's io; the pointer and
  // the buttons are kept for apply_pointer.
  void feed(const InputQueue& batch) {
    ImGuiIO& io = ImGui::GetIO();
    for (const InputEvent& e : batch) {
      switch (e.type) {
        case InputEvent::Type::Key:
          if (e.key < 0 || e.key >= IM_ARRAYSIZE(io.KeysDown) || e.action == GLFW_REPEAT) break;
          io.KeysDown[e.key] = e.action == GLFW_PRESS;
          // From the keys rather than the event's modifier bits, as the GLFW backend does:
          // those are not reliable across systems.
          io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
          io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT];
          io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT];
          io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER];
          break;
        case InputEvent::Type::Char: io.AddInputCharacter(e.codepoint); break;
        case InputEvent::Type::Scroll:
          io.MouseWheelH += float(e.x);
          io.MouseWheel += float(e.y);
          break;
        case InputEvent::Type::MouseButton:
          if (e.button >= 0 && e.button < kButtons) buttons_[e.button] = e.action == GLFW_PRESS;
          break;
        case InputEvent::Type::CursorMove: cursor_ = {e.x, e.y}; break;
        case InputEvent::Type::Drop: break;
      }
    }
  }
  // The pointer and buttons into io, after the platform backend's NewFrame (which reads them
  // from GLFW as they are now, past events still queued) and before ImGui::NewFrame.
  void apply_pointer() const {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(float(cursor_.x), float(cursor_.y));
    for (int b = 0; b < kButtons; ++b) io.MouseDown[b] = buttons_[b];
  }
  // Where the pointer is as of the events fed so far (window coordinates).
  glm::dvec2 cursor() const { return cursor_; }

 private:
  static constexpr int kButtons = 3;
  glm::dvec2 cursor_{-1.0};
  bool buttons_[kButtons] = {false, false, false};
};

// After ImGui::NewFrame: each event of the frame's batch, in order, to whoever takes it now:
// a command of Preferences > Keys waiting for its key, an open menu (or other non-modal popup:
// it owns the keyboard, Esc closes it and no shortcut reaches the editor behind it), the
// window's shortcuts unless a panel has the keyboard, else the editor.
inline void route_input(const InputQueue& batch, Editor& editor, UiState& ui) {
  const ImGuiIO& io = ImGui::GetIO();
  const bool menu_open =
      ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel) &&
      !ImGui::GetTopMostPopupModal();
  for (const InputEvent& e : batch) {
    if (capture_key(e, editor, ui)) continue;
    if (menu_open && (e.type == InputEvent::Type::Key || e.type == InputEvent::Type::Char)) {
      if (e.type == InputEvent::Type::Key && e.key == GLFW_KEY_ESCAPE && e.action == GLFW_PRESS)
        ImGui::ClosePopupToLevel(0, true);
      continue;
    }
    if (!io.WantCaptureKeyboard && handle_app_shortcut(e, editor, ui)) continue;
    editor.handle_event(e, io.WantCaptureMouse, io.WantCaptureKeyboard);
  }
}

}  // namespace primo::editor
