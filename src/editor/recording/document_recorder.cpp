#include "document_recorder.h"

#include "session_bridge.h"

namespace primo::editor {

void DocumentRecorder::start(const Document& doc, double now) {
  recorder_.start(session_state(doc.state), doc.mesh_path, doc.solver, now);
  marker_this_frame_ = false;
  undo_label_ = doc.history.undo_label();
  redo_label_ = doc.history.redo_label();
  history_size_ = doc.history.size();
}

void DocumentRecorder::note_undo(bool redo, double now) {
  if (!recorder_.recording()) return;
  recorder_.note_undo(redo, now);
  marker_this_frame_ = true;
}

void DocumentRecorder::observe(const Document& doc, double now) {
  if (!recorder_.recording()) return;
  // An undo moves the step that was "undo" to "redo" without adding one; a redo the other way.
  const UndoStack& h = doc.history;
  if (!marker_this_frame_ && h.size() == history_size_ && doc.state == h.current()) {
    if (!undo_label_.empty() && h.redo_label() == undo_label_ && h.undo_label() != undo_label_)
      note_undo(false, now);
    else if (!redo_label_.empty() && h.undo_label() == redo_label_ && h.redo_label() != redo_label_)
      note_undo(true, now);
  }
  recorder_.observe(session_state(doc.state), doc.n_faces(), now);
  undo_label_ = h.undo_label();
  redo_label_ = h.redo_label();
  history_size_ = h.size();
  marker_this_frame_ = false;
}

Session DocumentRecorder::stop(const Document& doc, double now) {
  if (recorder_.recording()) observe(doc, now);
  return recorder_.stop();
}

}  // namespace primo::editor
