#include "session_control.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <chrono>
#include <filesystem>
#include <memory>

#include "editor.h"
#include "primo/util/error.h"
#include "primo/sessions/session_animation.h"
#include "session_bridge.h"

namespace primo::editor {

std::string default_session_path(const std::string& mesh_path) {
  const std::filesystem::path mesh(mesh_path);
  return (mesh.parent_path() / (mesh.stem().string() + ".session.json")).string();
}

std::string format_duration(double seconds) {
  char text[32];
  if (!(seconds >= 0.0)) seconds = 0.0;
  if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  } else {
    const long long whole = (long long)std::llround(seconds);
    std::snprintf(text, sizeof text, "%lld min %02lld s", whole / 60, whole % 60);
  }
  return text;
}

void SessionControl::start_recording(Editor& e) {
  Document* doc = e.document();
  // A command that cannot run yet, or a session file that does not fit, is said in the status
  // bar (Editor::error_in_status); a popup only where work would be lost: a recording that
  // could not be saved, an animation export that failed after the user waited for it.
  if (!doc) return e.error_in_status("Nothing to record: open a mesh first");
  if (playing_) pause(e);
  recorder_.start(*doc, clock_);
  has_recording_ = true;
  doc_ = doc;
  e.info("Recording the session");
}

void SessionControl::stop_recording(Editor& e) {
  if (!recorder_.recording()) return;
  recorded_ = doc_ == e.document() && e.document() ? recorder_.stop(*e.document(), clock_)
                                                   : recorder_.session();
  if (recorder_.recording()) recorder_ = DocumentRecorder{};
  e.info("Recorded " + std::to_string(recorded_.events.size()) + " events over " +
         std::to_string(recorded_.frames()) + " frames");
}

void SessionControl::save(Editor& e, const std::string& path) {
  stop_recording(e);
  if (!has_recording_) return e.error_in_status("No session recorded yet: press Record first");
  try {
    save_session(recorded_, path);
    e.info("Saved the session to " + path);
  } catch (const std::exception& ex) {
    e.error(ex.what());
  }
}

void SessionControl::open_playback(Editor& e, const std::string& path) {
  Document* doc = e.document();
  if (!doc) return e.error_in_status("Open the session's mesh first");
  try {
    Session s = load_session(path);
    validate_session(s, doc->n_faces());  // names the event that does not fit this mesh
    if (recorder_.recording()) stop_recording(e);
    playback_initial_ = validate_session(
        Session{s.source, s.mesh, s.mesh_path, s.solver, s.initial, {}}, doc->n_faces());
    playback_ = std::move(s);
    time_ = 0.0;
    shown_events_ = 0;
    has_playback_ = true;
    playing_ = false;
    doc_ = doc;
    show(e, 0.0);
    e.info("Session " + path + ": " + std::to_string(playback_.events.size()) + " events, " +
           format_duration(playback_.duration()));
  } catch (const std::exception& ex) {
    e.error_in_status(ex.what());  // the file and the problem; nothing is lost
  }
}

void SessionControl::play(Editor& e) {
  if (!has_playback_) return;
  if (time_ >= duration()) show(e, 0.0);
  playing_ = true;
}

void SessionControl::pause(Editor& e) {
  if (!playing_) return;
  playing_ = false;
  e.commit("Session playback");
}

void SessionControl::seek(Editor& e, double t) {
  if (!has_playback_) return;
  show(e, std::clamp(t, 0.0, duration()));
  if (!playing_) e.commit("Session playback");
}

void SessionControl::close_playback(Editor& e) {
  pause(e);
  has_playback_ = false;
  playback_ = Session{};
}

void SessionControl::export_animation(Editor& e, const std::string& path) {
  const Document* doc = e.document();
  if (!doc) return e.error_in_status("Open the session's mesh first");
  if (exporting())
    return e.error_in_status("Still exporting the session animation; try again when it is done");
  stop_recording(e);
  if (!has_session())
    return e.error_in_status("No session to export: record one or open one for playback");
  auto session = std::make_shared<const Session>(has_playback_ ? playback_ : recorded_);
  std::shared_ptr<const Mesh> mesh = doc->mesh;
  try {
    // Refuses a file too large before solving, counting the UVs, materials and images it keeps.
    SessionAnimation(*session, *mesh, 1, path, *doc->attributes);
  } catch (const std::exception& ex) {
    return e.error_in_status(ex.what());
  }
  e.info("Exporting the session animation to " + path + " (replaying " +
         std::to_string(session->frames()) + " frames)");
  export_ = std::async(std::launch::async, [session, mesh, path, attributes = doc->attributes] {
    save_session_animation(*session, *mesh, 1, path, *attributes);
    return "Exported the session animation to " + path;
  });
}

void SessionControl::show(Editor& e, double t) {
  Document* doc = e.document();
  if (!doc) return;
  // Forward: apply the new events; backward: start again from the initial state.
  size_t n = 0;
  while (n < playback_.events.size() && playback_.events[n].t <= t) ++n;
  SessionState s = session_state(doc->state);
  int active = doc->state.active;
  size_t from = shown_events_;
  if (t < time_ || n < shown_events_ || t == 0.0) {
    s = playback_initial_;
    from = 0;
  }
  for (size_t i = from; i < n; ++i) {
    apply_event(s, playback_.events[i], doc->n_faces());
    // A new handle list keeps the active handle when it is still there, else its last one.
    if (playback_.events[i].type == SessionEvent::Type::Handles)
      active = std::min(active, int(s.handles.size()) - 1);
  }
  EditState shown = doc->state;
  set_session_state(shown, s, doc->topology->rest_geometry);
  shown.active = active >= int(shown.handles.size()) ? -1 : active;
  doc->state = shown;
  time_ = t;
  shown_events_ = n;
  e.live_edit();
}

void SessionControl::update(Editor& e, double seconds) {
  clock_ += seconds;
  if (export_.valid() && export_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      e.info(export_.get());
    } catch (const std::exception& ex) {
      e.error(ex.what());
    }
  }
  if (doc_ && doc_ != e.document()) {  // another document was opened
    if (recorder_.recording()) recorded_ = recorder_.session(), recorder_ = DocumentRecorder{};
    if (has_playback_) playing_ = false, has_playback_ = false;
    doc_ = nullptr;
  }
  if (recorder_.recording() && e.document()) recorder_.observe(*e.document(), clock_);
  if (playing_) {
    const double t = std::min(time_ + seconds, duration());
    show(e, t);
    if (t >= duration()) pause(e);
  }
}

}  // namespace primo::editor
