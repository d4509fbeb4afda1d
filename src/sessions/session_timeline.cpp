// A session's timeline applied to a state (docs/sessions.md): each event checked against the
// state and the mesh it is applied to, so that a bad file is rejected, naming the event, before
// anything is solved.

#include <algorithm>
#include <memory>

#include "primo/util/error.h"
#include "primo/sessions/session.h"

namespace primo {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(where.empty() ? what : where + ": " + what);
}

std::string at(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

void check_faces(const std::vector<int>& faces, int n_faces, const std::string& path, bool sorted) {
  for (size_t i = 0; i < faces.size(); ++i) {
    if (faces[i] < 0 || faces[i] >= n_faces)
      fail(path + "[" + std::to_string(i) + "]", "face " + std::to_string(faces[i]) +
                                                     " out of range (the mesh has " +
                                                     std::to_string(n_faces) + " faces)");
    if (sorted && i > 0 && faces[i] <= faces[i - 1])
      fail(path + "[" + std::to_string(i) + "]", "faces must be sorted and distinct");
  }
}

void check_handles(const std::vector<SessionHandle>& handles, int n_faces,
                   const std::string& path) {
  std::vector<int> owner(size_t(n_faces), -1);
  for (size_t h = 0; h < handles.size(); ++h) {
    const std::string p = path + "[" + std::to_string(h) + "]";
    if (handles[h].faces->empty()) fail(at(p, "faces"), "a handle needs at least one face");
    check_faces(*handles[h].faces, n_faces, at(p, "faces"), true);
    for (int f : *handles[h].faces) {
      if (owner[size_t(f)] >= 0)
        fail(at(p, "faces"), "face " + std::to_string(f) + " is also in handle " +
                                 std::to_string(owner[size_t(f)]));
      owner[size_t(f)] = int(h);
    }
  }
  // A falloff's springs pull free faces: none of its own handle's.
  for (size_t h = 0; h < handles.size(); ++h) {
    if (!handles[h].falloff) continue;
    const std::string p = at(path + "[" + std::to_string(h) + "]", "falloff.faces");
    const std::vector<int>& faces = handles[h].falloff->faces;
    check_faces(faces, n_faces, p, true);
    for (size_t i = 0; i < faces.size(); ++i)
      if (owner[size_t(faces[i])] == int(h))
        fail(p + "[" + std::to_string(i) + "]",
             "face " + std::to_string(faces[i]) + " is one of the handle's own faces");
  }
}

FaceFactors set_factors(const FaceFactors& old, int n_faces, const std::vector<int>& faces,
                        const std::vector<double>& values) {
  auto a = old ? std::make_shared<std::vector<double>>(*old)
               : std::make_shared<std::vector<double>>(size_t(n_faces), 1.0);
  a->resize(size_t(n_faces), 1.0);
  for (size_t i = 0; i < faces.size(); ++i) (*a)[size_t(faces[i])] = values[i];
  if (std::all_of(a->begin(), a->end(), [](double v) { return v == 1.0; })) return nullptr;
  return a;
}

// How messages name a session: its file, or "session" for one made in memory.
std::string source_name(const Session& s) { return s.source.empty() ? "session" : s.source; }

}  // namespace

const char* event_type_name(SessionEvent::Type type) {
  switch (type) {
    case SessionEvent::Type::Handles:
      return "handles";
    case SessionEvent::Type::Targets:
      return "targets";
    case SessionEvent::Type::Factors:
      return "factors";
    case SessionEvent::Type::Prisms:
      return "prisms";
    case SessionEvent::Type::Undo:
      return "undo";
    case SessionEvent::Type::Redo:
      return "redo";
  }
  return "?";
}

void apply_event(SessionState& state, const SessionEvent& e, int n_faces) {
  switch (e.type) {
    case SessionEvent::Type::Handles:
      check_handles(e.handles, n_faces, "handles");
      state.handles = e.handles;
      break;
    case SessionEvent::Type::Targets:
      for (size_t i = 0; i < e.poses.size(); ++i) {
        const int h = e.poses[i].handle;
        if (h < 0 || h >= int(state.handles.size()))
          fail("poses[" + std::to_string(i) + "].handle",
               "no handle " + std::to_string(h) + " (there are " +
                   std::to_string(state.handles.size()) + ")");
        state.handles[size_t(h)].pose = e.poses[i].pose;
      }
      break;
    case SessionEvent::Type::Factors: {
      check_faces(e.faces, n_faces, "faces", false);
      FaceFactors& f = e.layer == FactorLayer::Height ? state.height_factor : state.width_factor;
      f = set_factors(f, n_faces, e.faces, e.values);
      break;
    }
    case SessionEvent::Type::Prisms:
      state.prisms = e.prisms;
      break;
    case SessionEvent::Type::Undo:
    case SessionEvent::Type::Redo:
      break;
  }
}

SessionState initial_state(const Session& s, int n_faces) {
  const std::string src = source_name(s);
  SessionState state = s.initial;
  try {
    check_handles(state.handles, n_faces, "initial.handles");
    const auto check = [&](FaceFactors& f, const ListedFactors& listed, const std::string& key) {
      if (f && int(f->size()) > n_faces)
        fail("initial",
             "a painted face is out of range (the mesh has " + std::to_string(n_faces) + " faces)");
      check_faces(listed.faces, n_faces, key + ".faces", false);  // before any array is made
      if (f || !listed.faces.empty()) f = set_factors(f, n_faces, listed.faces, listed.values);
    };
    check(state.height_factor, s.initial.listed_height, "initial.height_factors");
    check(state.width_factor, s.initial.listed_width, "initial.width_factors");
  } catch (const Error& e) {
    throw Error(src + ": " + e.what());
  }
  return state;
}

SessionState validate_session(const Session& s, int n_faces) {
  const std::string src = source_name(s);
  SessionState state = initial_state(s, n_faces);
  for (size_t i = 0; i < s.events.size(); ++i) {
    try {
      apply_event(state, s.events[i], n_faces);
    } catch (const Error& e) {
      throw Error(src + ": events[" + std::to_string(i) + "] (" +
                  event_type_name(s.events[i].type) + "): " + e.what());
    }
  }
  return state;
}

}  // namespace primo
