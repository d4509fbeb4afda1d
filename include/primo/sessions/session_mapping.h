#pragma once
// A session carried over to a finer version of the surface it was recorded on (`primo replay
// --mesh`, docs/sessions.md).

#include "primo/mesh/mesh.h"
#include "primo/sessions/session.h"

namespace primo {

// Every face of `fine` takes the face of `coarse` whose centroid is nearest its own, and
// handles and painted factors select the fine faces of their coarse faces. Poses are unchanged
// (the same rigid motions about the same pivots), so the posing is the same. Validates the
// session on `coarse` first (errors name the event). Throws primo::Error when a handle ends up
// empty.
Session map_session_to_mesh(const Session& session, const Mesh& coarse, const Mesh& fine);

}  // namespace primo
