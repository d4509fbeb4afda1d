#pragma once
// Internal to the core library: the face-corner attributes of a scene read through Assimp
// (UV sets, colour sets, normals, materials and their images), collected face by face as the
// scene is baked into one soup (mesh_import_assimp.cpp).

#include <assimp/scene.h>

#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "primo/mesh/mesh_attributes.h"

namespace primo::detail {

class SceneAttributeCollector {
 public:
  // `path` is the scene file: relative texture paths are found in its folder.
  SceneAttributeCollector(const aiScene& scene, const std::string& path);

  // One face of the soup, in soup order: `ai_corners` are its corners as indices into
  // `mesh`'s vertices, `vertices` the soup vertices they became.
  void add_face(const aiMesh& mesh, const std::vector<unsigned>& ai_corners,
                const std::vector<int>& vertices);

  // The attributes of the faces added; what could not be kept goes to `dropped` (e.g. "1
  // uncompressed embedded texture").
  MeshAttributes finish(std::vector<std::string>& dropped);

 private:
  int material_of(unsigned ai_material);
  int image_of(const aiString& path);
  template <int N>
  void add_value(std::vector<CornerValues<N>>& sets,
                 std::vector<std::map<std::array<double, N>, int>>& known, size_t set,
                 const std::array<double, N>& value);

  const aiScene& scene_;
  std::string folder_;
  MeshAttributes out_;
  size_t n_corners_ = 0;
  std::vector<std::map<std::array<double, 2>, int>> known_texcoords_;
  std::vector<std::map<std::array<double, 4>, int>> known_colors_;
  std::map<std::pair<int, std::array<float, 3>>, int> normal_slots_;
  std::unordered_map<unsigned, int> materials_;
  std::map<std::string, int> images_;
  size_t raw_textures_ = 0;
  bool any_material_ = false;
};

}  // namespace primo::detail
