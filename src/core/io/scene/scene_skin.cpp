// Assimp's bones as one skin over the baked soup.
//
// - A bone names its node; the joints are those nodes, ordered as the node tree is walked (so a
//   parent comes first), each parented to its nearest ancestor that is a joint, with the
//   transforms of the nodes between folded into its rest transform.
// - Assimp's offset matrix takes the mesh's own coordinates to the bone's. The soup holds the
//   mesh with its node's global transform baked in, so the inverse bind matrix is the offset
//   times the inverse of that transform.
// - A vertex keeps its kSkinInfluences largest weights, renormalised to sum 1. Copies merged
//   into one vertex (split for UVs or normals) come from one control point and carry the same
//   weights; when they do not, the first copy's are kept and the note says how many differed.
// - glTF needs weights on every vertex of a skinned mesh: a vertex without any (a mesh without
//   bones, or weights that are all zero) follows the joint nearest above its mesh's node (the
//   first joint when there is none), which keeps a prop parented to a hand on the hand.

#include "scene_skin.h"

#include <algorithm>
#include <cmath>

#include "primo/util/error.h"

namespace primo::detail {
namespace {

// The tolerance under which two copies' weights, or two meshes' bind matrices, are the same.
constexpr double kSameWeight = 1e-6;
constexpr double kSameMatrix = 1e-6;

Eigen::Matrix4d matrix_of(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

std::array<double, 16> column_major(const Eigen::Matrix4d& m) {
  std::array<double, 16> out;
  Eigen::Map<Eigen::Matrix4d>(out.data()) = m;
  return out;
}

std::string quoted(const aiString& name) {
  std::string text = name.length ? std::string(name.C_Str()) : "(unnamed)";
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  if (text.size() > 40) text = text.substr(0, 40) + "...";
  return "'" + text + "'";
}

std::string counted(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

SceneSkinCollector::SceneSkinCollector(const aiScene& scene, const std::string& path)
    : scene_(scene), path_(path) {}

int SceneSkinCollector::joint_of(const aiNode& bone_node) {
  const auto [it, inserted] = joint_ids_.emplace(&bone_node, int(joint_nodes_.size()));
  if (inserted) {
    joint_nodes_.push_back(&bone_node);
    inverse_binds_.emplace_back(Eigen::Matrix4d::Zero());
  }
  return it->second;
}

void SceneSkinCollector::set_vertex(int vertex, Influences influences) {
  if (vertex_influences_.size() <= size_t(vertex)) {
    vertex_influences_.resize(size_t(vertex) + 1);
    weighed_.resize(size_t(vertex) + 1, false);
  }
  influences.erase(std::remove_if(influences.begin(), influences.end(),
                                  [](const auto& i) { return i.second == 0; }),
                   influences.end());
  if (influences.empty()) return;  // a copy without weights leaves the vertex to other copies
  std::sort(influences.begin(), influences.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  const bool too_many = influences.size() > size_t(kSkinInfluences);
  if (too_many) influences.resize(size_t(kSkinInfluences));
  double sum = 0;
  for (const auto& i : influences) sum += i.second;
  for (auto& i : influences) i.second /= sum;
  if (!weighed_[size_t(vertex)]) {
    weighed_[size_t(vertex)] = true;
    over_four_ += too_many;
    vertex_influences_[size_t(vertex)] = std::move(influences);
    return;
  }
  const Influences& first = vertex_influences_[size_t(vertex)];
  bool same = first.size() == influences.size();
  for (size_t k = 0; same && k < first.size(); ++k)
    same = first[k].first == influences[k].first &&
           std::abs(first[k].second - influences[k].second) <= kSameWeight;
  copies_differ_ += !same;
}

void SceneSkinCollector::add_mesh(const aiNode& node, const aiMesh& mesh,
                                  const Eigen::Matrix4d& transform,
                                  const std::vector<int>& index_of) {
  rigid_meshes_.emplace_back(&node, index_of);
  if (mesh.mNumBones == 0 || !mesh.mBones) return;
  const std::string where = "cannot read: the skin of mesh " + quoted(mesh.mName) + ": ";
  const Eigen::Matrix4d mesh_to_scene_inverse = transform.inverse();
  if (!mesh_to_scene_inverse.allFinite())
    throw Error(path_ + ": " + where + "its node " + quoted(node.mName) +
                "'s transform cannot be inverted");
  std::vector<Influences> influences(mesh.mNumVertices);
  for (unsigned b = 0; b < mesh.mNumBones; ++b) {
    const aiBone* bone = mesh.mBones[b];
    if (!bone) throw Error(path_ + ": " + where + "bone " + std::to_string(b) + " is missing");
    const aiNode* bone_node = scene_.mRootNode->FindNode(bone->mName);
    if (!bone_node)
      throw Error(path_ + ": " + where + "bone " + quoted(bone->mName) +
                  " names no node of the scene");
    const Eigen::Matrix4d offset = matrix_of(bone->mOffsetMatrix);
    if (!offset.allFinite())
      throw Error(path_ + ": " + where + "bone " + quoted(bone->mName) +
                  "'s inverse bind matrix is not finite");
    const int joint = joint_of(*bone_node);
    const Eigen::Matrix4d inverse_bind = offset * mesh_to_scene_inverse;
    Eigen::Matrix4d& known = inverse_binds_[size_t(joint)];
    if (known.isZero())
      known = inverse_bind;
    else if ((known - inverse_bind).cwiseAbs().maxCoeff() > kSameMatrix * (1 + known.norm()))
      ++joints_disagree_;
    if (bone->mNumWeights > 0 && !bone->mWeights)
      throw Error(path_ + ": " + where + "bone " + quoted(bone->mName) + " has no weights");
    for (unsigned w = 0; w < bone->mNumWeights; ++w) {
      const aiVertexWeight& weight = bone->mWeights[w];
      if (weight.mVertexId >= mesh.mNumVertices)
        throw Error(path_ + ": " + where + "bone " + quoted(bone->mName) + " weighs vertex " +
                    std::to_string(weight.mVertexId) + ", but the mesh has " +
                    std::to_string(mesh.mNumVertices) + " vertices");
      if (!std::isfinite(weight.mWeight) || weight.mWeight < 0)
        throw Error(path_ + ": " + where + "bone " + quoted(bone->mName) + " gives vertex " +
                    std::to_string(weight.mVertexId) + " the weight " +
                    std::to_string(weight.mWeight) + " (weights are finite and not negative)");
      Influences& list = influences[weight.mVertexId];
      const auto same_joint =
          std::find_if(list.begin(), list.end(), [&](const auto& i) { return i.first == joint; });
      if (same_joint != list.end())
        same_joint->second += weight.mWeight;
      else
        list.emplace_back(joint, double(weight.mWeight));
    }
  }
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) set_vertex(index_of[v], std::move(influences[v]));
  skinned_meshes_.emplace_back(quoted(node.mName), mesh.mNumBones);
}

MeshSkin SceneSkinCollector::finish(size_t n_vertices, std::vector<std::string>& said) {
  MeshSkin skin;
  if (joint_nodes_.empty()) return skin;

  // 1. Joints in the order of the node tree, each with its nearest joint ancestor.
  std::vector<int> index_of_id(joint_nodes_.size(), -1);
  std::vector<Eigen::Matrix4d> globals;
  struct Visit {
    const aiNode* node;
    Eigen::Matrix4d global;
    int parent_joint;
  };
  std::vector<Visit> stack{{scene_.mRootNode, matrix_of(scene_.mRootNode->mTransformation), -1}};
  while (!stack.empty()) {
    Visit visit = stack.back();
    stack.pop_back();
    const auto id = joint_ids_.find(visit.node);
    if (id != joint_ids_.end() && index_of_id[size_t(id->second)] < 0) {
      const int index = int(skin.joints.size());
      index_of_id[size_t(id->second)] = index;
      SkinJoint joint;
      joint.name = visit.node->mName.C_Str();
      joint.parent = visit.parent_joint;
      const Eigen::Matrix4d rest =
          visit.parent_joint < 0 ? visit.global
                                 : Eigen::Matrix4d(globals[size_t(visit.parent_joint)].inverse() *
                                                   visit.global);
      joint.rest = column_major(rest);
      joint.inverse_bind = column_major(inverse_binds_[size_t(id->second)]);
      skin.joints.push_back(std::move(joint));
      globals.push_back(visit.global);
      visit.parent_joint = index;
    }
    for (unsigned c = visit.node->mNumChildren; c-- > 0;)
      if (const aiNode* child = visit.node->mChildren[c])
        stack.push_back({child, visit.global * matrix_of(child->mTransformation),
                         visit.parent_joint});
  }

  // 2. The weights, with the joints renumbered; vertices without weights follow the joint
  // nearest above their mesh's node.
  skin.vertex_joints.assign(n_vertices, {0, 0, 0, 0});
  skin.vertex_weights.assign(n_vertices, {0, 0, 0, 0});
  vertex_influences_.resize(n_vertices);
  weighed_.resize(n_vertices, false);
  for (size_t v = 0; v < n_vertices; ++v)
    for (size_t k = 0; k < vertex_influences_[v].size(); ++k) {
      skin.vertex_joints[v][k] = index_of_id[size_t(vertex_influences_[v][k].first)];
      skin.vertex_weights[v][k] = vertex_influences_[v][k].second;
    }
  size_t unweighed = 0;
  for (const auto& [node, vertices] : rigid_meshes_) {
    int joint = 0;
    for (const aiNode* up = node; up; up = up->mParent)
      if (const auto id = joint_ids_.find(up); id != joint_ids_.end()) {
        joint = index_of_id[size_t(id->second)];
        break;
      }
    for (int v : vertices)
      if (!weighed_[size_t(v)]) {
        weighed_[size_t(v)] = true;
        skin.vertex_joints[size_t(v)] = {joint, 0, 0, 0};
        skin.vertex_weights[size_t(v)] = {1, 0, 0, 0};
        ++unweighed;
      }
  }

  // 3. What the note says.
  for (size_t s = 0; s < skinned_meshes_.size() && s < 3; ++s)
    said.push_back("kept the skin of " + skinned_meshes_[s].first + " (" +
                   counted(skinned_meshes_[s].second, "bone", "bones") + ")");
  if (skinned_meshes_.size() > 3)
    said.push_back("kept " + std::to_string(skinned_meshes_.size() - 3) + " more skins");
  if (over_four_)
    said.push_back(counted(over_four_, "vertex", "vertices") + " had more than " +
                   std::to_string(kSkinInfluences) + " bone weights: the " +
                   std::to_string(kSkinInfluences) + " largest kept, renormalised to sum 1");
  if (copies_differ_)
    said.push_back(counted(copies_differ_, "merged vertex copy", "merged vertex copies") +
                   " had other bone weights than the first copy: the first copy's kept");
  if (unweighed)
    said.push_back(counted(unweighed, "vertex", "vertices") +
                   " without bone weights follow the joint nearest above their mesh");
  if (joints_disagree_)
    said.push_back(counted(joints_disagree_, "bone binds", "bones bind") +
                   " two meshes differently: the first mesh's bind pose kept");
  return skin;
}

}  // namespace primo::detail
