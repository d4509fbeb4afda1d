// glTF 2.0 written by PriMo: the format is small enough that writing it here gives a file whose
// every field we choose and check (Assimp's exporter would need a scene built for it and
// triangulates through its own post-processing). Layout of the one buffer: positions (float32
// VEC3), normals (float32 VEC3), indices (uint32), each 4-byte aligned.

#include "mesh_export_gltf.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <limits>
#include <vector>

#include "primo/util/error.h"
#include "primo/io/input_files.h"
#include "relative_paths.h"

namespace primo::detail {
namespace {

using Json = GltfJson;

constexpr int kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;
constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kBinChunk = 0x004E4942;   // "BIN\0"

std::string base64(const std::string& bytes) {
  static const char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 |
                       uint32_t(uint8_t(bytes[i + 2]));
    out += kDigits[v >> 18];
    out += kDigits[(v >> 12) & 63];
    out += kDigits[(v >> 6) & 63];
    out += kDigits[v & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | (two ? uint32_t(uint8_t(bytes[i + 1])) << 8 : 0);
    out += kDigits[v >> 18];
    out += kDigits[(v >> 12) & 63];
    out += two ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

void append_u32(std::string& out, uint32_t value) {
  char bytes[4];
  std::memcpy(bytes, &value, 4);  // glTF is little-endian, as every machine PriMo builds on
  out.append(bytes, 4);
}

// "4x2928" or "3x10 4x5 3x1": the face sizes in file order, as runs.
std::string face_size_runs(const std::vector<int>& sizes) {
  std::string out;
  int size = 0, count = 0;
  const auto flush = [&] {
    if (count == 0) return;
    if (!out.empty()) out += ' ';
    out += std::to_string(size) + "x" + std::to_string(count);
  };
  for (const int n : sizes) {
    if (n != size) {
      flush();
      size = n;
      count = 0;
    }
    ++count;
  }
  flush();
  return out;
}

std::string face_size_runs(const Mesh& mesh) {
  std::vector<int> sizes;
  sizes.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) sizes.push_back(int(f.valence()));
  return face_size_runs(sizes);
}

// Appends vertex `v`'s position as float32 and widens the bounds glTF requires.
void append_float_position(const Mesh& mesh, Mesh::VertexHandle v, std::vector<float>& positions,
                           std::vector<float>& low, std::vector<float>& high,
                           const std::string& path) {
  const Vec3& p = mesh.point(v);
  for (int k = 0; k < 3; ++k) {
    const float value = float(p[k]);
    if (!std::isfinite(value))
      throw Error(path + ": cannot save: vertex " + std::to_string(v.idx()) +
                  " has a coordinate that float32 cannot hold (" + std::to_string(p[k]) + ")");
    positions.push_back(value);
    low[size_t(k)] = std::min(low[size_t(k)], value);
    high[size_t(k)] = std::max(high[size_t(k)], value);
  }
}

// GLB: a 12-byte header, the JSON chunk padded with spaces and the binary chunk padded with
// zeros to 4 bytes.
std::string glb_container(const Json& json, std::string buffer, const std::string& path) {
  std::string text = json.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  buffer.append((4 - buffer.size() % 4) % 4, '\0');
  if (12 + 8 + text.size() + 8 + buffer.size() > size_t(std::numeric_limits<uint32_t>::max()))
    throw Error(path + ": cannot save: the mesh is too large for a GLB file (4 GiB); use .gltf");
  std::string out;
  out.reserve(12 + 8 + text.size() + 8 + buffer.size());
  append_u32(out, kGlbMagic);
  append_u32(out, 2);
  append_u32(out, uint32_t(12 + 8 + text.size() + 8 + buffer.size()));
  append_u32(out, uint32_t(text.size()));
  append_u32(out, kJsonChunk);
  out += text;
  append_u32(out, uint32_t(buffer.size()));
  append_u32(out, kBinChunk);
  out += buffer;
  return out;
}

}  // namespace

// Area-weighted vertex normals (the Newell normal of each face, so n-gons count by their area),
// unit length as glTF requires; a vertex without faces gets +z.
std::vector<Vec3> vertex_normals(const Mesh& mesh) {
  // One normal slot per vertex: corner_normals then sums every face at each of its vertices.
  MeshAttributes per_vertex;
  per_vertex.n_normals = int(mesh.n_vertices());
  for (auto f : mesh.faces())
    for (auto v : f.vertices()) per_vertex.normal_corner.push_back(v.idx());
  return corner_normals(mesh, per_vertex);
}

GltfDocument gltf_document(const Mesh& mesh, const std::string& name, const std::string& path) {
  if (mesh.n_faces() == 0 || mesh.n_vertices() == 0)
    throw Error(path + ": cannot save: glTF cannot hold a mesh without faces");
  if (mesh.n_vertices() > size_t(std::numeric_limits<uint32_t>::max()))
    throw Error(path + ": cannot save: too many vertices for glTF's 32-bit indices");

  // 1. Positions as float32 (rounded to nearest) with their exact bounds, which glTF requires.
  const size_t n_vertices = mesh.n_vertices();
  std::vector<float> positions;
  positions.reserve(3 * n_vertices);
  std::vector<float> low(3, std::numeric_limits<float>::infinity());
  std::vector<float> high(3, -std::numeric_limits<float>::infinity());
  for (auto v : mesh.vertices()) append_float_position(mesh, v, positions, low, high, path);
  std::vector<float> normals;
  normals.reserve(3 * n_vertices);
  for (const Vec3& n : vertex_normals(mesh))
    for (int k = 0; k < 3; ++k) normals.push_back(float(n[k]));

  // 2. Every face as a fan around its first corner, in face order.
  std::vector<uint32_t> indices;
  std::vector<uint32_t> corners;
  for (auto f : mesh.faces()) {
    corners.clear();
    for (auto v : f.vertices()) corners.push_back(uint32_t(v.idx()));
    for (size_t k = 1; k + 1 < corners.size(); ++k) {
      indices.push_back(corners[0]);
      indices.push_back(corners[k]);
      indices.push_back(corners[k + 1]);
    }
  }

  std::string buffer;
  append_raw(buffer, positions);
  const size_t normals_offset = buffer.size();
  append_raw(buffer, normals);
  const size_t indices_offset = buffer.size();
  append_raw(buffer, indices);

  Json json;
  json["asset"] = {{"version", "2.0"}, {"generator", "PriMo"}};
  json["scene"] = 0;
  json["scenes"] = Json::array({{{"nodes", {0}}}});
  json["nodes"] = Json::array(
      {{{"name", name.empty() ? "mesh" : name},
        {"mesh", 0},
        {"extras", {{kFaceSizesKey, face_size_runs(mesh)}}}}});
  json["meshes"] = Json::array({{{"name", name.empty() ? "mesh" : name},
                                 {"primitives",
                                  {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}},
                                    {"indices", 2},
                                    {"mode", kTriangles}}}}}});
  json["accessors"] = Json::array({
      {{"bufferView", 0}, {"componentType", kFloat}, {"count", n_vertices}, {"type", "VEC3"},
       {"min", low}, {"max", high}},
      {{"bufferView", 1}, {"componentType", kFloat}, {"count", n_vertices}, {"type", "VEC3"}},
      {{"bufferView", 2}, {"componentType", kUnsignedInt}, {"count", indices.size()},
       {"type", "SCALAR"}},
  });
  json["bufferViews"] = Json::array({
      {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", normals_offset}, {"target", kArrayBuffer}},
      {{"buffer", 0}, {"byteOffset", normals_offset}, {"byteLength", indices_offset - normals_offset},
       {"target", kArrayBuffer}},
      {{"buffer", 0}, {"byteOffset", indices_offset}, {"byteLength", buffer.size() - indices_offset},
       {"target", kElementArrayBuffer}},
  });
  return {std::move(json), std::move(buffer)};
}

