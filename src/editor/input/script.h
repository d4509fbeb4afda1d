#pragma once
// Scripted sessions (`primo edit --script FILE`): timed input events that go through the same
// queue as real GLFW input, plus a few commands that call the same actions as the menus.
// One command per line; '#' starts a comment. Positions are window coordinates, or
// "@NAME [DX DY]" (the current screen position of handle NAME's pivot, plus an offset) or
// "center [DX DY]" (the viewport centre). Double quotes group words: move "@Handle 1" 10 0.
//
//   wait SECONDS                    pause
//   wait-settled [TIMEOUT]          until the solver has settled and the view shows it (60 s)
//   move POSITION [over SECONDS]    cursor motion, one event per frame when "over" is given
//   press|release|click BUTTON      left, right or middle; modifiers held with "hold"
//   scroll STEPS                    mouse wheel (positive: away from the user)
//   key COMBO                       e.g. ctrl+z, ctrl+shift+z, g, kp_1, f12, escape
//   hold KEY / unhold KEY           keep a key (e.g. shift) down / let it go
//   type TEXT                       characters, as typed into a text field
//   open PATH | save-mesh PATH | save-scenario PATH | screenshot PATH [ui]
//                                   (open first waits for an open or save under way)
//   echo TEXT                       print a line on stdout
//   report POSITION                 print "report X Y" (window coordinates) on stdout
//   wait-file PATH [TIMEOUT]        until the file exists (60 s): lets a test drive real input
//                                   (xdotool) and tell the script when it is done
//   record-start | record-stop      record the session (docs/sessions.md)
//   save-session PATH | play-session PATH   save the recording / open one and play it
//   quit                            exit (status 0 unless a command failed)
// Input commands emit at most one event per frame, as a person would; the others run at once,
// except that a screenshot ends the frame (it is taken when the frame is drawn).

#include <algorithm>
#include <string>
#include <vector>

#include "input.h"

namespace primo::editor {

struct ScriptCommand {
  enum class Kind {
    Wait,
    WaitSettled,
    Move,
    Press,
    Release,
    Click,
    Scroll,
    Key,
    Hold,
    Unhold,
    Type,
    Open,
    SaveMesh,
    SaveScenario,
    Screenshot,
    Echo,
    Report,
    WaitFile,
    Quit,
    RecordStart,
    RecordStop,
    SaveSession,
    PlaySession
  };
  Kind kind = Kind::Wait;
  int line = 0;
  double seconds = 0.0;  // Wait, WaitSettled timeout, Move duration
  // Move and Report: an absolute position, or an anchor (handle name or the viewport centre)
  // plus an offset.
  enum class Anchor { None, Handle, Center } anchor = Anchor::None;
  std::string handle;
  double x = 0.0, y = 0.0;
  int button = 0;        // Press, Release, Click
  int key = 0;           // Key, Hold, Unhold
  int mods = 0;          // Key
  double steps = 0.0;    // Scroll
  std::string text;      // Type, Echo, paths
  bool with_ui = false;  // Screenshot
};

// Throws primo::Error "<source>:<line>: <problem>".
std::vector<ScriptCommand> parse_script(const std::string& text, const std::string& source);

// What the player needs from the editor.
class ScriptHost {
 public:
  virtual ~ScriptHost() = default;
  virtual void push_input(const InputEvent& event) = 0;
  // Window position of a Move command's target; throws primo::Error when it has none.
  virtual void locate(const ScriptCommand& command, double& x, double& y) = 0;
  virtual void cursor(double& x, double& y) = 0;
  // The solver is idle for the latest edit and the view shows its result.
  virtual bool settled() = 0;
  // No mesh is open and none is loading (an `open` failed): waiting to settle is pointless.
  virtual bool nothing_open() { return false; }
  // Open, SaveMesh, SaveScenario, Screenshot, Echo, Quit. Throws primo::Error on failure.
  // (Report is printed by the player from locate().)
  virtual void run(const ScriptCommand& command) = 0;
};

class ScriptPlayer {
 public:
  explicit ScriptPlayer(std::vector<ScriptCommand> commands);
  // Once per frame, before input is handled. `now` in seconds (any origin).
  void update(double now, ScriptHost& host);
  bool finished() const { return next_ >= commands_.size() || failed_; }
  bool failed() const { return failed_; }
  const std::string& error() const { return error_; }
  // The script line of the command under way (the last one once finished; 0 when empty).
  int line() const {
    return commands_.empty() ? 0 : commands_[std::min(next_, commands_.size() - 1)].line;
  }

 private:
  bool step(double now, ScriptHost& host);  // true: command finished, go on this frame
  void emit(ScriptHost& host, const InputEvent& e) {
    host.push_input(e);
    emitted_ = true;
  }

  std::vector<ScriptCommand> commands_;
  size_t next_ = 0;
  bool started_ = false;  // the current command has begun
  double start_time_ = 0.0;
  double from_x_ = 0.0, from_y_ = 0.0, to_x_ = 0.0, to_y_ = 0.0;
  int phase_ = 0;  // sub-step of multi-event commands
  int held_mods_ = 0;
  bool emitted_ = false;  // an input event went out this frame
  bool failed_ = false;
  std::string error_;
};

}  // namespace primo::editor
