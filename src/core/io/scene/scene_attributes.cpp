// Assimp's attributes as PriMo keeps them. UV and colour values are shared by the corners that
// have the same value; normal slots by the corners of one vertex with the same normal as read
// (so the smooth and hard edges of the file survive the vertex merging); materials and images
// are taken when a face first uses them.

#include "scene_attributes.h"

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace primo::detail {
namespace {

std::string mime_type_of(const char* hint) {
  const std::string format(hint);
  if (format == "png") return "image/png";
  if (format == "jpg" || format == "jpeg") return "image/jpeg";
  return "";
}

}  // namespace

SceneAttributeCollector::SceneAttributeCollector(const aiScene& scene, const std::string& path)
    : scene_(scene), folder_(fs::path(path).parent_path().string()) {}

template <int N>
void SceneAttributeCollector::add_value(std::vector<CornerValues<N>>& sets,
                                        std::vector<std::map<std::array<double, N>, int>>& known,
                                        size_t set, const std::array<double, N>& value) {
  if (sets.size() <= set) {
    sets.resize(set + 1);
    known.resize(set + 1);
  }
  CornerValues<N>& values = sets[set];
  values.corner.resize(n_corners_, -1);  // corners of meshes without this set
  const auto [it, inserted] = known[set].emplace(value, int(values.values.size()));
  if (inserted) values.values.push_back(value);
  values.corner.push_back(it->second);
}

void SceneAttributeCollector::add_face(const aiMesh& mesh, const std::vector<unsigned>& ai_corners,
                                       const std::vector<int>& vertices) {
  for (size_t k = 0; k < ai_corners.size(); ++k) {
    const unsigned v = ai_corners[k];
    for (unsigned set = 0; set < AI_MAX_NUMBER_OF_TEXTURECOORDS; ++set)
      if (mesh.HasTextureCoords(set)) {
        const aiVector3D& uv = mesh.mTextureCoords[set][v];
        add_value<2>(out_.texcoords, known_texcoords_, set, {double(uv.x), double(uv.y)});
      }
    for (unsigned set = 0; set < AI_MAX_NUMBER_OF_COLOR_SETS; ++set)
      if (mesh.HasVertexColors(set)) {
        const aiColor4D& c = mesh.mColors[set][v];
        add_value<4>(out_.colors, known_colors_, set,
                     {double(c.r), double(c.g), double(c.b), double(c.a)});
      }
    out_.normal_corner.resize(n_corners_, -1);
    if (mesh.HasNormals()) {
      const aiVector3D& n = mesh.mNormals[v];
      const auto key = std::make_pair(vertices[k], std::array<float, 3>{n.x, n.y, n.z});
      const auto [it, inserted] = normal_slots_.emplace(key, out_.n_normals);
      if (inserted) ++out_.n_normals;
      out_.normal_corner.push_back(it->second);
    }
    ++n_corners_;
  }
  const int material = material_of(mesh.mMaterialIndex);
  out_.face_material.push_back(material);
  any_material_ = any_material_ || material >= 0;
}

int SceneAttributeCollector::image_of(const aiString& path) {
  const std::string uri(path.C_Str());
  const auto known = images_.find(uri);
  if (known != images_.end()) return known->second;
  MeshImage image;
  image.name = fs::path(uri).stem().string();
  // "*0" names an embedded texture; FBX embeds them under their file names.
  if (const aiTexture* embedded = scene_.GetEmbeddedTexture(uri.c_str())) {
    if (embedded->mHeight != 0 || !embedded->pcData) {
      ++raw_textures_;  // texels glTF cannot hold without an image encoder
      images_[uri] = -1;
      return -1;
    }
    image.name.clear();  // "*0" names no image
    image.mime_type = mime_type_of(embedded->achFormatHint);
    image.bytes.assign(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth);
    if (embedded->mFilename.length > 0)
      image.name = fs::path(embedded->mFilename.C_Str()).stem().string();
  } else {
    image.uri = uri;
    image.folder = folder_;
  }
  const int index = int(out_.images.size());
  out_.images.push_back(std::move(image));
  images_[uri] = index;
  return index;
}

int SceneAttributeCollector::material_of(unsigned ai_material) {
  if (ai_material >= scene_.mNumMaterials || !scene_.mMaterials[ai_material]) return -1;
  const auto known = materials_.find(ai_material);
  if (known != materials_.end()) return known->second;
  const aiMaterial& m = *scene_.mMaterials[ai_material];
  // Assimp adds a material of its own when a file has none: the file had no material to keep.
  if (m.GetName() == aiString(AI_DEFAULT_MATERIAL_NAME)) return materials_[ai_material] = -1;
  MeshMaterial material;
  material.name = m.GetName().C_Str();
  aiColor4D color;
  float value;
  if (m.Get(AI_MATKEY_BASE_COLOR, color) == aiReturn_SUCCESS) {
    material.base_color = {color.r, color.g, color.b, color.a};
  } else {
    // Phong (FBX, COLLADA): the diffuse colour, its opacity, and no metal.
    if (m.Get(AI_MATKEY_COLOR_DIFFUSE, color) == aiReturn_SUCCESS)
      material.base_color = {color.r, color.g, color.b, 1.0};
    if (m.Get(AI_MATKEY_OPACITY, value) == aiReturn_SUCCESS && value < 1) {
      material.base_color[3] = value;
      material.alpha_mode = "BLEND";
    }
    material.metallic = 0.0;
  }
  if (m.Get(AI_MATKEY_METALLIC_FACTOR, value) == aiReturn_SUCCESS) material.metallic = value;
  if (m.Get(AI_MATKEY_ROUGHNESS_FACTOR, value) == aiReturn_SUCCESS) material.roughness = value;
  if (m.Get(AI_MATKEY_COLOR_EMISSIVE, color) == aiReturn_SUCCESS)
    material.emissive = {color.r, color.g, color.b};
  int two_sided = 0;
  if (m.Get(AI_MATKEY_TWOSIDED, two_sided) == aiReturn_SUCCESS)
    material.double_sided = two_sided != 0;
  aiString alpha_mode;
  if (m.Get(AI_MATKEY_GLTF_ALPHAMODE, alpha_mode) == aiReturn_SUCCESS)
    material.alpha_mode = alpha_mode.C_Str();
  if (m.Get(AI_MATKEY_GLTF_ALPHACUTOFF, value) == aiReturn_SUCCESS) material.alpha_cutoff = value;

  const auto texture = [&](MaterialTexture& slot, std::initializer_list<aiTextureType> types) {
    for (aiTextureType type : types) {
      aiString path;
      if (m.GetTextureCount(type) == 0 || m.GetTexture(type, 0, &path) != aiReturn_SUCCESS)
        continue;
      slot.image = image_of(path);
      int set = 0;
      if (m.Get(AI_MATKEY_UVWSRC(type, 0), set) == aiReturn_SUCCESS && set >= 0)
        slot.texcoord = set;
      return;
    }
  };
  texture(material.base_color_texture, {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE});
  texture(material.metallic_roughness_texture, {aiTextureType_UNKNOWN});
  texture(material.normal_texture, {aiTextureType_NORMALS});
  texture(material.occlusion_texture, {aiTextureType_LIGHTMAP});
  texture(material.emissive_texture, {aiTextureType_EMISSIVE});

  const int index = int(out_.materials.size());
  out_.materials.push_back(std::move(material));
  materials_[ai_material] = index;
  return index;
}

MeshAttributes SceneAttributeCollector::finish(std::vector<std::string>& dropped) {
  for (auto& set : out_.texcoords) set.corner.resize(n_corners_, -1);
  for (auto& set : out_.colors) set.corner.resize(n_corners_, -1);
  if (out_.n_normals > 0)
    out_.normal_corner.resize(n_corners_, -1);
  else
    out_.normal_corner.clear();
  if (!any_material_) {
    out_.face_material.clear();
    out_.materials.clear();
  }
  if (raw_textures_ > 0)
    dropped.push_back(std::to_string(raw_textures_) + " uncompressed embedded texture" +
                      (raw_textures_ == 1 ? "" : "s"));
  return std::move(out_);
}

}  // namespace primo::detail