std::string gltf_file_bytes(GltfDocument document, bool binary, const std::string& path) {
  Json& json = document.json;
  std::string& buffer = document.buffer;
  Json buffer_json = {{"byteLength", buffer.size()}};
  if (!binary) buffer_json["uri"] = "data:application/octet-stream;base64," + base64(buffer);
  json["buffers"] = Json::array({buffer_json});

  if (!binary) return json.dump(1) + "\n";
  return glb_container(json, buffer, path);
}


namespace {

// A growing binary buffer with its views and accessors.
class BufferWriter {
 public:
  BufferWriter(Json& json) : json_(json) {
    json_["bufferViews"] = Json::array();
    json_["accessors"] = Json::array();
  }

  // A view of `bytes`, 4-byte aligned; returns its index.
  size_t view(const std::string& bytes, int target) {
    buffer_.append((4 - buffer_.size() % 4) % 4, '\0');
    Json view = {{"buffer", 0}, {"byteOffset", buffer_.size()}, {"byteLength", bytes.size()}};
    if (target) view["target"] = target;
    buffer_ += bytes;
    json_["bufferViews"].push_back(view);
    return json_["bufferViews"].size() - 1;
  }

  template <typename T>
  size_t accessor(const std::vector<T>& values, int component, const char* type, size_t width,
                  int target) {
    std::string bytes;
    append_raw(bytes, values);
    json_["accessors"].push_back({{"bufferView", view(bytes, target)},
                                  {"componentType", component},
                                  {"count", values.size() / width},
                                  {"type", type}});
    return json_["accessors"].size() - 1;
  }

