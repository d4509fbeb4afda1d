#pragma once
// Deformation sessions (`primo-session/1`, docs/sessions.md): a recorded posing session as the
// mesh it was made on, the state it started from (primo/sessions/session_state.h) and a timeline of
// every change to what the solver sees (handles created, deleted or re-moded, handle poses per
// frame, painted factors, prism settings) plus undo/redo markers. The state is recorded by
// value, so applying the events in order reproduces every frame's state exactly (doubles are
// written with round-trip precision).
//
//  - parse_session / session_to_json: strict reading (unknown keys, wrong types and
//    truncated files are errors naming the event, "events[12] (targets): ...") and writing.
//  - apply_event: one event on a SessionState; validate_session runs them all against a mesh
//    without solving, so a bad file is rejected before anything is computed or written.
//
// Recording is primo/sessions/session_recorder.h, headless replay
// primo/sessions/session_replay.h, carrying a session over to a finer mesh
// primo/sessions/session_mapping.h.

#include <string>
#include <vector>

#include "primo/scenario/scenario.h"
#include "primo/sessions/session_state.h"

namespace primo {

inline constexpr const char* kSessionFormat = "primo-session/1";

// Limits of what a session file may claim, checked when it is read (docs/sessions.md): the
// last frame (10,000,000: 46 hours at 60 frames a second; the frame count stays far from
// INT_MAX) and the largest face index of the initial painted factors (a first check before the
// mesh is known; initial_state checks them against the mesh).
inline constexpr int kMaxSessionFrame = 10000000;
inline constexpr int kMaxSessionFaces = 1 << 24;

// The painted layer a Factors event changes: the height factor (softer joints below 1) or the
// width factor (prisms shrunk or grown about their centroids).
enum class FactorLayer { Height, Width };

// One entry of a Targets event: a handle (its index at that time) and its new pose.
struct SessionTarget {
  int handle = 0;
  SessionPose pose;
};

struct SessionEvent {
  enum class Type { Handles, Targets, Factors, Prisms, Undo, Redo };
  Type type = Type::Handles;
  double t = 0.0;                           // seconds since the recording started
  int frame = 0;                            // editor frame since the recording started
  std::vector<SessionHandle> handles;       // Handles: the whole list afterwards
  std::vector<SessionTarget> poses;         // Targets: the handles whose pose changed
  FactorLayer layer = FactorLayer::Height;  // Factors
  std::vector<int> faces;                   // Factors: faces whose factor changed...
  std::vector<double> values;               // ...and their new values
  SessionPrisms prisms;                     // Prisms
};
const char* event_type_name(SessionEvent::Type type);

// Painted factors as a session file lists them: faces and their values (a later entry of a
// face wins).
struct ListedFactors {
  std::vector<int> faces;
  std::vector<double> values;
};

// The state a session starts from. The initial painted factors of a file stay listed here
// until the session meets its mesh (initial_state, validate_session): only with the mesh's face
// count known are they made into per-face arrays, so that a file naming face 16,777,215 of a
// 168-face mesh is an error before anything is allocated for it. A SessionState converts to
// this (with nothing listed); for the state itself use initial_state, not a copy of the base.
struct SessionStart : SessionState {
  SessionStart(SessionState state = {}) : SessionState(std::move(state)) {}  // NOLINT: implicit
  ListedFactors listed_height, listed_width;
};

struct Session {
  std::string source;     // the session file ("" when built in memory)
  std::string mesh;       // as written in the file (relative to its folder)
  std::string mesh_path;  // resolved
  SolverSpec solver;      // the recording's solver settings (settle tolerance, method)
  SessionStart initial;   // handles, prisms and factors at the start
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
void apply_event(SessionState& state, const SessionEvent& event, int n_faces);
// `session.initial` checked against a mesh of `n_faces` faces, its listed factors made into
// arrays. Throws primo::Error "<source>: initial.<key>: ..." when a face is out of range.
SessionState initial_state(const Session& session, int n_faces);
// Applies everything from `session.initial` on a mesh of `n_faces`: throws primo::Error
// "<source>: events[i] (type): ..." at the first event that does not fit. Returns the final
// state.
SessionState validate_session(const Session& session, int n_faces);

}  // namespace primo
