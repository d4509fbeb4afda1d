#include "primo/model/prism_layer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "primo/util/error.h"
#include "primo/mesh/geometry.h"

namespace primo {

PatchCorners PrismLayer::corner_patch(int a, int b) const {
  return {corner_point[size_t(a)] - corner_offset[size_t(a)], corner_point[size_t(b)] - corner_offset[size_t(b)],
          corner_point[size_t(a)] + corner_offset[size_t(a)], corner_point[size_t(b)] + corner_offset[size_t(b)]};
}

PatchCorners PrismLayer::side_patch(int face, int k) const {
  const int begin = corner_begin[face];
  return corner_patch(begin + k, begin + (k + 1) % degree(face));
}

PatchModes PrismLayer::joint_side(const Joint& joint, int side) const {
  return patch_modes(corner_patch(joint.corner[side][0], joint.corner[side][1]));
}

namespace {

double factor_or_one(const std::vector<double>& factors, int face) {
  return factors.empty() ? 1.0 : factors[face];
}

void check_parameters(const Mesh& mesh, const PrismParameters& p) {
  if (!std::isfinite(p.height) || !std::isfinite(p.normal_blend) || !std::isfinite(p.width))
    throw Error("prism parameters must be finite");
  for (const auto* factors : {&p.face_height_factor, &p.face_width_factor}) {
    if (!factors->empty() && factors->size() != mesh.n_faces())
      throw Error("per-face prism factors must have one value per face");
    for (double f : *factors)
      if (!std::isfinite(f)) throw Error("per-face prism factors must be finite");
  }
}

}  // namespace

PrismLayer build_prism_layer(const Mesh& mesh, const PrismParameters& params, const MeshOrder* order) {
  check_parameters(mesh, params);
  // "face F, vertex V" in the numbering of the file the user has.
  auto corner_name = [&](int face, int vertex) {
    if (order) face = order->face_of[size_t(face)], vertex = order->vertex_of[size_t(vertex)];
    return "face " + std::to_string(face) + ", vertex " + std::to_string(vertex);
  };
  const FaceGeometry geometry = compute_face_geometry(mesh);
  const std::vector<Vec3> vertex_normal = compute_vertex_normals(mesh, geometry);

  PrismLayer layer;
  layer.mean_edge_length = mean_edge_length(mesh);
  layer.bounding_box_diagonal = bounding_box_diagonal(mesh);
  layer.n_vertices = int(mesh.n_vertices());
  layer.face_centroid = geometry.centroid;
  layer.face_area = geometry.area;

  // A vertex's height factor is the minimum over its incident faces, so that with blend 0
  // and width 1 both prisms of a joint share its corners at rest.
  const double unit_length = params.height_unit == HeightUnit::Diagonal
                                 ? layer.bounding_box_diagonal
                                 : layer.mean_edge_length;
  std::vector<double> vertex_height(mesh.n_vertices(), 1.0);
  for (auto v : mesh.vertices()) {
    double factor = std::numeric_limits<double>::infinity();
    for (auto f : v.faces()) factor = std::min(factor, factor_or_one(params.face_height_factor, f.idx()));
    if (std::isfinite(factor)) vertex_height[v.idx()] = factor;
    vertex_height[v.idx()] *= params.height * unit_length;
  }

  const double beta = params.normal_blend;
  layer.corner_begin.reserve(mesh.n_faces() + 1);
  layer.corner_begin.push_back(0);
  // A corner per halfedge that has a face: reserved, so that a million faces' corners are not
  // copied through every doubling.
  const size_t corners = mesh.n_halfedges();
  layer.corner_vertex.reserve(corners);
  layer.corner_point.reserve(corners);
  layer.corner_offset.reserve(corners);
  for (auto f : mesh.faces()) {
    const int i = f.idx();
    const Vec3& c = geometry.centroid[i];
    const double width = params.width * factor_or_one(params.face_width_factor, i);
    for (auto v : f.vertices()) {
      const Vec3 blended = (1.0 - beta) * vertex_normal[v.idx()] + beta * geometry.normal[i];
      const double len = blended.norm();
      if (!std::isfinite(len))
        throw Error(corner_name(i, v.idx()) +
                    ": the blended extrusion direction is not finite (normal_blend " +
                    std::to_string(beta) + " is too large)");
      if (!(len > 0.0))
        throw Error(corner_name(i, v.idx()) +
                    ": the blended extrusion direction has zero length (normal_blend " +
                    std::to_string(beta) + ")");
      layer.corner_vertex.push_back(v.idx());
      // At width 1 the vertex itself, not c + (p - c), which rounds: a prism at rest then puts
      // its corner exactly on the file's coordinates.
      layer.corner_point.push_back(width == 1.0 ? mesh.point(v) : Vec3(c + width * (mesh.point(v) - c)));
      layer.corner_offset.push_back(vertex_height[v.idx()] / len * blended);
      // Products of finite settings can still overflow (a height or width of 1e300).
      if (!layer.corner_point.back().allFinite() || !layer.corner_offset.back().allFinite())
        throw Error(corner_name(i, v.idx()) +
                    ": the prism corner is not finite (prism height or width too large)");
    }
    layer.corner_begin.push_back(int(layer.corner_vertex.size()));
  }

  layer.vertex_corner_begin.assign(size_t(layer.n_vertices) + 1, 0);
  for (int v : layer.corner_vertex) ++layer.vertex_corner_begin[size_t(v) + 1];
  for (int v = 0; v < layer.n_vertices; ++v)
    layer.vertex_corner_begin[size_t(v) + 1] += layer.vertex_corner_begin[size_t(v)];
  layer.vertex_corners.resize(layer.corner_vertex.size());
  {
    std::vector<int> fill(layer.vertex_corner_begin.begin(), layer.vertex_corner_begin.end() - 1);
    for (int k = 0; k < int(layer.corner_vertex.size()); ++k)
      layer.vertex_corners[size_t(fill[size_t(layer.corner_vertex[size_t(k)])]++)] = k;
  }

  // Corner position of vertex `v` within face `f`.
  auto corner_of = [&](int f, int v) {
    for (int k = layer.corner_begin[f]; k < layer.corner_begin[f + 1]; ++k)
      if (layer.corner_vertex[k] == v) return k - layer.corner_begin[f];
    return -1;
  };

  layer.joints.reserve(mesh.n_edges());  // one per interior edge
  for (auto e : mesh.edges()) {
    if (e.is_boundary()) continue;
    auto h = e.h0();
    const int fi = h.face().idx(), fj = h.opp().face().idx();
    const int a = h.from().idx(), b = h.to().idx();
    Joint joint;
    joint.face[0] = fi;
    joint.face[1] = fj;
    joint.vertex[0] = a;
    joint.vertex[1] = b;
    const double length = (mesh.point(h.to()) - mesh.point(h.from())).norm();
    joint.weight = length * length / (geometry.area[fi] + geometry.area[fj]);
    for (int s = 0; s < 2; ++s) {
      const int f = joint.face[s];
      joint.corner[s][0] = layer.corner_begin[f] + corner_of(f, a);
      joint.corner[s][1] = layer.corner_begin[f] + corner_of(f, b);
    }
    layer.joints.push_back(joint);
  }
  return layer;
}

}  // namespace primo
