#include "shown_edges.h"

namespace primo::editor {

std::vector<unsigned> shown_edges(const MeshTopology& t, const HiddenFaces& hidden) {
  if (count_hidden(hidden) == 0) return t.edges;
  // An edge is shown when a shown face has both its vertices as neighbouring corners.
  std::vector<unsigned> out;
  for (size_t e = 0; e + 1 < t.edges.size(); e += 2) {
    const int a = int(t.edges[e]), b = int(t.edges[e + 1]);
    bool shown = false;
    for (int i = t.vertex_face_begin[size_t(a)]; i < t.vertex_face_begin[size_t(a) + 1] && !shown; ++i) {
      const int f = t.vertex_faces[size_t(i)];
      if (is_hidden(hidden, f)) continue;
      const int begin = t.face_begin[size_t(f)], n = t.degree(f);
      for (int k = 0; k < n && !shown; ++k) {
        const int u = t.face_vertices[size_t(begin + k)], v = t.face_vertices[size_t(begin + (k + 1) % n)];
        shown = (u == a && v == b) || (u == b && v == a);
      }
    }
    if (shown) out.insert(out.end(), {unsigned(a), unsigned(b)});
  }
  return out;
}

}  // namespace primo::editor
