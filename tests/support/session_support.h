#pragma once
// A posing session recorded without the editor, for the tests of the session module
// (test_session_*.cpp): the states an editor would show, fed to primo::SessionRecorder.

#include <string>

#include "primo/mesh/mesh.h"
#include "primo/sessions/session.h"

namespace primo::test {

struct RecordedSession {
  Mesh mesh;                 // the bar it was recorded on
  Session session;
  SessionState final_state;  // the state shown last
};

// A bar posed the way a user would: a fixed base, a handle on top dragged over 12 frames and
// rotated, a stroke of softer joints, a prism setting change, then an undo and a redo. The
// events: handles, handles, 12 targets, factors, prisms, undo, prisms, redo, prisms.
RecordedSession record_bar_session(const std::string& mesh_path);

}  // namespace primo::test
