#include "face_ring.h"

#include <algorithm>

namespace primo::editor {
namespace {

// Position of vertex v in face f, or -1.
int corner_of(const MeshTopology& t, int f, int v) {
  for (int k = 0; k < t.degree(f); ++k)
    if (t.face_vertices[size_t(t.face_begin[f] + k)] == v) return k;
  return -1;
}

int vertex_at(const MeshTopology& t, int f, int k) {
  return t.face_vertices[size_t(t.face_begin[f] + (k % t.degree(f)))];
}

}  // namespace

std::vector<int> faces_across_edge(const MeshTopology& t, int a, int b) {
  std::vector<int> faces;
  if (a < 0 || b < 0 || a >= t.n_vertices || b >= t.n_vertices || a == b) return faces;
  for (int i = t.vertex_face_begin[size_t(a)]; i < t.vertex_face_begin[size_t(a) + 1]; ++i) {
    const int f = t.vertex_faces[size_t(i)];
    const int ka = corner_of(t, f, a);
    // Adjacent corners only: (a, b) is an edge of f, not a diagonal.
    if (vertex_at(t, f, ka + 1) == b || vertex_at(t, f, ka + t.degree(f) - 1) == b)
      faces.push_back(f);
  }
  return faces;
}

std::vector<int> face_ring(const MeshTopology& t, int a, int b) {
  const std::vector<int> start = faces_across_edge(t, a, b);
  std::vector<char> taken(size_t(t.n_faces), 0);
  std::vector<int> ring;
  for (int first : start) {
    // Walk away from edge (a, b) through `first`, then on across each opposite edge.
    int f = first, u = a, v = b;
    while (f >= 0 && t.degree(f) == 4 && !taken[size_t(f)]) {
      taken[size_t(f)] = 1;
      ring.push_back(f);
      const int ku = corner_of(t, f, u);
      // In a quad u-v-x-y (either orientation), the edge opposite (u, v) is (y, x).
      const bool forward = vertex_at(t, f, ku + 1) == v;
      const int next_u = vertex_at(t, f, forward ? ku + 3 : ku + 1);
      const int next_v = vertex_at(t, f, ku + 2);
      int next = -1;
      for (int g : faces_across_edge(t, next_u, next_v))
        if (g != f) next = g;
      f = next, u = next_u, v = next_v;
    }
  }
  std::sort(ring.begin(), ring.end());
  return ring;
}

FaceEdge nearest_edge_of_face(const MeshTopology& t, int f,
                              const std::vector<Eigen::Vector2d>& points,
                              const Eigen::Vector2d& point) {
  FaceEdge best;
  double best_d = 0.0;
  for (int k = 0; k < t.degree(f); ++k) {
    const int a = vertex_at(t, f, k), b = vertex_at(t, f, k + 1);
    const Eigen::Vector2d p = points[size_t(a)], d = points[size_t(b)] - p;
    const double s = d.squaredNorm() > 0 ? std::clamp((point - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    const double dist = (p + s * d - point).norm();
    if (best.a < 0 || dist < best_d) best = {a, b}, best_d = dist;
  }
  return best;
}

}  // namespace primo::editor
