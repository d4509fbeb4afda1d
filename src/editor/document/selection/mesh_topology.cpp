#include "mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "primo/util/parallel.h"

namespace primo::editor {

MeshTopology build_topology(const Mesh& mesh) {
  MeshTopology t;
  t.n_vertices = int(mesh.n_vertices());
  t.n_faces = int(mesh.n_faces());
  t.face_begin.reserve(t.n_faces + 1);
  t.face_begin.push_back(0);
  for (auto f : mesh.faces()) {
    for (auto v : f.vertices()) t.face_vertices.push_back(v.idx());
    t.face_begin.push_back(int(t.face_vertices.size()));
  }

  // 1. Fan triangles and polygon edges (each undirected edge once: the lower index first).
  std::vector<std::pair<int, int>> edge_list;
  for (int f = 0; f < t.n_faces; ++f) {
    const int b = t.face_begin[f], n = t.degree(f);
    for (int k = 1; k + 1 < n; ++k) {
      t.triangles.insert(t.triangles.end(),
                         {unsigned(t.face_vertices[b]), unsigned(t.face_vertices[b + k]),
                          unsigned(t.face_vertices[b + k + 1])});
      t.triangle_face.push_back(f);
    }
    for (int k = 0; k < n; ++k) {
      int a = t.face_vertices[b + k], c = t.face_vertices[b + (k + 1) % n];
      edge_list.emplace_back(std::min(a, c), std::max(a, c));
    }
  }
  std::sort(edge_list.begin(), edge_list.end());
  edge_list.erase(std::unique(edge_list.begin(), edge_list.end()), edge_list.end());
  t.edges.reserve(2 * edge_list.size());
  for (const auto& [a, c] : edge_list) t.edges.insert(t.edges.end(), {unsigned(a), unsigned(c)});

  // 2. Vertex -> faces (CSR by counting).
  t.vertex_face_begin.assign(t.n_vertices + 1, 0);
  for (int v : t.face_vertices) ++t.vertex_face_begin[v + 1];
  for (int v = 0; v < t.n_vertices; ++v) t.vertex_face_begin[v + 1] += t.vertex_face_begin[v];
  t.vertex_faces.resize(t.face_vertices.size());
  std::vector<int> fill(t.vertex_face_begin.begin(), t.vertex_face_begin.end() - 1);
  for (int f = 0; f < t.n_faces; ++f)
    for (int k = t.face_begin[f]; k < t.face_begin[f + 1]; ++k)
      t.vertex_faces[fill[t.face_vertices[k]]++] = f;

  // 3. Rest geometry.
  t.rest_points.reserve(t.n_vertices);
  for (auto v : mesh.vertices()) t.rest_points.push_back(mesh.point(v));
  t.rest_geometry = compute_face_geometry(mesh);
  if (!t.rest_points.empty()) {
    t.bbox_min = t.bbox_max = t.rest_points.front();
    for (const Vec3& p : t.rest_points) {
      t.bbox_min = t.bbox_min.cwiseMin(p);
      t.bbox_max = t.bbox_max.cwiseMax(p);
    }
  }
  t.bbox_diagonal = (t.bbox_max - t.bbox_min).norm();
  return t;
}

Vec3 face_centroid(const MeshTopology& t, const std::vector<Vec3>& points, int f) {
  Vec3 c = Vec3::Zero();
  for (int k = t.face_begin[f]; k < t.face_begin[f + 1]; ++k) c += points[t.face_vertices[k]];
  return c / double(t.degree(f));
}

Vec3 face_vector_area(const MeshTopology& t, const std::vector<Vec3>& points, int f,
                      const Vec3& centroid) {
  const int b = t.face_begin[f], n = t.degree(f);
  Vec3 a = Vec3::Zero();
  for (int k = 0; k < n; ++k)
    a += (points[t.face_vertices[b + k]] - centroid)
             .cross(points[t.face_vertices[b + (k + 1) % n]] - centroid);
  return 0.5 * a;
}

void compute_vertex_normals(const MeshTopology& topology, const std::vector<Vec3>& points,
                            std::vector<float>& normals) {
  // Face areas, then each vertex's sum over its faces in face order: in parallel, with the
  // sums of a serial scatter over the faces.
  std::vector<Vec3> area(size_t(topology.n_faces));
  parallel_chunks(area.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (int f = int(begin); f < int(end); ++f)
      area[size_t(f)] = face_vector_area(topology, points, f, face_centroid(topology, points, f));
  });
  normals.resize(3 * size_t(topology.n_vertices));
  parallel_chunks(size_t(topology.n_vertices), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      Vec3 sum = Vec3::Zero();
      for (int i = topology.vertex_face_begin[v]; i < topology.vertex_face_begin[v + 1]; ++i)
        sum += area[size_t(topology.vertex_faces[size_t(i)])];
      const double len = sum.norm();
      const Vec3 n = len > 0 ? Vec3(sum / len) : Vec3::UnitZ();
      for (int k = 0; k < 3; ++k) normals[3 * v + size_t(k)] = float(n[k]);
    }
  });
}

std::vector<Vec3> face_centroids(const MeshTopology& topology, const std::vector<Vec3>& points) {
  std::vector<Vec3> c(topology.n_faces);
  for (int f = 0; f < topology.n_faces; ++f) c[f] = face_centroid(topology, points, f);
  return c;
}

Vec3 weighted_centroid(const MeshTopology& topology, const std::vector<Vec3>& points,
                       const std::vector<int>& faces) {
  Vec3 sum = Vec3::Zero();
  double area = 0.0;
  for (int f : faces) {
    sum += topology.rest_geometry.area[f] * face_centroid(topology, points, f);
    area += topology.rest_geometry.area[f];
  }
  return area > 0 ? Vec3(sum / area) : Vec3::Zero();
}

void bounding_sphere(const std::vector<Vec3>& points, Vec3& center, double& radius) {
  if (points.empty()) {
    center = Vec3::Zero();
    radius = 1.0;
    return;
  }
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  center = 0.5 * (lo + hi);
  // The farthest point from the box centre: tighter than half the box diagonal.
  double r2 = 0.0;
  for (const Vec3& p : points) r2 = std::max(r2, (p - center).squaredNorm());
  radius = std::max(std::sqrt(r2), 1e-9);
}

}  // namespace primo::editor
