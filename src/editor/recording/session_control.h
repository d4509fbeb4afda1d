#pragma once
// The editor's session recorder and player (docs/sessions.md), without a window: the panel
// (ui/session_panel.cpp) and the script commands record-start / record-stop / save-session /
// play-session call it, and Editor::update drives it once per frame.
//
// Recording observes the document after every frame (DocumentRecorder). Playback loads a
// session recorded on the open mesh (same face count) and shows the edit state at the
// playback time: seeking recomputes it from the session's initial state, playing advances the
// time with the frame clock. Each shown state goes to the solver like a live edit; pausing or
// reaching the end records one undo step ("Session playback").

#include <future>
#include <string>

#include "document_recorder.h"
#include "primo/sessions/session.h"

namespace primo::editor {

class Editor;

// Where the Session panel proposes to save a recording of `mesh_path`: beside the mesh, named
// after it (spot.obj -> spot.session.json), so that meshes of one folder do not share a file.
std::string default_session_path(const std::string& mesh_path);
// A duration as people read it: "8.1 s", "2 min 05 s".
std::string format_duration(double seconds);

class SessionControl {
 public:
  // --- Recording ------------------------------------------------------------------------
  void start_recording(Editor& editor);
  void stop_recording(Editor& editor);
  bool recording() const { return recorder_.recording(); }
  // The last recording (also while it runs); false when there is none.
  bool has_recording() const { return has_recording_; }
  const Session& recording_session() const {
    return recorder_.recording() ? recorder_.session() : recorded_;
  }
  // Saves the last recording (stopping it first). Errors become editor messages.
  void save(Editor& editor, const std::string& path);

  // --- Playback -------------------------------------------------------------------------
  // Loads a session file for playback (paused at its start). Errors become editor messages.
  void open_playback(Editor& editor, const std::string& path);
  bool has_playback() const { return has_playback_; }
  const Session& playback_session() const { return playback_; }
  void play(Editor& editor);
  void pause(Editor& editor);
  bool playing() const { return playing_; }
  void seek(Editor& editor, double t);
  double time() const { return time_; }
  double duration() const { return playback_.duration(); }
  void close_playback(Editor& editor);

  // --- Animation ------------------------------------------------------------------------
  // The session to export: the one open for playback, else the last recording.
  bool has_session() const { return has_playback_ || has_recording_; }
  // Writes the session as one animated glTF (.glb or .gltf), the file `primo replay
  // --animation` writes (every frame): replayed on the open mesh in the background; the
  // message says when it is written, or why not. Too large a file is refused at once.
  void export_animation(Editor& editor, const std::string& path);
  bool exporting() const { return export_.valid(); }

  // Once per frame from Editor::update.
  void update(Editor& editor, double seconds);

 private:
  void show(Editor& editor, double t);

  DocumentRecorder recorder_;
  Session recorded_;
  bool has_recording_ = false;
  double clock_ = 0.0;
  const Document* doc_ = nullptr;  // the document recorded or played on

  Session playback_;
  SessionState playback_initial_;  // the session's initial state on the open mesh
  bool has_playback_ = false;
  bool playing_ = false;
  double time_ = 0.0;
  size_t shown_events_ = 0;

  std::future<std::string> export_;  // the message once written
};

}  // namespace primo::editor
