#include "primo/mesh/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace primo {

FaceGeometry compute_face_geometry(const Mesh& mesh) {
  const size_t n = mesh.n_faces();
  FaceGeometry g;
  g.centroid.resize(n);
  g.vector_area.resize(n);
  g.area.resize(n);
  g.normal.resize(n);
  std::vector<Vec3> corners;
  for (auto f : mesh.faces()) {
    corners.clear();
    for (auto v : f.vertices()) corners.push_back(mesh.point(v));
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : corners) c += p;
    c /= double(corners.size());
    // Newell's formula about the centroid: exact for planar faces, the natural average
    // orientation for non-planar ones.
    Vec3 a = Vec3::Zero();
    for (size_t k = 0; k < corners.size(); ++k)
      a += (corners[k] - c).cross(corners[(k + 1) % corners.size()] - c);
    a *= 0.5;
    const int i = f.idx();
    g.centroid[i] = c;
    g.vector_area[i] = a;
    g.area[i] = a.norm();
    g.normal[i] = g.area[i] > 0 ? Vec3(a / g.area[i]) : Vec3::Zero();
  }
  return g;
}

std::vector<Vec3> compute_vertex_normals(const Mesh& mesh, const FaceGeometry& faces) {
  std::vector<Vec3> normals(mesh.n_vertices(), Vec3::Zero());
  std::vector<double> area_sum(mesh.n_vertices(), 0.0);
  for (auto f : mesh.faces())
    for (auto v : f.vertices()) {
      normals[v.idx()] += faces.vector_area[f.idx()];
      area_sum[v.idx()] += faces.area[f.idx()];
    }
  for (size_t v = 0; v < normals.size(); ++v) {
    // Vector areas that cancel up to rounding (a doubly covered sheet) leave a noise
    // direction; report those as zero so that callers can reject them.
    const double len = normals[v].norm();
    normals[v] = len > 1e-12 * area_sum[v] ? Vec3(normals[v] / len) : Vec3::Zero();
  }
  return normals;
}

double mean_edge_length(const Mesh& mesh) {
  if (mesh.n_edges() == 0) return 0.0;
  double sum = 0.0;
  for (auto e : mesh.edges())
    sum += (mesh.point(e.v0()) - mesh.point(e.v1())).norm();
  return sum / double(mesh.n_edges());
}

double largest_point_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.size() != b.size())
    throw std::invalid_argument("largest_point_distance: " + std::to_string(a.size()) +
                                " points against " + std::to_string(b.size()));
  double largest = 0.0;
  for (size_t i = 0; i < a.size(); ++i) largest = std::max(largest, (a[i] - b[i]).norm());
  return largest;
}

double bounding_box_diagonal(const Mesh& mesh) {
  // Of the vertices that faces use: one unused vertex far away (1e7) would inflate every
  // length scaled by the diagonal, the energy floor below which a solve stops included.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  bool any = false;
  for (auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    lo = lo.cwiseMin(mesh.point(v));
    hi = hi.cwiseMax(mesh.point(v));
    any = true;
  }
  return any ? (hi - lo).norm() : 0.0;
}

Vec3 area_weighted_centroid(const FaceGeometry& faces, const std::vector<int>& face_indices) {
  Vec3 sum = Vec3::Zero();
  double weight = 0.0;
  for (int f : face_indices) {
    sum += faces.area[f] * faces.centroid[f];
    weight += faces.area[f];
  }
  return weight > 0 ? Vec3(sum / weight) : sum;
}

}  // namespace primo
