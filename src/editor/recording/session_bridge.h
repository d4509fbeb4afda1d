#pragma once
// The editor's edit state as a recorded session keeps it (primo/sessions/session_state.h), and
// back. A session holds what the solver sees: handles, prisms and painted factors. The
// selection, the active handle and the counters for new handles' names and colours stay in the
// editor.

#include "document/edit_state.h"
#include "primo/sessions/session_state.h"

namespace primo::editor {

SessionHandleMode session_mode(HandleMode mode);
HandleMode handle_mode(SessionHandleMode mode);

SessionHandle session_handle(const HandleGroup& group);
// `rest`: the mesh's rest face geometry, which a falloff's springs are made from.
HandleGroup handle_group(const SessionHandle& handle, const FaceGeometry& rest);

// The handles, prisms and factors of `state` (face lists and factor arrays stay shared).
SessionState session_state(const EditState& state);
// Replaces the handles, prisms and factors of `state` by the session state's; everything else
// (selection, active handle, counters) is kept.
void set_session_state(EditState& state, const SessionState& session, const FaceGeometry& rest);

}  // namespace primo::editor
