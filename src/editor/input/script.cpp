#include "script.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "primo/util/error.h"

namespace primo::editor {
namespace {

// A word of the script for a message: printable ASCII, anything else as \xNN.
std::string shown(const std::string& s) {
  std::string out = "'";
  for (unsigned char c : s.substr(0, 40)) {
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\x%02X", c);
      out += buffer;
    }
  }
  return out + (s.size() > 40 ? "...'" : "'");
}

int parse_button(const std::string& name) {
  if (name == "left") return GLFW_MOUSE_BUTTON_LEFT;
  if (name == "right") return GLFW_MOUSE_BUTTON_RIGHT;
  if (name == "middle") return GLFW_MOUSE_BUTTON_MIDDLE;
  throw std::invalid_argument("unknown button " + shown(name) + " (left, right or middle)");
}

double parse_number(const std::string& s) {
  size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size()) throw std::invalid_argument("expected a number, got " + shown(s));
  // stod reads "nan" and "inf": a wait or a move that never ends.
  if (!std::isfinite(v)) throw std::invalid_argument("expected a finite number, got " + shown(s));
  return v;
}

// A duration: wait, wait-settled, wait-file and move ... over. At most a day, so that a script
// always ends.
double parse_seconds(const std::string& s) {
  const double v = parse_number(s);
  if (v < 0.0 || v > 86400.0)
    throw std::invalid_argument("expected seconds from 0 to 86400, got " + shown(s));
  return v;
}

std::string rest_of(std::istringstream& in) {
  std::string rest;
  std::getline(in, rest);
  const size_t b = rest.find_first_not_of(" \t");
  return b == std::string::npos ? "" : rest.substr(b);
}

