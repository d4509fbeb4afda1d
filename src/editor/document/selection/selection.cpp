#include "selection.h"

#include <algorithm>
#include <cmath>

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

void select_linked(FaceMask& mask, const MeshTopology& t, double max_angle_deg) {
  const double min_cos = std::cos(std::min(max_angle_deg, 180.0) * M_PI / 180.0) - 1e-12;
  std::vector<int> queue;
  for (int f = 0; f < t.n_faces; ++f)
    if (mask[f]) queue.push_back(f);
  while (!queue.empty()) {
    const int f = queue.back();
    queue.pop_back();
    const int n = t.degree(f);
    for (int k = 0; k < n; ++k) {
      // The faces across edge (a, b): around a, the ones that also have b.
      const int a = t.face_vertices[t.face_begin[f] + k];
      const int b = t.face_vertices[t.face_begin[f] + (k + 1) % n];
      for (int i = t.vertex_face_begin[a]; i < t.vertex_face_begin[a + 1]; ++i) {
        const int g = t.vertex_faces[i];
        if (mask[g]) continue;
        const auto begin = t.face_vertices.begin() + t.face_begin[g];
        if (std::find(begin, begin + t.degree(g), b) == begin + t.degree(g)) continue;
        if (t.rest_geometry.normal[f].dot(t.rest_geometry.normal[g]) < min_cos) continue;
        mask[g] = 1;
        queue.push_back(g);
      }
    }
  }
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
