#include "input.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace primo::editor {

InputEvent InputEvent::cursor(double x, double y) {
  InputEvent e;
  e.type = Type::CursorMove;
  e.x = x;
  e.y = y;
  return e;
}

InputEvent InputEvent::mouse(int button, int action, int mods) {
  InputEvent e;
  e.type = Type::MouseButton;
  e.button = button;
  e.action = action;
  e.mods = mods;
  return e;
}

InputEvent InputEvent::scroll(double dx, double dy) {
  InputEvent e;
  e.type = Type::Scroll;
  e.x = dx;
  e.y = dy;
  return e;
}

InputEvent InputEvent::key_event(int key, int action, int mods) {
  InputEvent e;
  e.type = Type::Key;
  e.key = key;
  e.action = action;
  e.mods = mods;
  return e;
}

InputEvent InputEvent::character(unsigned codepoint) {
  InputEvent e;
  e.type = Type::Char;
  e.codepoint = codepoint;
  return e;
}

InputEvent InputEvent::drop(std::vector<std::string> paths) {
  InputEvent e;
  e.type = Type::Drop;
  e.paths = std::move(paths);
  return e;
}

std::size_t one_ui_frame_of_input(const InputQueue& queue) {
  using Type = InputEvent::Type;
  std::optional<Type> changed;  // the kind of change this frame has taken
  std::size_t n = 0;
  for (const InputEvent& e : queue) {
    switch (e.type) {
      case Type::CursorMove:
        if (changed == Type::MouseButton || changed == Type::Scroll) return n;
        break;
      case Type::Drop: break;
      case Type::Key:
        if (e.action == GLFW_REPEAT) break;
        [[fallthrough]];
      case Type::MouseButton:
      case Type::Scroll:
        if (changed) return n;
        changed = e.type;
        break;
      case Type::Char:
        if (changed && changed != Type::Char) return n;
        changed = Type::Char;
        break;
    }
    ++n;
  }
  return n;
}

int modifier_bit(int key) {
  switch (key) {
    case GLFW_KEY_LEFT_SHIFT: case GLFW_KEY_RIGHT_SHIFT: return GLFW_MOD_SHIFT;
    case GLFW_KEY_LEFT_CONTROL: case GLFW_KEY_RIGHT_CONTROL: return GLFW_MOD_CONTROL;
    case GLFW_KEY_LEFT_ALT: case GLFW_KEY_RIGHT_ALT: return GLFW_MOD_ALT;
    case GLFW_KEY_LEFT_SUPER: case GLFW_KEY_RIGHT_SUPER: return GLFW_MOD_SUPER;
    default: return 0;
  }
}

namespace {

const std::map<std::string, int>& named_keys() {
  static const std::map<std::string, int> keys = {
      {"escape", GLFW_KEY_ESCAPE}, {"esc", GLFW_KEY_ESCAPE}, {"enter", GLFW_KEY_ENTER},
      {"return", GLFW_KEY_ENTER}, {"tab", GLFW_KEY_TAB}, {"space", GLFW_KEY_SPACE},
      {"backspace", GLFW_KEY_BACKSPACE}, {"delete", GLFW_KEY_DELETE}, {"home", GLFW_KEY_HOME},
      {"end", GLFW_KEY_END}, {"left", GLFW_KEY_LEFT}, {"right", GLFW_KEY_RIGHT},
      {"up", GLFW_KEY_UP}, {"down", GLFW_KEY_DOWN}, {"minus", GLFW_KEY_MINUS},
      {"equal", GLFW_KEY_EQUAL}, {"[", GLFW_KEY_LEFT_BRACKET}, {"]", GLFW_KEY_RIGHT_BRACKET},
      {"period", GLFW_KEY_PERIOD}, {"kp_add", GLFW_KEY_KP_ADD},
      {"kp_subtract", GLFW_KEY_KP_SUBTRACT}, {"kp_decimal", GLFW_KEY_KP_DECIMAL},
      {"shift", GLFW_KEY_LEFT_SHIFT}, {"ctrl", GLFW_KEY_LEFT_CONTROL},
      {"alt", GLFW_KEY_LEFT_ALT}, {"super", GLFW_KEY_LEFT_SUPER},
      // What key_label prints, so that labels read back.
      {"=", GLFW_KEY_EQUAL}, {"-", GLFW_KEY_MINUS},
      {",", GLFW_KEY_COMMA}, {".", GLFW_KEY_PERIOD}, {"/", GLFW_KEY_SLASH},
      {";", GLFW_KEY_SEMICOLON}, {"'", GLFW_KEY_APOSTROPHE}, {"`", GLFW_KEY_GRAVE_ACCENT},
      {"\\", GLFW_KEY_BACKSLASH}, {"insert", GLFW_KEY_INSERT}, {"page up", GLFW_KEY_PAGE_UP},
      {"page down", GLFW_KEY_PAGE_DOWN}, {"numpad .", GLFW_KEY_KP_DECIMAL},
      {"numpad plus", GLFW_KEY_KP_ADD}, {"numpad minus", GLFW_KEY_KP_SUBTRACT},
      {"numpad *", GLFW_KEY_KP_MULTIPLY}, {"numpad /", GLFW_KEY_KP_DIVIDE},
      {"numpad enter", GLFW_KEY_KP_ENTER}};
  return keys;
}

int key_from_name(const std::string& name) {
  const auto& keys = named_keys();
  if (auto it = keys.find(name); it != keys.end()) return it->second;
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0])))
    return GLFW_KEY_A + (std::tolower(static_cast<unsigned char>(name[0])) - 'a');
  if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0])))
    return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() == 4 && name.rfind("kp_", 0) == 0 && std::isdigit(static_cast<unsigned char>(name[3])))
    return GLFW_KEY_KP_0 + (name[3] - '0');
  if (name.size() == 8 && name.rfind("numpad ", 0) == 0 &&
      std::isdigit(static_cast<unsigned char>(name[7])))
    return GLFW_KEY_KP_0 + (name[7] - '0');
  if (name.rfind("key ", 0) == 0) {  // key_label of a key without a name
    const std::string code = name.substr(4);
    if (!code.empty() && code.size() < 5 &&
        std::all_of(code.begin(), code.end(), [](unsigned char c) { return std::isdigit(c); }))
      return std::stoi(code);
  }
  if (name.size() >= 2 && name[0] == 'f') {
    int n = 0;
    try {
      n = std::stoi(name.substr(1));
    } catch (const std::exception&) {
      n = 0;
    }
    if (n >= 1 && n <= 25) return GLFW_KEY_F1 + (n - 1);
  }
  throw std::invalid_argument("unknown key '" + name + "'");
}

}  // namespace