ScriptCommand parse_line(const std::string& line) {
  std::istringstream in(line);
  std::string word;
  in >> word;
  ScriptCommand c;
  std::vector<std::string> args;
  auto all_args = [&] {  // "quoted words" may hold spaces: "@Handle 1"
    std::string a;
    while (in >> std::quoted(a)) args.push_back(a);
  };
  using K = ScriptCommand::Kind;
  if (word == "wait") {
    all_args();
    if (args.size() != 1) throw std::invalid_argument("wait takes SECONDS");
    c.kind = K::Wait;
    c.seconds = parse_seconds(args[0]);
  } else if (word == "wait-settled") {
    all_args();
    if (args.size() > 1) throw std::invalid_argument("wait-settled takes at most a TIMEOUT");
    c.kind = K::WaitSettled;
    c.seconds = args.empty() ? 60.0 : parse_seconds(args[0]);
  } else if (word == "move" || word == "report") {
    all_args();
    c.kind = word == "move" ? K::Move : K::Report;
    if (c.kind == K::Move && args.size() >= 2 && args[args.size() - 2] == "over") {
      c.seconds = parse_seconds(args.back());
      args.resize(args.size() - 2);
    }
    size_t i = 0;
    if (!args.empty() && args[0][0] == '@') {
      c.anchor = ScriptCommand::Anchor::Handle;
      c.handle = args[0].substr(1);
      if (c.handle.empty()) throw std::invalid_argument("'@' needs a handle name");
      i = 1;
    } else if (!args.empty() && args[0] == "center") {
      c.anchor = ScriptCommand::Anchor::Center;
      i = 1;
    }
    const size_t numbers = args.size() - i;
    if (c.anchor == ScriptCommand::Anchor::None ? numbers != 2 : (numbers != 0 && numbers != 2))
      throw std::invalid_argument(word + " takes X Y, @HANDLE [DX DY] or center [DX DY]");
    if (numbers == 2) {
      c.x = parse_number(args[i]);
      c.y = parse_number(args[i + 1]);
    }
  } else if (word == "press" || word == "release" || word == "click") {
    all_args();
    if (args.size() != 1) throw std::invalid_argument(word + " takes BUTTON");
    c.kind = word == "press" ? K::Press : word == "release" ? K::Release : K::Click;
    c.button = parse_button(args[0]);
  } else if (word == "scroll") {
    all_args();
    if (args.size() != 1) throw std::invalid_argument("scroll takes STEPS");
    c.kind = K::Scroll;
    c.steps = parse_number(args[0]);
  } else if (word == "key" || word == "hold" || word == "unhold") {
    all_args();
    if (args.size() != 1) throw std::invalid_argument(word + " takes one key");
    c.kind = word == "key" ? K::Key : word == "hold" ? K::Hold : K::Unhold;
    parse_key_combo(args[0], c.key, c.mods);
    if (c.kind != K::Key && c.mods != 0)
      throw std::invalid_argument(word + " takes a single key, not a combination");
  } else if (word == "type" || word == "echo") {
    c.kind = word == "type" ? K::Type : K::Echo;
    c.text = rest_of(in);
  } else if (word == "open" || word == "save-mesh" || word == "save-scenario") {
    c.kind = word == "open" ? K::Open : word == "save-mesh" ? K::SaveMesh : K::SaveScenario;
    c.text = rest_of(in);
    if (c.text.empty()) throw std::invalid_argument(word + " takes PATH");
  } else if (word == "save-session" || word == "play-session") {
    c.kind = word == "save-session" ? K::SaveSession : K::PlaySession;
    c.text = rest_of(in);
    if (c.text.empty()) throw std::invalid_argument(word + " takes PATH");
  } else if (word == "record-start" || word == "record-stop") {
    all_args();
    if (!args.empty()) throw std::invalid_argument(word + " takes no argument");
    c.kind = word == "record-start" ? K::RecordStart : K::RecordStop;
  } else if (word == "screenshot") {
    all_args();
    if (args.empty() || args.size() > 2 || (args.size() == 2 && args[1] != "ui"))
      throw std::invalid_argument("screenshot takes PATH [ui]");
    c.kind = K::Screenshot;
    c.text = args[0];
    c.with_ui = args.size() == 2;
  } else if (word == "wait-file") {
    all_args();
    if (args.empty() || args.size() > 2) throw std::invalid_argument("wait-file takes PATH [TIMEOUT]");
    c.kind = K::WaitFile;
    c.text = args[0];
    c.seconds = args.size() == 2 ? parse_seconds(args[1]) : 60.0;
  } else if (word == "quit") {
    all_args();
    if (!args.empty()) throw std::invalid_argument("quit takes no argument");
    c.kind = K::Quit;
  } else {
    throw std::invalid_argument("unknown command " + shown(word));
  }
  return c;
}

}  // namespace

std::vector<ScriptCommand> parse_script(const std::string& text, const std::string& source) {
  std::vector<ScriptCommand> commands;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    try {
      ScriptCommand c = parse_line(line);
      c.line = number;
      commands.push_back(std::move(c));
    } catch (const std::invalid_argument& e) {
      throw Error(source + ":" + std::to_string(number) + ": " + e.what());
    }
  }
  return commands;
}

ScriptPlayer::ScriptPlayer(std::vector<ScriptCommand> commands) : commands_(std::move(commands)) {}

void ScriptPlayer::update(double now, ScriptHost& host) {
  emitted_ = false;
  while (!finished()) {
    bool done = false;
    try {
      done = step(now, host);
    } catch (const std::exception& e) {
      failed_ = true;
      error_ = "script line " + std::to_string(commands_[next_].line) + ": " + e.what();
      return;
    }
    if (!done) return;
    ++next_;
    started_ = false;
    phase_ = 0;
    if (emitted_) return;  // the next command's input waits for the next frame
  }
}

