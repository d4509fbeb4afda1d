// The stand-in's collapse test against OpenMesh's own, on every halfedge, before and during
// a run of collapses (boundaries, corners, thin parts and deleted elements included).

#include <gtest/gtest.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <vector>

#include "document/collapse_check.h"
#include "primo/mesh/mesh_generators.h"

using namespace primo;
using namespace primo::editor;

namespace {

struct StatusTraits : OpenMesh::DefaultTraits {
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
  FaceAttributes(OpenMesh::Attributes::Status);
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<StatusTraits>;

TriMesh triangulated(const Mesh& mesh) {
  TriMesh tri;
  for (const auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    tri.add_vertex(TriMesh::Point(float(p[0]), float(p[1]), float(p[2])));
  }
  for (const auto f : mesh.faces()) {
    std::vector<TriMesh::VertexHandle> corners;
    for (const auto v : f.vertices()) corners.push_back(tri.vertex_handle(unsigned(v.idx())));
    for (size_t i = 1; i + 1 < corners.size(); ++i)
      tri.add_face(corners[0], corners[i], corners[i + 1]);
  }
  return tri;
}

// Every halfedge, OpenMesh's answer against ours; the number that may be collapsed.
int compare_all(TriMesh& mesh, const char* what) {
  int allowed = 0, differ = 0;
  for (const auto h : mesh.halfedges()) {
    const bool theirs = mesh.TriConnectivity::is_collapse_ok(h);
    if (theirs != collapse_keeps_manifold(mesh, h)) ++differ;
    allowed += theirs ? 1 : 0;
  }
  EXPECT_EQ(differ, 0) << what << ": halfedges where the two tests disagree";
  return allowed;
}

void check_through_collapses(TriMesh mesh, const char* what) {
  int allowed = compare_all(mesh, what);
  EXPECT_GT(allowed, 0) << what;
  bool some_refused = allowed < int(mesh.n_halfedges());
  // Collapse every fifth allowed halfedge in index order, rounds until a third of the vertices
  // are gone, comparing after each round: the mesh gets boundaries meeting, high valences and
  // deleted elements the first comparison did not see.
  const size_t target = mesh.n_vertices() * 2 / 3;
  for (int round = 0; round < 50; ++round) {
    size_t live = 0;
    for (const auto v : mesh.vertices()) live += mesh.status(v).deleted() ? 0 : 1;
    if (live <= target) break;
    int seen = 0;
    for (const auto h : mesh.halfedges())
      if (mesh.TriConnectivity::is_collapse_ok(h) && ++seen % 5 == 0) mesh.collapse(h);
    allowed = compare_all(mesh, what);
    some_refused = some_refused || allowed < int(mesh.n_halfedges());
  }
  EXPECT_TRUE(some_refused) << what << ": the comparison saw no refused collapse";
}

}  // namespace

TEST(EditorCollapseCheck, AgreesWithOpenMeshOnClosedOpenAndThinMeshes) {
  check_through_collapses(triangulated(make_cylinder(0.25, 2.0, 24, 30, FaceShape::Triangles)),
                          "open cylinder");
  check_through_collapses(triangulated(make_grid(1.0, 1.0, 12, 12, FaceShape::Quads)),
                          "sheet with corners");
  check_through_collapses(triangulated(make_bar(0.05, 2.0, 2, 60)), "thin closed bar");
}