std::string key_label(int key) {
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, char('A' + (key - GLFW_KEY_A)));
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return std::string(1, char('0' + (key - GLFW_KEY_0)));
  if (key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9) return "Numpad " + std::to_string(key - GLFW_KEY_KP_0);
  if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F25) return "F" + std::to_string(key - GLFW_KEY_F1 + 1);
  static const std::map<int, std::string> labels = {
      {GLFW_KEY_ESCAPE, "Esc"}, {GLFW_KEY_ENTER, "Enter"}, {GLFW_KEY_TAB, "Tab"},
      {GLFW_KEY_SPACE, "Space"}, {GLFW_KEY_BACKSPACE, "Backspace"}, {GLFW_KEY_DELETE, "Delete"},
      {GLFW_KEY_INSERT, "Insert"}, {GLFW_KEY_HOME, "Home"}, {GLFW_KEY_END, "End"},
      {GLFW_KEY_PAGE_UP, "Page Up"}, {GLFW_KEY_PAGE_DOWN, "Page Down"}, {GLFW_KEY_LEFT, "Left"},
      {GLFW_KEY_RIGHT, "Right"}, {GLFW_KEY_UP, "Up"}, {GLFW_KEY_DOWN, "Down"},
      {GLFW_KEY_EQUAL, "="}, {GLFW_KEY_MINUS, "-"}, {GLFW_KEY_LEFT_BRACKET, "["},
      {GLFW_KEY_RIGHT_BRACKET, "]"}, {GLFW_KEY_COMMA, ","}, {GLFW_KEY_PERIOD, "."},
      {GLFW_KEY_SLASH, "/"}, {GLFW_KEY_SEMICOLON, ";"}, {GLFW_KEY_APOSTROPHE, "'"},
      {GLFW_KEY_GRAVE_ACCENT, "`"}, {GLFW_KEY_BACKSLASH, "\\"}, {GLFW_KEY_KP_DECIMAL, "Numpad ."},
      {GLFW_KEY_KP_ADD, "Numpad Plus"}, {GLFW_KEY_KP_SUBTRACT, "Numpad Minus"},
      {GLFW_KEY_KP_MULTIPLY, "Numpad *"}, {GLFW_KEY_KP_DIVIDE, "Numpad /"},
      {GLFW_KEY_KP_ENTER, "Numpad Enter"}, {GLFW_KEY_LEFT_SHIFT, "Shift"},
      {GLFW_KEY_RIGHT_SHIFT, "Shift"}, {GLFW_KEY_LEFT_CONTROL, "Ctrl"},
      {GLFW_KEY_RIGHT_CONTROL, "Ctrl"}, {GLFW_KEY_LEFT_ALT, "Alt"}, {GLFW_KEY_RIGHT_ALT, "Alt"},
      {GLFW_KEY_LEFT_SUPER, "Super"}, {GLFW_KEY_RIGHT_SUPER, "Super"}};
  if (const auto it = labels.find(key); it != labels.end()) return it->second;
  return "Key " + std::to_string(key);
}

void parse_key_combo(const std::string& text, int& key, int& mods) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  mods = 0;
  key = 0;
  std::stringstream parts(lower);
  std::string part;
  std::vector<std::string> names;
  while (std::getline(parts, part, '+')) names.push_back(part);
  if (names.empty() || names.back().empty() || lower.back() == '+') throw std::invalid_argument("empty key '" + text + "'");
  for (size_t i = 0; i + 1 < names.size(); ++i) {
    const int bit = modifier_bit(key_from_name(names[i]));
    if (bit == 0) throw std::invalid_argument("'" + names[i] + "' is not a modifier in '" + text + "'");
    mods |= bit;
  }
  key = key_from_name(names.back());
}

}  // namespace primo::editor
