#pragma once
// Deformation sessions (`primo-session/1`, docs/sessions.md): a recorded posing session as the
// mesh it was made on, the editor state it started from and a timeline of every change to
// what the solver sees (handles created, deleted or re-moded, handle poses per frame, painted
// factors, prism settings) plus undo/redo markers. The state is recorded by value, so applying
// the events in order reproduces every frame's EditState exactly (doubles are written with
// round-trip precision).
//
//  - SessionRecorder: fed the Document once per frame while recording; diffs the live state
//    against the last recorded one and appends events.
//  - parse_session / session_to_json: strict reading (unknown keys, wrong types and
//    truncated files are errors naming the event, "events[12] (targets): ...") and writing.
//  - apply_event: one event on an EditState; validate_session runs them all against a mesh
//    without solving, so a bad file is rejected before anything is computed or written.

#include <string>
#include <vector>

#include "document.h"
#include "edit_state.h"
#include "paint.h"
#include "primo/scenario.h"

namespace primo::editor {

inline constexpr const char* kSessionFormat = "primo-session/1";

struct SessionPose {
  int handle = 0;  // index into the handle list at that time
  Pose pose;
};

struct SessionEvent {
  enum class Type { Handles, Targets, Factors, Prisms, Undo, Redo };
  Type type = Type::Handles;
  double t = 0.0;  // seconds since the recording started
  int frame = 0;   // editor frame since the recording started
  std::vector<HandleGroup> handles;  // Handles: the whole list afterwards
  std::vector<SessionPose> poses;    // Targets: the handles whose pose changed
  PaintLayer layer = PaintLayer::Height;  // Factors
  std::vector<int> faces;                 // Factors: faces whose factor changed...
  std::vector<double> values;             // ...and their new values
  PrismSettings prisms;                   // Prisms
};
const char* event_type_name(SessionEvent::Type type);

struct Session {
  std::string source;     // the session file ("" when built in memory)
  std::string mesh;       // as written in the file (relative to its folder)
  std::string mesh_path;  // resolved
  SolverSpec solver;      // the document's solver settings (settle tolerance, method)
  EditState initial;      // handles, prisms and factors at the start (no selection)
  std::vector<SessionEvent> events;
  int frames() const { return events.empty() ? 0 : events.back().frame + 1; }
  double duration() const { return events.empty() ? 0.0 : events.back().t; }
};

// Throws primo::Error "<source>: <where>: <problem>"; <where> is "events[i] (type)" inside
// the timeline, also for a file cut off in the middle of an event.
Session parse_session(const std::string& json_text, const std::string& source);
Session load_session(const std::string& path);
// `session_path`: where it will be written, so that "mesh" is relative to its folder.
std::string session_to_json(const Session& session, const std::string& session_path);
// Atomic (temporary file + rename).
void save_session(const Session& session, const std::string& path);

// Applies one event. Throws primo::Error (without location) when it does not fit the state or
// a mesh of `n_faces` faces.
void apply_event(EditState& state, const SessionEvent& event, int n_faces);
// Applies everything from `session.initial` on a mesh of `n_faces`: throws primo::Error
// "<source>: events[i] (type): ..." at the first event that does not fit. Returns the final
// state.
EditState validate_session(const Session& session, int n_faces);

class SessionRecorder {
 public:
  void start(const Document& doc, double now);
  bool recording() const { return recording_; }
  // Once per frame (after input and commands): appends the events that turn the last
  // recorded state into doc.state.
  void observe(const Document& doc, double now);
  // Explicit undo/redo markers (observe() also infers them from the undo history).
  void note_undo(bool redo, double now);
  // Ends the recording (a final observe first) and returns it.
  Session stop(const Document& doc, double now);
  const Session& session() const { return session_; }

 private:
  void push(SessionEvent e, double now);

  bool recording_ = false;
  Session session_;
  EditState last_;
  double t0_ = 0.0;
  int frame_ = 0;
  bool marker_this_frame_ = false;
  std::string undo_label_, redo_label_;
  size_t history_size_ = 0;
};

}  // namespace primo::editor