  Json& last_accessor() { return json_["accessors"].back(); }
  std::string& buffer() { return buffer_; }

 private:
  Json& json_;
  std::string buffer_;
};

std::string mime_type_of(const MeshImage& image) {
  if (!image.mime_type.empty()) return image.mime_type;
  std::string ext = std::filesystem::path(image.uri).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png" ? "image/png" : "image/jpeg";
}

Json texture_json(const MaterialTexture& texture) {
  Json out = {{"index", texture.image}};
  if (texture.texcoord != 0) out["texCoord"] = texture.texcoord;
  return out;
}

Json material_json(const MeshMaterial& m) {
  Json pbr = {{"baseColorFactor", m.base_color},
              {"metallicFactor", m.metallic},
              {"roughnessFactor", m.roughness}};
  if (m.base_color_texture.image >= 0) pbr["baseColorTexture"] = texture_json(m.base_color_texture);
  if (m.metallic_roughness_texture.image >= 0)
    pbr["metallicRoughnessTexture"] = texture_json(m.metallic_roughness_texture);
  Json out = {{"name", m.name}, {"pbrMetallicRoughness", pbr}};
  if (m.normal_texture.image >= 0) out["normalTexture"] = texture_json(m.normal_texture);
  if (m.occlusion_texture.image >= 0) out["occlusionTexture"] = texture_json(m.occlusion_texture);
  if (m.emissive_texture.image >= 0) out["emissiveTexture"] = texture_json(m.emissive_texture);
  if (m.emissive != std::array<double, 3>{0, 0, 0}) out["emissiveFactor"] = m.emissive;
  const bool known_mode = m.alpha_mode == "MASK" || m.alpha_mode == "BLEND";
  if (known_mode) out["alphaMode"] = m.alpha_mode;
  if (m.alpha_mode == "MASK") out["alphaCutoff"] = m.alpha_cutoff;
  if (m.double_sided) out["doubleSided"] = true;
  return out;
}

constexpr int kUnsignedShort = 5123;

// JOINTS_0 and WEIGHTS_0 of every glTF vertex, from its mesh vertex. Float weights are made to
// sum to 1 as closely as float32 can: the largest takes what the others leave.
struct SkinVertices {
  std::vector<uint16_t> joints;
  std::vector<float> weights;
};

SkinVertices skin_vertices(const MeshSkin& skin, const GltfVertices& vertices,
                           const std::string& path) {
  if (skin.joints.size() > size_t(std::numeric_limits<uint16_t>::max()) + 1)
    throw Error(path + ": cannot save: the skin has " + std::to_string(skin.joints.size()) +
                " joints, more than glTF's 16-bit joint indices reach");
  SkinVertices out;
  out.joints.reserve(4 * vertices.mesh_vertex.size());
  out.weights.reserve(4 * vertices.mesh_vertex.size());
  for (const int v : vertices.mesh_vertex) {
    const auto& joints = skin.vertex_joints[size_t(v)];
    const auto& weights = skin.vertex_weights[size_t(v)];
    double others = 0;
    for (int k = 1; k < kSkinInfluences; ++k) others += double(float(weights[size_t(k)]));
    for (int k = 0; k < kSkinInfluences; ++k) {
      out.joints.push_back(uint16_t(joints[size_t(k)]));
      out.weights.push_back(k == 0 ? float(1.0 - others) : float(weights[size_t(k)]));
    }
  }
  return out;
}

// The skin's joints as nodes after the mesh nodes (the roots in the scene, each at its rest
// transform), and the skin the mesh nodes name, with its inverse bind matrices. The mesh nodes
// have no transform, which viewers ignore for a skinned mesh anyway.
void add_skin(Json& json, BufferWriter& out, const MeshSkin& skin, const std::string& path) {
  const size_t first = json["nodes"].size();
  std::vector<float> matrices;
  Json joints = Json::array();
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const SkinJoint& joint = skin.joints[j];
    Json node = {{"name", joint.name}, {"matrix", joint.rest}};
    json["nodes"].push_back(node);
    joints.push_back(first + j);
    if (joint.parent < 0)
      json["scenes"][0]["nodes"].push_back(first + j);
    else {
      Json& parent = json["nodes"][first + size_t(joint.parent)];
      if (!parent.contains("children")) parent["children"] = Json::array();
      parent["children"].push_back(first + j);
    }
    for (double x : joint.inverse_bind) {
      if (!std::isfinite(float(x)))
        throw Error(path + ": cannot save: the inverse bind matrix of joint " + std::to_string(j) +
                    " has a value that float32 cannot hold (" + std::to_string(x) + ")");
      matrices.push_back(float(x));
    }
  }
  const size_t inverse_binds = out.accessor(matrices, kFloat, "MAT4", 16, 0);
  json["skins"] = Json::array({{{"inverseBindMatrices", inverse_binds}, {"joints", joints}}});
}

}  // namespace

