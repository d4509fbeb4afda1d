#include "vertex_selection.h"

namespace primo::editor {

const char* selection_mode_label(SelectionMode mode) {
  return mode == SelectionMode::Vertices ? "vertices" : "faces";
}

VertexMask vertices_of_faces(const MeshTopology& t, const FaceMask& faces) {
  VertexMask v(size_t(t.n_vertices), 0);
  for (int f = 0; f < t.n_faces && f < int(faces.size()); ++f)
    if (faces[size_t(f)])
      for (int k = t.face_begin[size_t(f)]; k < t.face_begin[size_t(f) + 1]; ++k)
        v[size_t(t.face_vertices[size_t(k)])] = 1;
  return v;
}

FaceMask faces_within_vertices(const MeshTopology& t, const VertexMask& vertices) {
  FaceMask faces(size_t(t.n_faces), 0);
  for (int f = 0; f < t.n_faces; ++f) {
    bool all = true;
    for (int k = t.face_begin[size_t(f)]; k < t.face_begin[size_t(f) + 1] && all; ++k)
      all = vertices[size_t(t.face_vertices[size_t(k)])] != 0;
    faces[size_t(f)] = all ? 1 : 0;
  }
  return faces;
}

FaceMask faces_touching_vertices(const MeshTopology& t, const VertexMask& vertices) {
  FaceMask faces(size_t(t.n_faces), 0);
  for (int v = 0; v < t.n_vertices && v < int(vertices.size()); ++v)
    if (vertices[size_t(v)])
      for (int k = t.vertex_face_begin[size_t(v)]; k < t.vertex_face_begin[size_t(v) + 1]; ++k)
        faces[size_t(t.vertex_faces[size_t(k)])] = 1;
  return faces;
}

VertexMask corners_of(const MeshTopology& t, const std::vector<int>& faces) {
  FaceMask mask(size_t(t.n_faces), 0);
  apply_selection(mask, faces, SelectOp::Add);
  return vertices_of_faces(t, mask);
}

std::vector<unsigned> shown_vertices(const MeshTopology& t, const HiddenFaces& hidden) {
  FaceMask shown(size_t(t.n_faces), 1);
  deselect_hidden(shown, hidden);
  const VertexMask corners = vertices_of_faces(t, shown);
  std::vector<unsigned> out;
  for (size_t v = 0; v < corners.size(); ++v)
    if (corners[v]) out.push_back(unsigned(v));
  return out;
}

std::vector<unsigned> selected_vertices(const VertexMask& vertices, const HiddenFaces& hidden,
                                        const MeshTopology& t) {
  std::vector<unsigned> out;
  for (unsigned v : shown_vertices(t, hidden))
    if (v < vertices.size() && vertices[v]) out.push_back(v);
  return out;
}

}  // namespace primo::editor
