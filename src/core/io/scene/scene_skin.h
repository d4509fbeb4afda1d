#pragma once
// Internal to the core library: the skin of a scene read through Assimp (its bones, their
// node hierarchy and the vertex weights), collected mesh by mesh as the scene is baked into one
// soup (mesh_import_assimp.cpp) and kept as MeshAttributes::skin.

#include <assimp/scene.h>

#include <Eigen/Dense>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "primo/mesh/mesh_attributes.h"

namespace primo::detail {

class SceneSkinCollector {
 public:
  SceneSkinCollector(const aiScene& scene, const std::string& path);

  // `mesh`, the mesh of `node` whose global transform is `transform`, after its vertices were
  // baked: Assimp's vertex v became soup vertex index_of[v]. Throws Error "<path>: cannot read:
  // ..." for a bone that names no node, an inverse bind matrix that is not finite, a weight that
  // is negative or not finite, or a vertex index out of the mesh.
  void add_mesh(const aiNode& node, const aiMesh& mesh, const Eigen::Matrix4d& transform,
                const std::vector<int>& index_of);

  // The skin of the `n_vertices` soup vertices (empty when no mesh had bones); what was kept
  // and changed goes to `said` ("the skin of 'Cylinder' (9 bones)", "3 vertices had more than
  // 4 weights: ...").
  MeshSkin finish(size_t n_vertices, std::vector<std::string>& said);

 private:
  using Influences = std::vector<std::pair<int, double>>;  // (joint id, weight)
  int joint_of(const aiNode& bone_node);
  void set_vertex(int vertex, Influences influences);

  const aiScene& scene_;
  const std::string& path_;
  // Joints in the order first seen, with their nodes and inverse bind matrices.
  std::map<const aiNode*, int> joint_ids_;
  std::vector<const aiNode*> joint_nodes_;
  std::vector<Eigen::Matrix4d> inverse_binds_;
  // Per soup vertex (grown as meshes come), its influences, largest first, renormalised.
  std::vector<Influences> vertex_influences_;
  std::vector<bool> weighed_;
  // Soup vertices of meshes without bones, with their node: they follow its nearest joint.
  std::vector<std::pair<const aiNode*, std::vector<int>>> rigid_meshes_;
  std::vector<std::pair<std::string, size_t>> skinned_meshes_;  // quoted node name, bones
  size_t over_four_ = 0, copies_differ_ = 0, joints_disagree_ = 0;
};

}  // namespace primo::detail
