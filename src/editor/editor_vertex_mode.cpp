// Vertex mode: brush, box, lasso and click pick vertices; a handle made from them takes every
// face touching one (vertex_selection.h).

#include "editor.h"

namespace primo::editor {

SelectionMode Editor::selection_mode() const {
  return doc_ && doc_->state.vertex_selection ? SelectionMode::Vertices : SelectionMode::Faces;
}

FaceMask Editor::selection_as_faces() const {
  const EditState& s = doc_->state;
  if (!s.vertex_selection) return *s.selection;
  FaceMask faces = faces_touching_vertices(*doc_->topology, *s.vertex_selection);
  deselect_hidden(faces, s.hidden);
  return faces;
}

void Editor::set_selection_mode(SelectionMode mode) {
  if (!doc_ || mode == selection_mode()) return;
  end_gesture_before_edit();
  EditState& s = doc_->state;
  if (mode == SelectionMode::Vertices) {
    store_vertex_selection(vertices_of_faces(*doc_->topology, *s.selection));
    commit("Vertex mode");
    info("Vertex mode: brush, box and lasso pick vertices; a handle takes every face touching "
         "one (" + key_map().label(Action::SelectFaceMode) + ": face mode)");
  } else {
    // The faces whose corners are all selected stay selected (`selection` holds them).
    s.vertex_selection.reset();
    commit("Face mode");
    info("Face mode: the faces whose vertices were all selected stay selected");
  }
  overlay_changed_ = true;
}

void Editor::store_vertex_selection(VertexMask vertices) {
  EditState& s = doc_->state;
  const MeshTopology& t = *doc_->topology;
  if (s.hidden)  // a vertex of hidden faces only is hidden too
    for (int v = 0; v < t.n_vertices; ++v) {
      if (!vertices[size_t(v)]) continue;
      bool shown = false;
      for (int k = t.vertex_face_begin[size_t(v)]; k < t.vertex_face_begin[size_t(v) + 1] && !shown; ++k)
        shown = !is_hidden(s.hidden, t.vertex_faces[size_t(k)]);
      vertices[size_t(v)] = shown ? 1 : 0;
    }
  FaceMask faces = faces_within_vertices(t, vertices);
  deselect_hidden(faces, s.hidden);
  s.vertex_selection = std::make_shared<const VertexMask>(std::move(vertices));
  s.selection = std::make_shared<const FaceMask>(std::move(faces));
  overlay_changed_ = true;
}

void Editor::set_vertex_selection(VertexMask vertices, const std::string& label) {
  end_gesture_before_edit();
  store_vertex_selection(std::move(vertices));
  commit(label);
}

void Editor::select_picked(const std::vector<int>& items) {
  EditState& s = doc_->state;
  if (s.vertex_selection) {
    VertexMask v = *s.vertex_selection;
    apply_selection(v, items, select_op_);
    if (v != *s.vertex_selection) store_vertex_selection(std::move(v));
    return;
  }
  FaceMask mask = *s.selection;
  apply_selection(mask, items, select_op_);
  finish_selection(*s.selection, mask);
  if (mask != *s.selection) s.selection = std::make_shared<const FaceMask>(std::move(mask));
  overlay_changed_ = true;
}

std::vector<int> Editor::vertices_under(const ScreenShape& shape) {
  // Visible where they are (the pick buffer's depth), or any with x-ray; the vertices of hidden
  // faces only are left out when the selection is stored.
  return points_in_shape(shape, pick_image_under(shape), project_points(positions()), tools.xray,
                         0.01 * doc_->topology->bbox_diagonal);
}

int Editor::vertex_at_cursor() {
  // The corner of the face under the cursor nearest to it.
  const int f = face_at_cursor();
  if (f < 0) return -1;
  const MeshTopology& t = *doc_->topology;
  int best = -1;
  double best_d = 0.0;
  for (int k = t.face_begin[size_t(f)]; k < t.face_begin[size_t(f) + 1]; ++k) {
    const int v = t.face_vertices[size_t(k)];
    const Vec3& p = positions()[size_t(v)];
    const glm::dvec3 s = camera_.project(glm::dvec3(p.x(), p.y(), p.z()));
    const double d = glm::length(glm::dvec2(s.x, s.y) - cursor_);
    if (best < 0 || d < best_d) best = v, best_d = d;
  }
  return best;
}

}  // namespace primo::editor
