#include "mesh_quality.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "primo/util/error.h"
#include "primo/mesh/geometry.h"
#include "self_intersections.h"

namespace primo::quality {
namespace {

double degrees(double radians) { return radians * 180.0 / M_PI; }

// The angle between two unit vectors, accurate near 0 and near 180 degrees (acos is not).
double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Root mean square and maximum of absolute values.
struct Spread {
  double sum_of_squares = 0.0;
  double max = 0.0;
  int count = 0;
  void add(double value) {
    sum_of_squares += value * value;
    max = std::max(max, std::abs(value));
    ++count;
  }
  double rms() const { return count > 0 ? std::sqrt(sum_of_squares / count) : 0.0; }
};

double percent_change(double rest, double deformed) {
  return 100.0 * (deformed - rest) / std::abs(rest);
}

// Every boundary loop as its boundary halfedges in order. A boundary halfedge runs the way the
// missing face would, so a cap that follows it is oriented like the rest of the surface.
std::vector<std::vector<OpenMesh::SmartHalfedgeHandle>> boundary_loops(const Mesh& mesh) {
  std::vector<bool> seen(mesh.n_halfedges(), false);
  std::vector<std::vector<OpenMesh::SmartHalfedgeHandle>> loops;
  for (auto h : mesh.halfedges()) {
    if (!h.is_boundary() || seen[size_t(h.idx())]) continue;
    loops.emplace_back();
    for (auto g = h; !seen[size_t(g.idx())]; g = g.next()) {
      seen[size_t(g.idx())] = true;
      loops.back().push_back(g);
    }
  }
  return loops;
}

}  // namespace

double capped_volume(const Mesh& mesh) {
  // A polygon fanned about a point c encloses with the origin sum_k det(c, p_k, p_k+1) / 6
  // = c . (sum_k p_k x p_k+1) / 6 = c . a / 3, a its Newell vector area (the sum does not depend
  // on the point Newell's formula is taken about). Faces: about their centroids.
  const FaceGeometry faces = compute_face_geometry(mesh);
  double volume = 0.0;
  for (size_t f = 0; f < faces.centroid.size(); ++f)
    volume += faces.centroid[f].dot(faces.vector_area[f]) / 3.0;
  // Caps: about each loop's vertex centroid.
  for (const auto& loop : boundary_loops(mesh)) {
    Vec3 centroid = Vec3::Zero();
    Vec3 vector_area = Vec3::Zero();
    for (auto h : loop) {
      centroid += mesh.point(h.from());
      vector_area += 0.5 * mesh.point(h.from()).cross(mesh.point(h.to()));
    }
    centroid /= double(loop.size());
    volume += centroid.dot(vector_area) / 3.0;
  }
  return volume;
}

void check_same_connectivity(const Mesh& rest, const Mesh& deformed, const std::string& rest_name,
                             const std::string& deformed_name) {
  const auto counts = [](const Mesh& m) {
    return std::to_string(m.n_vertices()) + " vertices and " + std::to_string(m.n_faces()) +
           " faces";
  };
  if (rest.n_vertices() != deformed.n_vertices() || rest.n_faces() != deformed.n_faces())
    throw Error(deformed_name + ": has " + counts(deformed) + " but " + rest_name + " has " +
                counts(rest) + "; the meshes must have the same connectivity");
  for (auto f : rest.faces()) {
    const auto g = deformed.face_handle(unsigned(f.idx()));
    std::vector<int> a, b;
    for (auto v : f.vertices()) a.push_back(v.idx());
    for (auto v : deformed.fv_range(g)) b.push_back(v.idx());
    if (a != b)
      throw Error(deformed_name + ": face " + std::to_string(f.idx()) +
                  " has other corners than in " + rest_name +
                  "; the meshes must have the same connectivity");
  }
}

QualityMetrics measure_quality(const Mesh& rest, const Mesh& deformed,
                               const std::string& rest_name, const std::string& deformed_name) {
  check_same_connectivity(rest, deformed, rest_name, deformed_name);
  QualityMetrics m;
  m.vertices = int(rest.n_vertices());
  m.faces = int(rest.n_faces());
  m.boundary_loops = int(boundary_loops(rest).size());

  m.rest_volume = capped_volume(rest);
  m.deformed_volume = capped_volume(deformed);
  // A flat or nearly flat rest shape has no volume to compare against (relative to the cube
  // of its size, below rounding of the volume sum).
  const double diagonal = bounding_box_diagonal(rest);
  if (std::abs(m.rest_volume) > 1e-12 * diagonal * diagonal * diagonal)
    m.volume_change_percent = percent_change(m.rest_volume, m.deformed_volume);

  const FaceGeometry rest_faces = compute_face_geometry(rest);
  const FaceGeometry deformed_faces = compute_face_geometry(deformed);
  for (double a : rest_faces.area) m.rest_area += a;
  for (double a : deformed_faces.area) m.deformed_area += a;
  m.area_change_percent = percent_change(m.rest_area, m.deformed_area);

  Spread dihedral, edge;
  for (auto e : rest.edges()) {
    const auto a = e.v0(), b = e.v1();
    const double rest_length = (rest.point(a) - rest.point(b)).norm();
    const double deformed_length =
        (deformed.point(deformed.vertex_handle(unsigned(a.idx()))) -
         deformed.point(deformed.vertex_handle(unsigned(b.idx()))))
            .norm();
    edge.add(100.0 * (deformed_length - rest_length) / rest_length);

    if (e.is_boundary()) continue;
    const size_t f = size_t(e.h0().face().idx()), g = size_t(e.h1().face().idx());
    const double rest_angle = angle_between(rest_faces.normal[f], rest_faces.normal[g]);
    const double deformed_angle = angle_between(deformed_faces.normal[f], deformed_faces.normal[g]);
    dihedral.add(degrees(deformed_angle - rest_angle));
    if (degrees(deformed_angle) > kFoldOverDegrees) ++m.fold_overs;
  }
  m.interior_edges = dihedral.count;
  m.dihedral_change_rms_deg = dihedral.rms();
  m.dihedral_change_max_deg = dihedral.max;
  m.edge_change_rms_percent = edge.rms();
  m.edge_change_max_percent = edge.max;

  const SelfIntersections intersections = find_self_intersections(deformed);
  m.self_intersecting_pairs = int(intersections.face_pairs.size());
  m.degenerate_triangles = intersections.degenerate_triangles;
  return m;
}

}  // namespace primo::quality
