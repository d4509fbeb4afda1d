// Face-corner attributes: the corner numbering, recomputed normals and the checks a reader and
// a writer make (primo/mesh/mesh_attributes.h).

#include "primo/mesh/mesh_attributes.h"

#include <cmath>
#include <string>

#include "primo/util/error.h"

namespace primo {

std::vector<int> first_corners(const Mesh& mesh) {
  std::vector<int> first;
  first.reserve(mesh.n_faces() + 1);
  int corner = 0;
  for (auto f : mesh.faces()) {
    first.push_back(corner);
    corner += int(f.valence());
  }
  first.push_back(corner);
  return first;
}

std::vector<Vec3> corner_normals(const Mesh& mesh, const MeshAttributes& attributes) {
  std::vector<Vec3> sums(size_t(std::max(attributes.n_normals, 0)), Vec3::Zero());
  // The face a slot last took its area from: a face that uses one slot at several corners
  // counts once.
  std::vector<int> last_face(sums.size(), -1);
  std::vector<Vec3> corners;
  size_t c = 0;
  for (auto f : mesh.faces()) {
    corners.clear();
    for (auto v : f.vertices()) corners.push_back(mesh.point(v));
    // The Newell vector: twice the area along the normal, for n-gons too.
    Vec3 area = Vec3::Zero();
    for (size_t k = 0; k < corners.size(); ++k)
      area += corners[k].cross(corners[(k + 1) % corners.size()]);
    for (size_t k = 0; k < corners.size(); ++k, ++c) {
      if (c >= attributes.normal_corner.size()) continue;
      const int slot = attributes.normal_corner[c];
      if (slot < 0 || size_t(slot) >= sums.size() || last_face[size_t(slot)] == f.idx()) continue;
      last_face[size_t(slot)] = f.idx();
      sums[size_t(slot)] += area;
    }
  }
  for (Vec3& n : sums) {
    const double length = n.norm();
    n = length > 0 && std::isfinite(length) ? Vec3(n / length) : Vec3(0, 0, 1);
  }
  return sums;
}

namespace {

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw Error(source + ": " + what);
}

template <int N>
void check_corner_values(const CornerValues<N>& set, const char* kind, size_t index,
                         size_t n_corners, const std::string& source) {
  const std::string name = std::string(kind) + " set " + std::to_string(index);
  if (set.corner.size() != n_corners)
    fail(source, name + " has " + std::to_string(set.corner.size()) + " corners, the mesh " +
                     std::to_string(n_corners));
  for (size_t c = 0; c < set.corner.size(); ++c)
    if (set.corner[c] < -1 || set.corner[c] >= int(set.values.size()))
      fail(source, name + ": corner " + std::to_string(c) + " refers to value " +
                       std::to_string(set.corner[c]) + " of " + std::to_string(set.values.size()));
  for (size_t v = 0; v < set.values.size(); ++v)
    for (double x : set.values[v])
      if (!std::isfinite(x)) fail(source, name + ": value " + std::to_string(v) + " is not finite");
}

bool all_finite(const std::array<double, 16>& matrix) {
  for (double x : matrix)
    if (!std::isfinite(x)) return false;
  return true;
}

// The sum of a vertex's weights may differ from 1 by rounding only (renormalised in double).
constexpr double kWeightSumTolerance = 1e-9;

void check_skin(const MeshSkin& skin, size_t n_vertices, const std::string& source) {
  if (skin.empty() && skin.vertex_joints.empty() && skin.vertex_weights.empty()) return;
  const int n_joints = int(skin.joints.size());
  if (skin.vertex_joints.size() != n_vertices || skin.vertex_weights.size() != n_vertices)
    fail(source, "the skin weighs " + std::to_string(skin.vertex_weights.size()) +
                     " vertices, the mesh has " + std::to_string(n_vertices));
  for (int j = 0; j < n_joints; ++j) {
    const SkinJoint& joint = skin.joints[size_t(j)];
    if (joint.parent < -1 || joint.parent >= j)
      fail(source, "skin joint " + std::to_string(j) + " has parent " +
                       std::to_string(joint.parent) + " (a parent comes before its children)");
    if (!all_finite(joint.inverse_bind))
      fail(source, "skin joint " + std::to_string(j) + ": its inverse bind matrix is not finite");
    if (!all_finite(joint.rest))
      fail(source, "skin joint " + std::to_string(j) + ": its rest transform is not finite");
  }
  for (size_t v = 0; v < n_vertices; ++v) {
    double sum = 0;
    for (int k = 0; k < kSkinInfluences; ++k) {
      const int joint = skin.vertex_joints[v][size_t(k)];
      const double weight = skin.vertex_weights[v][size_t(k)];
      if (joint < 0 || joint >= n_joints)
        fail(source, "vertex " + std::to_string(v) + " is weighed by joint " +
                         std::to_string(joint) + " of " + std::to_string(n_joints));
      if (!std::isfinite(weight) || weight < 0)
        fail(source, "vertex " + std::to_string(v) + " has skin weight " + std::to_string(weight) +
                         " (weights are finite and not negative)");
      sum += weight;
    }
    if (std::abs(sum - 1) > kWeightSumTolerance)
      fail(source, "the skin weights of vertex " + std::to_string(v) + " sum to " +
                       std::to_string(sum) + ", not 1");
  }
}

}  // namespace

