// The Editor's handling of unsaved work: asking before it is discarded, autosaving it, and
// recovering it (editor.h, "Unsaved work"; docs/editor.md, "Files").

#include "user_files/autosave.h"
#include "editor.h"

#include <chrono>

namespace primo::editor {

bool Editor::has_unsaved_changes() const {
  if (!doc_) return false;
  EditState saved = doc_->saved_state;
  saved.selection = doc_->state.selection;  // selecting is not work to lose
  saved.hidden = doc_->state.hidden;        // nor is hiding
  saved.vertex_selection = doc_->state.vertex_selection;
  return !(doc_->state == saved);
}

void Editor::request_open(const std::string& path) {
  if (!has_unsaved_changes()) return open(path);
  discard_question_ = DiscardQuestion{DiscardQuestion::Then::Open, path};
}

bool Editor::ask_to_quit() {
  if (!has_unsaved_changes()) return true;
  discard_question_ = DiscardQuestion{DiscardQuestion::Then::Quit, {}};
  return false;
}

void Editor::answer_discard(DiscardAnswer answer, const std::string& save_path) {
  if (!discard_question_) return;
  const DiscardQuestion question = *discard_question_;
  if (answer == DiscardAnswer::Cancel) {
    discard_question_.reset();
    return;
  }
  if (answer == DiscardAnswer::Save) {
    const std::string path = save_path.empty() && doc_ ? doc_->scenario_path : save_path;
    if (path.empty()) return error_in_status("Choose where to save the scenario first");
    if (!save_scenario(path)) return;  // the question stays: the work is not safe yet
  } else {
    forget_autosave();  // discarded by choice
  }
  discard_question_.reset();
  if (question.then == DiscardQuestion::Then::Open)
    open(question.path);
  else
    request_quit();
}

bool Editor::autosave_now() {
  if (!doc_) return false;
  const std::string path = autosave_path(doc_->mesh_path);
  try {
    write_autosave(path, scenario_text(path, autosave_mesh_reference(path, doc_->mesh_path)));
  } catch (const std::exception& e) {
    error("Autosave failed: " + std::string(e.what()));
    return false;
  }
  return true;
}

bool Editor::autosave_before_exit(double max_seconds) {
  if (!doc_) return false;
  // A solve under way is stopped where it is, so that the autosave keeps the pose it reached
  // (solved_state) instead of none, or the one of the edit before. A stop asked for before the
  // solver took the latest edit is dropped: ask again until it is idle.
  const auto start = std::chrono::steady_clock::now();
  while (!worker_->idle_for_latest() &&
         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < max_seconds) {
    worker_->stop();
    worker_->wait_idle(0.05);
  }
  update(0.0);  // takes the stopped solve's result
  return autosave_now();
}

void Editor::forget_autosave() {
  if (doc_) remove_autosave(autosave_path(doc_->mesh_path));
}

void Editor::recover(const std::string& autosave_file) { open_file(autosave_file, true); }

}  // namespace primo::editor
