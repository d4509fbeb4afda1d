#pragma once
// Recording a posing session (docs/sessions.md) from the states it is shown, one per frame:
// each is compared with the last recorded one, and the events that turn one into the other are
// appended. Whoever records says when a change came from an undo or a redo (note_undo); the
// editor infers that from its undo history (src/editor/recording/document_recorder.h).

#include <string>

#include "primo/scenario/scenario.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_state.h"

namespace primo {

class SessionRecorder {
 public:
  // Starts a recording of `initial` on the mesh at `mesh_path`, solved with `solver`'s settings.
  // `now` is in seconds on any clock that the later calls share.
  void start(const SessionState& initial, const std::string& mesh_path, const SolverSpec& solver,
             double now);
  bool recording() const { return recording_; }
  // Once per frame: appends the events that turn the last recorded state into `state` (on a
  // mesh of `n_faces` faces), and counts the frame.
  void observe(const SessionState& state, int n_faces, double now);
  // An undo or redo marker in the current frame.
  void note_undo(bool redo, double now);
  // Ends the recording and returns it.
  Session stop();
  // The recording so far (also after stop()).
  const Session& session() const { return session_; }

 private:
  void push(SessionEvent e, double now);

  bool recording_ = false;
  Session session_;
  SessionState last_;
  double t0_ = 0.0;
  int frame_ = 0;
};

}  // namespace primo