void check_attributes(const Mesh& mesh, const MeshAttributes& attributes,
                      const std::string& source) {
  const size_t n_corners = size_t(first_corners(mesh).back());
  for (size_t s = 0; s < attributes.texcoords.size(); ++s)
    check_corner_values(attributes.texcoords[s], "texture coordinate", s, n_corners, source);
  for (size_t s = 0; s < attributes.colors.size(); ++s)
    check_corner_values(attributes.colors[s], "colour", s, n_corners, source);
  if (attributes.n_normals > 0 || !attributes.normal_corner.empty()) {
    if (attributes.normal_corner.size() != n_corners)
      fail(source, "the normals cover " + std::to_string(attributes.normal_corner.size()) +
                       " corners, the mesh has " + std::to_string(n_corners));
    for (size_t c = 0; c < n_corners; ++c)
      if (attributes.normal_corner[c] < -1 || attributes.normal_corner[c] >= attributes.n_normals)
        fail(source, "corner " + std::to_string(c) + " refers to normal " +
                         std::to_string(attributes.normal_corner[c]) + " of " +
                         std::to_string(attributes.n_normals));
  }
  if (!attributes.face_material.empty()) {
    if (attributes.face_material.size() != mesh.n_faces())
      fail(source, "materials are given for " + std::to_string(attributes.face_material.size()) +
                       " faces, the mesh has " + std::to_string(mesh.n_faces()));
    for (size_t f = 0; f < mesh.n_faces(); ++f)
      if (attributes.face_material[f] < -1 ||
          attributes.face_material[f] >= int(attributes.materials.size()))
        fail(source, "face " + std::to_string(f) + " refers to material " +
                         std::to_string(attributes.face_material[f]) + " of " +
                         std::to_string(attributes.materials.size()));
  }
  for (size_t m = 0; m < attributes.materials.size(); ++m) {
    const MeshMaterial& material = attributes.materials[m];
    for (const MaterialTexture* texture :
         {&material.base_color_texture, &material.metallic_roughness_texture,
          &material.normal_texture, &material.occlusion_texture, &material.emissive_texture})
      if (texture->image < -1 || texture->image >= int(attributes.images.size()) ||
          texture->texcoord < 0)
        fail(source, "material " + std::to_string(m) + " refers to image " +
                         std::to_string(texture->image) + " of " +
                         std::to_string(attributes.images.size()));
  }
  check_skin(attributes.skin, mesh.n_vertices(), source);
}

}  // namespace primo
