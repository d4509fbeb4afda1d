#include "selection.h"

#include <algorithm>

namespace primo::editor {

void apply_selection(FaceMask& mask, const std::vector<int>& faces, SelectOp op) {
  if (op == SelectOp::Replace) std::fill(mask.begin(), mask.end(), 0);
  const std::uint8_t value = op == SelectOp::Subtract ? 0 : 1;
  for (int f : faces)
    if (f >= 0 && f < int(mask.size())) mask[f] = value;
}

namespace {

// Faces that share a vertex with a face whose mask value is `seed`.
FaceMask touching(const FaceMask& mask, const MeshTopology& t, std::uint8_t seed) {
  FaceMask out(mask.size(), 0);
  std::vector<std::uint8_t> vertex_hit(t.n_vertices, 0);
  for (int f = 0; f < t.n_faces; ++f)
    if (mask[f] == seed)
      for (int k = t.face_begin[f]; k < t.face_begin[f + 1]; ++k) vertex_hit[t.face_vertices[k]] = 1;
  for (int v = 0; v < t.n_vertices; ++v)
    if (vertex_hit[v])
      for (int k = t.vertex_face_begin[v]; k < t.vertex_face_begin[v + 1]; ++k)
        out[t.vertex_faces[k]] = 1;
  return out;
}

}  // namespace

void grow_selection(FaceMask& mask, const MeshTopology& topology) {
  const FaceMask near = touching(mask, topology, 1);
  for (size_t f = 0; f < mask.size(); ++f) mask[f] = mask[f] || near[f];
}

void shrink_selection(FaceMask& mask, const MeshTopology& topology) {
  const FaceMask near_unselected = touching(mask, topology, 0);
  for (size_t f = 0; f < mask.size(); ++f)
    if (near_unselected[f]) mask[f] = 0;
}

void invert_selection(FaceMask& mask) {
  for (auto& m : mask) m = m ? 0 : 1;
}

void clear_selection(FaceMask& mask) { std::fill(mask.begin(), mask.end(), 0); }

void select_all(FaceMask& mask) { std::fill(mask.begin(), mask.end(), 1); }

std::vector<int> selected_faces(const FaceMask& mask) {
  std::vector<int> faces;
  for (size_t f = 0; f < mask.size(); ++f)
    if (mask[f]) faces.push_back(int(f));
  return faces;
}

int count_selected(const FaceMask& mask) {
  return int(std::count_if(mask.begin(), mask.end(), [](std::uint8_t m) { return m != 0; }));
}

}  // namespace primo::editor
