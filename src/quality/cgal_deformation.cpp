// CGAL's Surface_mesh_deformation as a peer of PriMo: the established ARAP implementations,
// run unchanged (default cotangent weights, Eigen's sparse LDLT), so the comparison measures
// the methods rather than a re-implementation of them. CGAL's headers stay in this file and
// self_intersections.cpp (the primo_quality library).

#include "cgal_deformation.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>

#include <string>

#include "primo/util/error.h"

namespace primo::quality {
namespace {

// Deformation needs constructions, not exact predicates: plain doubles, as CGAL's examples use.
using Kernel = CGAL::Simple_cartesian<double>;
using TriangleMesh = CGAL::Surface_mesh<Kernel::Point_3>;

template <CGAL::Deformation_algorithm_tag Tag>
std::vector<Vec3> run(TriangleMesh& mesh, const std::vector<int>& control_vertices,
                      const std::vector<Vec3>& targets, const PeerSettings& settings) {
  using Deformation = CGAL::Surface_mesh_deformation<TriangleMesh, CGAL::Default, CGAL::Default, Tag>;
  Deformation deformation(mesh);
  deformation.insert_roi_vertices(mesh.vertices().begin(), mesh.vertices().end());
  for (size_t i = 0; i < control_vertices.size(); ++i) {
    // Braces: with parentheses clang reads a function declaration (the most vexing parse).
    const TriangleMesh::Vertex_index v{TriangleMesh::size_type(control_vertices[i])};
    deformation.insert_control_vertex(v);
    const Vec3& t = targets[i];
    deformation.set_target_position(v, Kernel::Point_3(t.x(), t.y(), t.z()));
  }
  if (!deformation.preprocess())
    throw Error(std::string("CGAL ") +
                (Tag == CGAL::SRE_ARAP ? "SR-ARAP" : "ARAP") +
                ": preprocessing failed (the Laplacian system could not be factorized)");
  deformation.deform(settings.max_iterations, settings.tolerance);

  std::vector<Vec3> positions;
  positions.reserve(mesh.number_of_vertices());
  for (auto v : mesh.vertices()) {
    const Kernel::Point_3& p = mesh.point(v);
    positions.emplace_back(p.x(), p.y(), p.z());
  }
  return positions;
}

}  // namespace

const char* peer_method_name(PeerMethod method) {
  return method == PeerMethod::SrArap ? "SR-ARAP" : "ARAP";
}

PeerResult deform_with_cgal(const Mesh& triangle_mesh, const std::vector<int>& control_vertices,
                            const std::vector<Vec3>& targets, PeerMethod method,
                            const PeerSettings& settings) {
  if (control_vertices.size() != targets.size())
    throw Error("CGAL deformation: " + std::to_string(control_vertices.size()) +
                " control vertices but " + std::to_string(targets.size()) + " targets");
  TriangleMesh mesh;
  for (auto v : triangle_mesh.vertices()) {
    const Vec3& p = triangle_mesh.point(v);
    mesh.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
  }
  for (auto f : triangle_mesh.faces()) {
    std::vector<TriangleMesh::Vertex_index> corners;
    for (auto v : f.vertices()) corners.emplace_back(TriangleMesh::size_type(v.idx()));
    if (corners.size() != 3)
      throw Error("CGAL deformation needs a triangle mesh, but face " + std::to_string(f.idx()) +
                  " has " + std::to_string(corners.size()) + " corners");
    if (mesh.add_face(corners) == TriangleMesh::null_face())
      throw Error("CGAL deformation: face " + std::to_string(f.idx()) +
                  " was refused (non-manifold input)");
  }
  for (int v : control_vertices)
    if (v < 0 || v >= int(mesh.number_of_vertices()))
      throw Error("CGAL deformation: control vertex " + std::to_string(v) + " is out of range");

  PeerResult result;
  const Stopwatch stopwatch;
  result.positions = method == PeerMethod::SrArap
                         ? run<CGAL::SRE_ARAP>(mesh, control_vertices, targets, settings)
                         : run<CGAL::ORIGINAL_ARAP>(mesh, control_vertices, targets, settings);
  result.seconds = stopwatch.elapsed();
  return result;
}

}  // namespace primo::quality
