// Attributes as CBOR (nlohmann::json): the tables of indices and values travel as binary
// strings, so a million corners cost four megabytes, not a million JSON numbers.

#include "mesh_attributes_codec.h"

#include <cstring>
#include <nlohmann/json.hpp>

namespace primo::detail {
namespace {

using Json = nlohmann::json;

template <typename T>
Json binary_of(const std::vector<T>& values) {
  std::vector<uint8_t> bytes(values.size() * sizeof(T));
  if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return Json::binary(std::move(bytes));
}

template <typename T>
bool from_binary(const Json& json, std::vector<T>& values) {
  if (!json.is_binary()) return false;
  const auto& bytes = json.get_binary();
  if (bytes.size() % sizeof(T) != 0) return false;
  values.resize(bytes.size() / sizeof(T));
  if (!bytes.empty()) std::memcpy(values.data(), bytes.data(), bytes.size());
  return true;
}

template <int N>
Json corner_values_json(const std::vector<CornerValues<N>>& sets) {
  Json out = Json::array();
  for (const auto& set : sets)
    out.push_back({{"values", binary_of(set.values)}, {"corner", binary_of(set.corner)}});
  return out;
}

template <int N>
bool corner_values_from(const Json& json, std::vector<CornerValues<N>>& sets) {
  if (!json.is_array()) return false;
  sets.resize(json.size());
  for (size_t s = 0; s < json.size(); ++s)
    if (!json[s].is_object() || !json[s].contains("values") || !json[s].contains("corner") ||
        !from_binary(json[s]["values"], sets[s].values) ||
        !from_binary(json[s]["corner"], sets[s].corner))
      return false;
  return true;
}

Json texture_json(const MaterialTexture& texture) { return {texture.image, texture.texcoord}; }

void texture_from(const Json& json, MaterialTexture& texture) {
  texture.image = json.at(0).get<int>();
  texture.texcoord = json.at(1).get<int>();
}

Json skin_json(const MeshSkin& skin) {
  Json names = Json::array(), parents = Json::array();
  std::vector<std::array<double, 16>> rest, inverse_bind;
  for (const SkinJoint& joint : skin.joints) {
    names.push_back(joint.name);
    parents.push_back(joint.parent);
    rest.push_back(joint.rest);
    inverse_bind.push_back(joint.inverse_bind);
  }
  return {{"names", names},
          {"parents", parents},
          {"rest", binary_of(rest)},
          {"inverse_bind", binary_of(inverse_bind)},
          {"vertex_joints", binary_of(skin.vertex_joints)},
          {"vertex_weights", binary_of(skin.vertex_weights)}};
}

bool skin_from(const Json& json, MeshSkin& skin) {
  std::vector<std::array<double, 16>> rest, inverse_bind;
  const Json& names = json.at("names");
  const Json& parents = json.at("parents");
  if (!from_binary(json.at("rest"), rest) || !from_binary(json.at("inverse_bind"), inverse_bind) ||
      !from_binary(json.at("vertex_joints"), skin.vertex_joints) ||
      !from_binary(json.at("vertex_weights"), skin.vertex_weights) || !names.is_array() ||
      names.size() != rest.size() || parents.size() != rest.size() ||
      inverse_bind.size() != rest.size())
    return false;
  skin.joints.resize(rest.size());
  for (size_t j = 0; j < rest.size(); ++j)
    skin.joints[j] = {names[j].get<std::string>(), parents[j].get<int>(), rest[j], inverse_bind[j]};
  return true;
}

}  // namespace

std::string encode_attributes(const MeshAttributes& a) {
  Json materials = Json::array();
  for (const MeshMaterial& m : a.materials)
    materials.push_back(
        {{"name", m.name},
         {"base_color", m.base_color},
         {"metallic", m.metallic},
         {"roughness", m.roughness},
         {"emissive", m.emissive},
         {"double_sided", m.double_sided},
         {"alpha_mode", m.alpha_mode},
         {"alpha_cutoff", m.alpha_cutoff},
         {"textures",
          {texture_json(m.base_color_texture), texture_json(m.metallic_roughness_texture),
           texture_json(m.normal_texture), texture_json(m.occlusion_texture),
           texture_json(m.emissive_texture)}}});
  Json images = Json::array();
  for (const MeshImage& i : a.images)
    images.push_back(
        {{"name", i.name},
         {"uri", i.uri},
         {"folder", i.folder},
         {"mime_type", i.mime_type},
         {"bytes", Json::binary(std::vector<uint8_t>(i.bytes.begin(), i.bytes.end()))}});
  const Json json = {{"texcoords", corner_values_json(a.texcoords)},
                     {"colors", corner_values_json(a.colors)},
                     {"normal_corner", binary_of(a.normal_corner)},
                     {"n_normals", a.n_normals},
                     {"face_material", binary_of(a.face_material)},
                     {"materials", materials},
                     {"images", images},
                     {"skin", skin_json(a.skin)}};
  const std::vector<uint8_t> bytes = Json::to_cbor(json);
  return std::string(bytes.begin(), bytes.end());
}

bool decode_attributes(std::string_view bytes, MeshAttributes& a) {
  try {
    const Json json = Json::from_cbor(bytes.begin(), bytes.end());
    if (!corner_values_from(json.at("texcoords"), a.texcoords) ||
        !corner_values_from(json.at("colors"), a.colors) ||
        !from_binary(json.at("normal_corner"), a.normal_corner) ||
        !from_binary(json.at("face_material"), a.face_material))
      return false;
    a.n_normals = json.at("n_normals").get<int>();
    a.materials.clear();
    for (const Json& m : json.at("materials")) {
      MeshMaterial material;
      material.name = m.at("name").get<std::string>();
      material.base_color = m.at("base_color").get<std::array<double, 4>>();
      material.metallic = m.at("metallic").get<double>();
      material.roughness = m.at("roughness").get<double>();
      material.emissive = m.at("emissive").get<std::array<double, 3>>();
      material.double_sided = m.at("double_sided").get<bool>();
      material.alpha_mode = m.at("alpha_mode").get<std::string>();
      material.alpha_cutoff = m.at("alpha_cutoff").get<double>();
      const Json& t = m.at("textures");
      texture_from(t.at(0), material.base_color_texture);
      texture_from(t.at(1), material.metallic_roughness_texture);
      texture_from(t.at(2), material.normal_texture);
      texture_from(t.at(3), material.occlusion_texture);
      texture_from(t.at(4), material.emissive_texture);
      a.materials.push_back(std::move(material));
    }
    a.images.clear();
    for (const Json& i : json.at("images")) {
      MeshImage image;
      image.name = i.at("name").get<std::string>();
      image.uri = i.at("uri").get<std::string>();
      image.folder = i.at("folder").get<std::string>();
      image.mime_type = i.at("mime_type").get<std::string>();
      const auto& data = i.at("bytes").get_binary();
      image.bytes.assign(data.begin(), data.end());
      a.images.push_back(std::move(image));
    }
    return skin_from(json.at("skin"), a.skin);
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace primo::detail
