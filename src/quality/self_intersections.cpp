// Why CGAL: a deformed mesh that touches itself produces near-coplanar and near-degenerate
// triangle pairs, where floating-point triangle-triangle tests answer either way. CGAL's
// Polygon_mesh_processing::self_intersections uses exact predicates (the Epick kernel's
// filtered arithmetic falls back to exact numbers when the filter cannot decide) and an AABB
// box-intersection pass, so every reported pair truly intersects and none is missed, without
// hand-written intersection code. CGAL's headers are heavy, so only this file and
// cgal_deformation.cpp include them (the primo_quality library).

#include "self_intersections.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <string>

#include "primo/util/error.h"

namespace primo::quality {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using TriangleMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using TriangleFace = TriangleMesh::Face_index;

}  // namespace

SelfIntersections find_self_intersections(const Mesh& mesh) {
  TriangleMesh triangles;
  std::vector<TriangleMesh::Vertex_index> vertices;
  vertices.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const Vec3& p = mesh.point(v);
    vertices.push_back(triangles.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  }
  // The original face of every triangle, indexed by the triangle's index in `triangles`.
  std::vector<int> original_face;
  original_face.reserve(mesh.n_faces() * 2);
  std::vector<TriangleMesh::Vertex_index> corners;
  for (auto f : mesh.faces()) {
    corners.clear();
    for (auto v : f.vertices()) corners.push_back(vertices[size_t(v.idx())]);
    for (size_t k = 1; k + 1 < corners.size(); ++k) {
      const TriangleFace t = triangles.add_face(corners[0], corners[k], corners[k + 1]);
      // A valid polygon mesh always triangulates into a valid triangle mesh; a refusal means
      // the input was not the manifold mesh the loaders guarantee.
      if (t == TriangleMesh::null_face())
        throw Error("self-intersection test: face " + std::to_string(f.idx()) +
                    " could not be triangulated (non-manifold input)");
      original_face.push_back(f.idx());
    }
  }

  std::vector<std::pair<TriangleFace, TriangleFace>> triangle_pairs;
  CGAL::Polygon_mesh_processing::self_intersections(triangles, std::back_inserter(triangle_pairs));

  SelfIntersections result;
  for (const auto& [a, b] : triangle_pairs) {
    if (a == b) {  // how CGAL reports a degenerate triangle
      ++result.degenerate_triangles;
      continue;
    }
    const int f = original_face[size_t(a.idx())];
    const int g = original_face[size_t(b.idx())];
    if (f == g) continue;  // a fan of one non-planar face may fold onto itself; not a collision
    result.face_pairs.emplace_back(std::min(f, g), std::max(f, g));
  }
  std::sort(result.face_pairs.begin(), result.face_pairs.end());
  result.face_pairs.erase(std::unique(result.face_pairs.begin(), result.face_pairs.end()),
                          result.face_pairs.end());
  return result;
}

}  // namespace primo::quality
