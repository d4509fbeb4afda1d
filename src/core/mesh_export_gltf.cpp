// glTF 2.0 written by PriMo: the format is small enough that writing it here gives a file whose
// every field we choose and check (Assimp's exporter would need a scene built for it and
// triangulates through its own post-processing). Layout of the one buffer: positions (float32
// VEC3), normals (float32 VEC3), indices (uint32), each 4-byte aligned.

#include "mesh_export_gltf.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "primo/error.h"

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
std::string face_size_runs(const Mesh& mesh) {
  std::string out;
  int size = 0, count = 0;
  const auto flush = [&] {
    if (count == 0) return;
    if (!out.empty()) out += ' ';
    out += std::to_string(size) + "x" + std::to_string(count);
  };
  for (auto f : mesh.faces()) {
    const int n = int(f.valence());
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

}  // namespace

// The Newell normal of each face, so that n-gons count by their area.
std::vector<Vec3> vertex_normals(const Mesh& mesh) {
  std::vector<Vec3> normals(mesh.n_vertices(), Vec3::Zero());
  std::vector<Vec3> corners;
  for (auto f : mesh.faces()) {
    corners.clear();
    for (auto v : f.vertices()) corners.push_back(mesh.point(v));
    Vec3 area = Vec3::Zero();
    for (size_t k = 0; k < corners.size(); ++k)
      area += corners[k].cross(corners[(k + 1) % corners.size()]);
    for (auto v : f.vertices()) normals[size_t(v.idx())] += area;
  }
  for (Vec3& n : normals) {
    const double length = n.norm();
    n = length > 0 && std::isfinite(length) ? Vec3(n / length) : Vec3(0, 0, 1);
  }
  return normals;
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
  for (auto v : mesh.vertices()) {
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

  // 3. GLB: a 12-byte header, the JSON chunk padded with spaces and the binary chunk padded
  // with zeros to 4 bytes.
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

std::string gltf_bytes(const Mesh& mesh, bool binary, const std::string& name,
                       const std::string& path) {
  return gltf_file_bytes(gltf_document(mesh, name, path), binary, path);
}

}  // namespace primo::detail
