#pragma once
// Input events as the editor consumes them. GLFW callbacks and the script player (--script)
// both produce these and push them into the same queue, so a scripted drag runs exactly the
// code a real one does. Codes and flags are GLFW's (keys, buttons, actions, modifier bits).

#ifndef GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_NONE
#endif
#include <GLFW/glfw3.h>

#include <cstddef>
#include <deque>
#include <string>
#include <vector>

namespace primo::editor {

struct InputEvent {
  enum class Type { CursorMove, MouseButton, Scroll, Key, Char, Drop };
  Type type = Type::CursorMove;
  double x = 0.0, y = 0.0;  // CursorMove: window coordinates; Scroll: offsets
  int button = 0;           // MouseButton: GLFW_MOUSE_BUTTON_*
  int key = 0;              // Key: GLFW_KEY_*
  int scancode = 0;
  int action = 0;           // GLFW_PRESS, GLFW_RELEASE, GLFW_REPEAT
  int mods = 0;             // GLFW_MOD_* bits
  unsigned codepoint = 0;   // Char
  std::vector<std::string> paths;  // Drop

  static InputEvent cursor(double x, double y);
  static InputEvent mouse(int button, int action, int mods);
  static InputEvent scroll(double dx, double dy);
  static InputEvent key_event(int key, int action, int mods);
  static InputEvent character(unsigned codepoint);
  static InputEvent drop(std::vector<std::string> paths);
};

using InputQueue = std::deque<InputEvent>;

// How many of the queue's first events one frame of the window's panels can take (at least
// one, unless the queue is empty). Dear ImGui as Debian ships it (1.86) has no input queue: it
// reads which keys and buttons are down, the pointer and the typed characters once per frame,
// so a key pressed and released within one frame would never be down for it (a quick Enter
// would leave a field in edit mode), and an arrow key or Backspace would act after characters
// typed behind it.
// A frame therefore takes at most one change of a key or button, one run of characters or one
// wheel step; pointer moves, key repeats (Dear ImGui repeats by itself) and dropped files go
// with any frame, but a move after a button change or a wheel step waits for the next frame
// (the click or the scroll happened where the pointer was). The window runs as many panel
// frames as its queue needs (ui/ui_input.h); the editor gets the same events in the same order.
std::size_t one_ui_frame_of_input(const InputQueue& queue);

// Modifier bit of a modifier key (GLFW_KEY_LEFT_SHIFT -> GLFW_MOD_SHIFT), 0 for other keys.
int modifier_bit(int key);

// "A", "Numpad 1", "Delete", "[": a key's name as menus print it; parse_key_combo reads it.
std::string key_label(int key);

// "ctrl+shift+z", "kp_1", "Numpad 1", "escape", "f12", "a" -> key code and modifier bits. Throws
// std::invalid_argument for an unknown name.
void parse_key_combo(const std::string& text, int& key, int& mods);

}  // namespace primo::editor
