// Edge loops: Alt+click on an edge selects the ring of quads across it (face_ring.h).

#include "document/selection/face_ring.h"
#include "editor.h"

namespace primo::editor {

bool Editor::select_loop_at_cursor(bool add) {
  if (!doc_) return false;
  const int face = face_at_cursor();
  if (face < 0) {
    info("Alt+click on an edge of the surface selects the loop of faces across it");
    return false;
  }
  const MeshTopology& t = *doc_->topology;
  // Only the clicked face's corners need a place on screen.
  std::vector<Eigen::Vector2d> screen(size_t(t.n_vertices), Eigen::Vector2d::Zero());
  const std::vector<Vec3>& points = positions();
  for (int k = t.face_begin[size_t(face)]; k < t.face_begin[size_t(face) + 1]; ++k) {
    const int v = t.face_vertices[size_t(k)];
    const Vec3& p = points[size_t(v)];
    const glm::dvec3 s = camera_.project(glm::dvec3(p.x(), p.y(), p.z()));
    screen[size_t(v)] = {s.x, s.y};
  }
  const FaceEdge edge = nearest_edge_of_face(t, face, screen, {cursor_.x, cursor_.y});
  std::vector<int> ring = face_ring(t, edge.a, edge.b);
  drop_hidden(ring, doc_->state.hidden);
  if (ring.empty()) {
    info("Edge loops need quads: the faces at this edge are not quads, nothing new selected");
    return false;
  }
  const std::string label = add ? "Add loop" : "Select loop";
  if (const auto& selected = doc_->state.vertex_selection) {
    VertexMask vertices = corners_of(t, ring);
    if (add)
      for (size_t v = 0; v < vertices.size(); ++v) vertices[v] |= (*selected)[v];
    set_vertex_selection(std::move(vertices), label);
  } else {
    FaceMask mask = *doc_->state.selection;
    apply_selection(mask, ring, add ? SelectOp::Add : SelectOp::Replace);
    set_selection(mask, label);
  }
  info("Loop of " + std::to_string(ring.size()) + " faces selected" +
       (add ? " (added)" : " (Shift+Alt+click adds another)"));
  return true;
}

}  // namespace primo::editor
