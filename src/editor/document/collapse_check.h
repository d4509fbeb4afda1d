#pragma once
// Whether collapsing a halfedge keeps a triangle mesh manifold: OpenMesh's
// TriConnectivity::is_collapse_ok, the same test, compiled in this project. Debian's
// libOpenMeshCore is built with its assertions on, and there every status the test reads
// builds and compares a type name: about a third of the stand-in's decimation time went to it
// (perf, the koala's stand-in: 1.0 s before, 0.4 s after, the same stand-in).

#include <OpenMesh/Core/Mesh/Handles.hh>

namespace primo::editor {

// For a triangle mesh with vertex and edge status (OpenMesh's TriMesh_ArrayKernelT).
template <class Mesh>
bool collapse_keeps_manifold(const Mesh& mesh, OpenMesh::HalfedgeHandle v0v1) {
  using OpenMesh::HalfedgeHandle;
  using OpenMesh::VertexHandle;
  if (mesh.status(mesh.edge_handle(v0v1)).deleted()) return false;
  const HalfedgeHandle v1v0 = mesh.opposite_halfedge_handle(v0v1);
  const VertexHandle v0 = mesh.to_vertex_handle(v1v0), v1 = mesh.to_vertex_handle(v0v1);
  if (mesh.status(v0).deleted() || mesh.status(v1).deleted()) return false;
  // The corner across the edge on each side (none on a boundary side). A side whose two other
  // edges are both on the boundary would collapse into a dangling edge.
  auto corner_across = [&](HalfedgeHandle h, VertexHandle& corner) {
    if (mesh.is_boundary(h)) return true;
    const HalfedgeHandle h1 = mesh.next_halfedge_handle(h), h2 = mesh.next_halfedge_handle(h1);
    corner = mesh.to_vertex_handle(h1);
    return !(mesh.is_boundary(mesh.opposite_halfedge_handle(h1)) &&
             mesh.is_boundary(mesh.opposite_halfedge_handle(h2)));
  };
  VertexHandle vl, vr;
  if (!corner_across(v0v1, vl) || !corner_across(v1v0, vr) || vl == vr) return false;
  // The link condition: the two ends share no neighbour but the corners across the edge.
  for (const VertexHandle a : mesh.vv_range(v0))
    if (a != vl && a != vr)
      for (const VertexHandle b : mesh.vv_range(v1))
        if (a == b) return false;
  // An edge between two boundary vertices must itself be on the boundary.
  return !(mesh.is_boundary(v0) && mesh.is_boundary(v1) && !mesh.is_boundary(v0v1) &&
           !mesh.is_boundary(v1v0));
}

}  // namespace primo::editor
