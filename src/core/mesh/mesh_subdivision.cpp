#include "primo/mesh/mesh_subdivision.h"

#include <vector>

#include "primo/util/error.h"
#include "primo/mesh/polygon_soup.h"

// After primo/mesh/mesh.h: the Eigen vector traits come first.
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

namespace primo {
namespace {

// OpenMesh's LoopT works on its own triangle-mesh kernel, so the mesh is copied over and back.
struct LoopTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using LoopMesh = OpenMesh::TriMesh_ArrayKernelT<LoopTraits>;

}  // namespace

Mesh loop_subdivide(const Mesh& mesh, int steps, const std::string& source) {
  LoopMesh tri;
  std::vector<LoopMesh::VertexHandle> vertices;
  vertices.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const Vec3& p = mesh.point(v);
    vertices.push_back(tri.add_vertex(LoopMesh::Point(p.x(), p.y(), p.z())));
  }
  std::vector<LoopMesh::VertexHandle> corners;
  for (auto f : mesh.faces()) {
    corners.clear();
    for (auto v : mesh.fv_range(f)) corners.push_back(vertices[size_t(v.idx())]);
    if (corners.size() != 3)
      throw Error(source + ": Loop subdivision needs a triangle mesh, but face " +
                  std::to_string(f.idx()) + " has " + std::to_string(corners.size()) + " sides");
    if (!tri.add_face(corners).is_valid())
      throw Error(source + ": OpenMesh refused face " + std::to_string(f.idx()) +
                  " while copying the mesh for subdivision");
  }
  OpenMesh::Subdivider::Uniform::LoopT<LoopMesh, double> loop;
  if (!loop.attach(tri) || !loop(size_t(steps)))
    throw Error(source + ": Loop subdivision failed");
  loop.detach();

  PolygonSoup soup;
  soup.points.reserve(tri.n_vertices());
  for (auto v : tri.vertices()) {
    const LoopMesh::Point& p = tri.point(v);
    soup.points.emplace_back(p[0], p[1], p[2]);
  }
  soup.faces.reserve(tri.n_faces());
  for (auto f : tri.faces()) {
    std::vector<int> face;
    for (auto v : tri.fv_range(f)) face.push_back(v.idx());
    soup.faces.push_back(std::move(face));
  }
  return mesh_from_soup(soup, source + " after " + std::to_string(steps) + " Loop steps");
}

}  // namespace primo