std::string gltf_bytes(const Mesh& mesh, bool binary, const std::string& name,
                       const std::string& path) {
  return gltf_file_bytes(gltf_document(mesh, name, path), binary, path);
}

bool has_gltf_attributes(const MeshAttributes& attributes) {
  return !attributes.texcoords.empty() || !attributes.colors.empty() || attributes.n_normals > 0 ||
         !attributes.face_material.empty() || !attributes.skin.empty();
}

GltfVertices gltf_vertices(const Mesh& mesh, const MeshAttributes& attributes) {
  GltfVertices out;
  if (!has_gltf_attributes(attributes)) {
    for (auto v : mesh.vertices()) out.mesh_vertex.push_back(v.idx()), out.normal_slot.push_back(-1);
    for (auto f : mesh.faces())
      for (auto v : f.vertices()) out.corner_vertex.push_back(uint32_t(v.idx()));
    return out;
  }
  std::map<std::vector<int>, uint32_t> vertex_of;
  std::vector<int> key;
  size_t c = 0;
  for (auto f : mesh.faces())
    for (auto v : f.vertices()) {
      const int slot = attributes.n_normals > 0 ? attributes.normal_corner[c] : -1;
      key.assign({v.idx(), slot});
      for (const auto& set : attributes.texcoords) key.push_back(set.corner[c]);
      for (const auto& set : attributes.colors) key.push_back(set.corner[c]);
      const auto [it, inserted] = vertex_of.emplace(key, uint32_t(out.mesh_vertex.size()));
      out.corner_vertex.push_back(it->second);
      if (inserted) {
        out.mesh_vertex.push_back(v.idx());
        out.normal_slot.push_back(slot);
        out.first_corner.push_back(c);
      }
      ++c;
    }
  return out;
}

