// Hide and reveal: hidden faces leave the view and the selection, never the solve
// (face_visibility.h). In vertex mode the faces touching the selected vertices are hidden.

#include "editor.h"

namespace primo::editor {
namespace {

std::string faces_text(int n) { return std::to_string(n) + (n == 1 ? " face" : " faces"); }

}  // namespace

void Editor::hide_faces(bool selected) {
  if (!doc_) return;
  end_gesture_before_edit();
  EditState& s = doc_->state;
  FaceMask selection = selection_as_faces();
  if (count_selected(selection) == 0)
    return error_in_status(selected ? "Select faces first: H hides the selection (Shift+H hides the rest)"
                                    : "Select faces first: Shift+H hides every face but the selection");
  FaceMask hidden = s.hidden ? *s.hidden : FaceMask(size_t(doc_->n_faces()), 0);
  const int n = selected ? primo::editor::hide_selected(hidden, selection)
                         : primo::editor::hide_unselected(hidden, selection);
  s.hidden = std::make_shared<const FaceMask>(std::move(hidden));
  if (s.vertex_selection)
    store_vertex_selection(*s.vertex_selection);  // leaves out the vertices now hidden
  else
    s.selection = std::make_shared<const FaceMask>(std::move(selection));
  commit(selected ? "Hide " + faces_text(n) : "Hide " + faces_text(n) + " around the selection");
  info("Hid " + faces_text(n) + "; " + faces_text(count_hidden(s.hidden)) +
       " hidden in all (" + key_map().label(Action::RevealAll) + " reveals)");
}

void Editor::hide_selected() { hide_faces(true); }

void Editor::hide_unselected() { hide_faces(false); }

void Editor::reveal_all() {
  if (!doc_) return;
  end_gesture_before_edit();
  EditState& s = doc_->state;
  if (count_hidden(s.hidden) == 0) return info("No face is hidden");
  FaceMask hidden = *s.hidden;
  FaceMask revealed(hidden.size(), 0);
  const int n = primo::editor::reveal_all(hidden, revealed);
  s.hidden.reset();
  if (s.vertex_selection) {
    VertexMask vertices = vertices_of_faces(*doc_->topology, revealed);
    for (size_t v = 0; v < vertices.size(); ++v) vertices[v] |= (*s.vertex_selection)[v];
    store_vertex_selection(std::move(vertices));
  } else {
    FaceMask selection = *s.selection;
    apply_selection(selection, selected_faces(revealed), SelectOp::Add);
    s.selection = std::make_shared<const FaceMask>(std::move(selection));
  }
  commit("Reveal " + faces_text(n));
  info("Revealed " + faces_text(n) + " (selected, so " + key_map().label(Action::HideSelected) +
       " hides them again)");
}

}  // namespace primo::editor
