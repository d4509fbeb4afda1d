#pragma once
// Input events as the editor consumes them. GLFW callbacks and the script player (--script)
// both produce these and push them into the same queue, so a scripted drag runs exactly the
// code a real one does. Codes and flags are GLFW's (keys, buttons, actions, modifier bits).

#ifndef GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_NONE
#endif
#include <GLFW/glfw3.h>

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

// Modifier bit of a modifier key (GLFW_KEY_LEFT_SHIFT -> GLFW_MOD_SHIFT), 0 for other keys.
int modifier_bit(int key);

// "A", "Numpad 1", "Delete", "[": a key's name as menus print it; parse_key_combo reads it.
std::string key_label(int key);

// "ctrl+shift+z", "kp_1", "Numpad 1", "escape", "f12", "a" -> key code and modifier bits. Throws
// std::invalid_argument for an unknown name.
void parse_key_combo(const std::string& text, int& key, int& mods);

}  // namespace primo::editor
