#pragma once
// Records a posing session from the editor's document (docs/sessions.md): once per frame the
// document's edit state goes to a primo::SessionRecorder, and undo and redo are told apart
// from other edits by watching the document's undo history.

#include <string>

#include "document/document.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_recorder.h"

namespace primo::editor {

class DocumentRecorder {
 public:
  void start(const Document& doc, double now);
  bool recording() const { return recorder_.recording(); }
  // Once per frame (after input and commands): appends the events that turn the last
  // recorded state into doc.state.
  void observe(const Document& doc, double now);
  // Explicit undo/redo markers (observe() also infers them from the undo history).
  void note_undo(bool redo, double now);
  // Ends the recording (a final observe first) and returns it.
  Session stop(const Document& doc, double now);
  const Session& session() const { return recorder_.session(); }

 private:
  SessionRecorder recorder_;
  bool marker_this_frame_ = false;
  std::string undo_label_, redo_label_;
  size_t history_size_ = 0;
};

}  // namespace primo::editor