std::vector<Vec3> gltf_vertex_normals(const Mesh& mesh, const MeshAttributes& attributes,
                                      const GltfVertices& vertices) {
  const std::vector<Vec3> slot_normals =
      attributes.n_normals > 0 ? corner_normals(mesh, attributes) : std::vector<Vec3>{};
  const std::vector<Vec3> smooth_normals = vertex_normals(mesh);
  std::vector<Vec3> out;
  out.reserve(vertices.mesh_vertex.size());
  for (size_t i = 0; i < vertices.mesh_vertex.size(); ++i) {
    const int slot = vertices.normal_slot[i];
    out.push_back(slot >= 0 ? slot_normals[size_t(slot)]
                            : smooth_normals[size_t(vertices.mesh_vertex[i])]);
  }
  return out;
}

GltfDocument gltf_document(const Mesh& mesh, const MeshAttributes& attributes, bool binary,
                           const std::string& name, const std::string& path) {
  if (!has_gltf_attributes(attributes)) return gltf_document(mesh, name, path);
  if (mesh.n_faces() == 0) throw Error(path + ": cannot save: glTF cannot hold a mesh without faces");

  // 1. One glTF vertex per distinct (vertex, UVs, colours, normal slot) of the corners.
  const GltfVertices vertices = gltf_vertices(mesh, attributes);
  const std::vector<uint32_t>& corner_vertex = vertices.corner_vertex;
  std::vector<float> positions, normals;
  std::vector<std::vector<float>> texcoords(attributes.texcoords.size()),
      colors(attributes.colors.size());
  std::vector<float> low(3, std::numeric_limits<float>::infinity());
  std::vector<float> high(3, -std::numeric_limits<float>::infinity());
  for (const Vec3& n : gltf_vertex_normals(mesh, attributes, vertices))
    for (int k = 0; k < 3; ++k) normals.push_back(float(n[k]));
  for (size_t i = 0; i < vertices.mesh_vertex.size(); ++i) {
    const size_t c = vertices.first_corner[i];
    append_float_position(mesh, mesh.vertex_handle(vertices.mesh_vertex[i]), positions, low, high,
                          path);
    for (size_t s = 0; s < texcoords.size(); ++s) {
      const int t = attributes.texcoords[s].corner[c];
      const auto uv = t >= 0 ? attributes.texcoords[s].values[size_t(t)] : std::array<double, 2>{0, 1};
      texcoords[s].push_back(float(uv[0]));
      texcoords[s].push_back(float(1.0 - uv[1]));  // glTF's v runs down
    }
    for (size_t s = 0; s < colors.size(); ++s) {
      const int k = attributes.colors[s].corner[c];
      const auto rgba = k >= 0 ? attributes.colors[s].values[size_t(k)] : std::array<double, 4>{1, 1, 1, 1};
      for (double x : rgba) colors[s].push_back(float(x));
    }
  }

  Json json;
  json["asset"] = {{"version", "2.0"}, {"generator", "PriMo"}};
  json["scene"] = 0;
  BufferWriter out(json);
  Json vertex_attributes;
  vertex_attributes["POSITION"] = out.accessor(positions, kFloat, "VEC3", 3, kArrayBuffer);
  out.last_accessor()["min"] = low;
  out.last_accessor()["max"] = high;
  vertex_attributes["NORMAL"] = out.accessor(normals, kFloat, "VEC3", 3, kArrayBuffer);
  for (size_t s = 0; s < texcoords.size(); ++s)
    vertex_attributes["TEXCOORD_" + std::to_string(s)] =
        out.accessor(texcoords[s], kFloat, "VEC2", 2, kArrayBuffer);
  for (size_t s = 0; s < colors.size(); ++s)
    vertex_attributes["COLOR_" + std::to_string(s)] =
        out.accessor(colors[s], kFloat, "VEC4", 4, kArrayBuffer);
  if (!attributes.skin.empty()) {
    const SkinVertices skin = skin_vertices(attributes.skin, vertices, path);
    vertex_attributes["JOINTS_0"] = out.accessor(skin.joints, kUnsignedShort, "VEC4", 4, kArrayBuffer);
    vertex_attributes["WEIGHTS_0"] = out.accessor(skin.weights, kFloat, "VEC4", 4, kArrayBuffer);
  }

  // 2. One primitive per material, in the order the faces first use them; fans as above. Each
  // is a mesh of its own node, whose extras give its face sizes and say that its vertex copies
  // are to be merged by position, so that PriMo reads the polygons back.
  const std::vector<int> first = first_corners(mesh);
  std::vector<int> groups;
  std::map<int, std::vector<uint32_t>> indices;
  std::map<int, std::vector<int>> sizes;
  for (auto f : mesh.faces()) {
    const size_t face = size_t(f.idx());
    const int material = face < attributes.face_material.size() ? attributes.face_material[face] : -1;
    if (!indices.count(material)) groups.push_back(material);
    std::vector<uint32_t>& fans = indices[material];
    const size_t begin = size_t(first[face]), size = size_t(first[face + 1]) - begin;
    sizes[material].push_back(int(size));
    for (size_t k = 1; k + 1 < size; ++k)
      fans.insert(fans.end(), {corner_vertex[begin], corner_vertex[begin + k],
                               corner_vertex[begin + k + 1]});
  }
  const std::string mesh_name = name.empty() ? "mesh" : name;
  json["meshes"] = Json::array();
  json["nodes"] = Json::array();
  json["scenes"] = Json::array({{{"nodes", Json::array()}}});
  for (int material : groups) {
    Json primitive = {{"attributes", vertex_attributes},
                      {"indices", out.accessor(indices[material], kUnsignedInt, "SCALAR", 1,
                                               kElementArrayBuffer)},
                      {"mode", kTriangles}};
    if (material >= 0) primitive["material"] = material;
    const std::string part =
        groups.size() == 1 || material < 0 ? mesh_name
                                           : mesh_name + "-" + attributes.materials[size_t(material)].name;
    json["scenes"][0]["nodes"].push_back(json["nodes"].size());
    json["nodes"].push_back({{"name", part},
                             {"mesh", json["meshes"].size()},
                             {"extras", {{kFaceSizesKey, face_size_runs(sizes[material])},
                                         {kVertexCopiesKey, "merge by position"}}}});
    if (!attributes.skin.empty()) json["nodes"].back()["skin"] = 0;
    json["meshes"].push_back({{"name", part}, {"primitives", Json::array({primitive})}});
  }
  if (!attributes.skin.empty()) add_skin(json, out, attributes.skin, path);

  // 3. Materials, a texture per image, and the images.
  if (!attributes.materials.empty()) {
    json["materials"] = Json::array();
    for (const MeshMaterial& m : attributes.materials) json["materials"].push_back(material_json(m));
  }
  if (!attributes.images.empty()) {
    json["textures"] = Json::array();
    json["images"] = Json::array();
    for (size_t i = 0; i < attributes.images.size(); ++i) {
      const MeshImage& image = attributes.images[i];
      json["textures"].push_back({{"source", i}});
      Json image_json;
      if (!image.name.empty()) image_json["name"] = image.name;
      const std::string file = (std::filesystem::path(image.folder) / image.uri).string();
      if (binary) {
        std::string bytes = image.bytes;
        if (bytes.empty()) try {
            bytes = read_input_file(file);
          } catch (const Error& e) {
            throw Error(path + ": cannot save: a GLB embeds its images, and " + e.what() +
                        "; save as .gltf to refer to it instead");
          }
        image_json["bufferView"] = out.view(bytes, 0);
        image_json["mimeType"] = mime_type_of(image);
      } else if (!image.bytes.empty()) {
        image_json["uri"] = "data:" + mime_type_of(image) + ";base64," + base64(image.bytes);
      } else {
        image_json["uri"] = path_from_folder(image.uri, image.folder, folder_of_file(path));
      }
      json["images"].push_back(image_json);
    }
  }
  std::string buffer = std::move(out.buffer());
  return GltfDocument{std::move(json), std::move(buffer)};
}

std::string gltf_bytes(const Mesh& mesh, const MeshAttributes& attributes, bool binary,
                       const std::string& name, const std::string& path) {
  return gltf_file_bytes(gltf_document(mesh, attributes, binary, name, path), binary, path);
}

}  // namespace primo::detail