bool ScriptPlayer::step(double now, ScriptHost& host) {
  const ScriptCommand& c = commands_[next_];
  using K = ScriptCommand::Kind;
  if (!started_) {
    started_ = true;
    start_time_ = now;
    if (c.kind == K::Move) {
      host.cursor(from_x_, from_y_);
      host.locate(c, to_x_, to_y_);
    }
  }
  const double elapsed = now - start_time_;
  switch (c.kind) {
    case K::Wait: return elapsed >= c.seconds;
    case K::WaitSettled:
      if (host.settled()) return true;
      if (host.nothing_open()) throw Error("nothing is open to settle (did an open fail?)");
      if (elapsed > c.seconds) throw Error("the solver did not settle within " + std::to_string(c.seconds) + " s");
      return false;
    case K::Move: {
      const double t = c.seconds > 0 ? std::min(1.0, elapsed / c.seconds) : 1.0;
      emit(host, InputEvent::cursor(from_x_ + t * (to_x_ - from_x_), from_y_ + t * (to_y_ - from_y_)));
      return t >= 1.0;
    }
    case K::Press: emit(host, InputEvent::mouse(c.button, GLFW_PRESS, held_mods_)); return true;
    case K::Release: emit(host, InputEvent::mouse(c.button, GLFW_RELEASE, held_mods_)); return true;
    case K::Click:
      emit(host, InputEvent::mouse(c.button, phase_ == 0 ? GLFW_PRESS : GLFW_RELEASE, held_mods_));
      return ++phase_ == 2;
    case K::Scroll: emit(host, InputEvent::scroll(0.0, c.steps)); return true;
    case K::Key: {
      // Modifiers down one by one, the key down and up, modifiers up: as a keyboard sends them.
      std::vector<int> modifier_keys;
      if (c.mods & GLFW_MOD_CONTROL) modifier_keys.push_back(GLFW_KEY_LEFT_CONTROL);
      if (c.mods & GLFW_MOD_SHIFT) modifier_keys.push_back(GLFW_KEY_LEFT_SHIFT);
      if (c.mods & GLFW_MOD_ALT) modifier_keys.push_back(GLFW_KEY_LEFT_ALT);
      if (c.mods & GLFW_MOD_SUPER) modifier_keys.push_back(GLFW_KEY_LEFT_SUPER);
      const int n = int(modifier_keys.size());
      const int mods = held_mods_ | c.mods;
      if (phase_ < n) {
        emit(host, InputEvent::key_event(modifier_keys[phase_], GLFW_PRESS, held_mods_));
      } else if (phase_ == n) {
        emit(host, InputEvent::key_event(c.key, GLFW_PRESS, mods));
      } else if (phase_ == n + 1) {
        emit(host, InputEvent::key_event(c.key, GLFW_RELEASE, mods));
      } else {
        emit(host, InputEvent::key_event(modifier_keys[2 * n + 1 - phase_], GLFW_RELEASE, mods));
      }
      return ++phase_ == 2 * n + 2;
    }
    case K::Hold:
      emit(host, InputEvent::key_event(c.key, GLFW_PRESS, held_mods_));
      held_mods_ |= modifier_bit(c.key);
      return true;
    case K::Unhold:
      held_mods_ &= ~modifier_bit(c.key);
      emit(host, InputEvent::key_event(c.key, GLFW_RELEASE, held_mods_));
      return true;
    case K::Type:
      if (phase_ < int(c.text.size()))
        emit(host, InputEvent::character(static_cast<unsigned char>(c.text[phase_])));
      return ++phase_ >= int(c.text.size());
    case K::Report: {
      double x, y;
      host.locate(c, x, y);
      std::printf("report %.1f %.1f\n", x, y);
      std::fflush(stdout);
      return true;
    }
    case K::WaitFile:
      if (std::filesystem::exists(c.text)) return true;
      if (elapsed > c.seconds) throw Error(c.text + " did not appear within " + std::to_string(c.seconds) + " s");
      return false;
    case K::Screenshot:
      host.run(c);
      emitted_ = true;  // taken at the end of this frame: the next command waits for the next
      return true;
    case K::Open: case K::SaveMesh: case K::SaveScenario: case K::Echo: case K::Quit:
    case K::RecordStart: case K::RecordStop: case K::SaveSession: case K::PlaySession:
      host.run(c);
      return true;
  }
  return true;
}

}  // namespace primo::editor
