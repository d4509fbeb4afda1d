// A glTF asset's buffers, buffer views, accessors and primitives are checked before Assimp
// reads them (src/core/gltf_accessor_checks.h): each file below made Assimp allocate
// gigabytes, read overlapping or foreign bytes, or drop a face without a word; each is now
// refused in one line naming the rule, and sound assets (sparse ones included) still load.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "primo/error.h"
#include "primo/mesh_io.h"
#include "test_support.h"

namespace primo {
namespace {

using Json = nlohmann::json;

std::string pack_floats(const std::vector<float>& values, size_t pad = 0) {
  std::string out;
  for (float v : values) {
    out.append(reinterpret_cast<const char*>(&v), 4);
    if (pad && out.size() % (pad + 12) == 12) out.append(pad, '\0');
  }
  return out;
}

std::string pack_u16(const std::vector<uint16_t>& values) {
  std::string out(reinterpret_cast<const char*>(values.data()), values.size() * 2);
  while (out.size() % 4) out += '\0';
  return out;
}

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= uint8_t(bytes[i + 2]);
    out += digits[(n >> 18) & 63];
    out += digits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

// One triangle: positions (view 0, 36 bytes), indices (view 1, 8 bytes), in a data: URI.
Json triangle(const std::string& extra = "") {
  const std::string buffer = pack_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) + pack_u16({0, 1, 2}) + extra;
  Json g = Json::parse(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}]})");
  g["buffers"] = Json::array({{{"byteLength", buffer.size()},
                               {"uri", "data:application/octet-stream;base64," + base64(buffer)}}});
  return g;
}

// The triangle with its second vertex moved to (5, 5, 5) by a sparse accessor, on a
// position view of `stride` bytes (0: none).
Json sparse_triangle(int stride) {
  const std::string positions = stride == 16 ? pack_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, 4)
                                             : pack_floats({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string indices = pack_u16({0, 1, 2});
  const std::string sparse_index = pack_u16({1});
  const std::string sparse_value = pack_floats({5, 5, 5});
  const std::string buffer = positions + indices + sparse_index + sparse_value;
  Json g = triangle();
  const size_t p = positions.size(), i = p + indices.size(), v = i + sparse_index.size();
  g["buffers"][0] = {{"byteLength", buffer.size()},
                     {"uri", "data:application/octet-stream;base64," + base64(buffer)}};
  g["bufferViews"] = Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", p}},
                                  {{"buffer", 0}, {"byteOffset", p}, {"byteLength", 6}},
                                  {{"buffer", 0}, {"byteOffset", i}, {"byteLength", 2}},
                                  {{"buffer", 0}, {"byteOffset", v}, {"byteLength", 12}}});
  if (stride) g["bufferViews"][0]["byteStride"] = stride;
  g["accessors"][0]["sparse"] = {{"count", 1},
                                 {"indices", {{"bufferView", 2}, {"componentType", 5123}}},
                                 {"values", {{"bufferView", 3}}}};
  return g;
}

struct Bad {
  std::string name;
  Json gltf;
  std::string needle;
};

TEST(GltfAccessors, WhatAssimpWouldMisreadIsRefusedBeforeIt) {
  const std::string dir = test::temp_dir();
  std::vector<Bad> bad;
  Json g = triangle();
  g["accessors"][0]["count"] = 100000000;  // 648 bytes asking for 1.2 GB
  bad.push_back({"count.gltf", g, "accessor 0 reads 1200000000 bytes"});
  g = triangle();
  g["bufferViews"][0]["byteStride"] = 4;  // VEC3 floats 4 bytes apart overlap
  bad.push_back({"stride.gltf", g, "byteStride is 4 (its elements would overlap)"});
  g = triangle();
  g["bufferViews"][0]["byteStride"] = 14;
  bad.push_back({"stride14.gltf", g, "byteStride 14 is not a multiple of 4"});
  g = triangle();
  g["meshes"][0]["primitives"][0]["mode"] = 5;  // a strip of one index: 2^64 bytes
  g["accessors"][1]["count"] = 1;
  bad.push_back({"strip.gltf", g, "is a triangle strip of 1 vertices (at least 3)"});
  g = triangle();
  g["meshes"][0]["primitives"][0]["mode"] = 9;
  bad.push_back({"mode.gltf", g, "mode 9 is not one glTF has"});
  g = triangle();  // an index past the vertices: Assimp dropped the face
  g["buffers"][0]["uri"] = "data:application/octet-stream;base64," +
                           base64(pack_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) + pack_u16({0, 1, 7}));
  bad.push_back({"index.gltf", g, "mesh 0 primitive 0: index 2 is 7, past its 3 vertices"});
  g = triangle();
  g["bufferViews"][1]["byteLength"] = 600;
  bad.push_back({"view.gltf", g, "buffer view 1 (bytes 36 + 600) runs past buffer 0 (44 bytes)"});
  g = triangle();
  g["buffers"][0]["byteLength"] = 4000;
  bad.push_back({"buffer.gltf", g, "buffer 0 declares 4000 bytes but holds 44"});
  g = triangle();
  g["accessors"][1]["componentType"] = 5122;  // signed
  bad.push_back({"indices.gltf", g, "its indices are not unsigned SCALAR"});
  g = triangle();
  g["accessors"][0]["componentType"] = 1234;
  bad.push_back({"component.gltf", g, "componentType 1234 is not one glTF has"});
  g = triangle();  // Assimp reads every attribute for POSITION's count
  g["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"count", 1}, {"type", "VEC3"}});
  g["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
  bad.push_back({"attribute.gltf", g, "attribute NORMAL has 1 elements, POSITION 3"});
  g = triangle();
  g["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
  g["meshes"][0]["primitives"][0]["targets"] = Json::array({{{"POSITION", 2}}});
  bad.push_back({"target.gltf", g, "morph target 0 POSITION has 2 elements, POSITION 3"});
  // A sparse accessor on a strided view: Assimp 5.2 copied it as packed (garbage positions).
  bad.push_back({"sparse-strided.gltf", sparse_triangle(16),
                 "accessor 0 is sparse on a strided buffer view"});
  g = sparse_triangle(0);
  {  // a sparse index past the accessor's elements: Assimp wrote there
    Json& buffer = g["buffers"][0];
    std::string bytes = pack_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) + pack_u16({0, 1, 2}) +
                        pack_u16({9}) + pack_floats({5, 5, 5});
    buffer["uri"] = "data:application/octet-stream;base64," + base64(bytes);
  }
  bad.push_back({"sparse-index.gltf", g, "sparse part: index 0 is 9, past the accessor's 3 elements"});
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.name);
    test::expect_refused_from_file_and_bytes(dir + "/" + b.name, b.gltf.dump(), b.needle);
    try {
      load_mesh(dir + "/" + b.name);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("not a glTF file PriMo accepts ("), std::string::npos);
    }
  }
}

TEST(GltfAccessors, SoundAssetsStillLoad) {
  const std::string dir = test::temp_dir();
  test::write_text(dir + "/triangle.gltf", triangle().dump());
  EXPECT_EQ(load_mesh(dir + "/triangle.gltf").n_faces(), 1u);
  // A sparse accessor on a packed view (and on a view whose stride is its element) moves the
  // vertex it names.
  for (int stride : {0, 12}) {
    const std::string path = dir + "/sparse" + std::to_string(stride) + ".gltf";
    test::write_text(path, sparse_triangle(stride).dump());
    const Mesh mesh = load_mesh(path);
    ASSERT_EQ(mesh.n_vertices(), 3u);
    EXPECT_EQ(mesh.point(Mesh::VertexHandle(1)), Vec3(5, 5, 5));
  }
  // PriMo's own glTF and GLB, and the Khronos sample with its .bin beside it.
  const Mesh grid = load_mesh(test::source_path("fuzz/seeds/glb/quads.glb"));
  EXPECT_EQ(grid.n_faces(), 6u);
  EXPECT_EQ(load_mesh(test::source_path("fuzz/seeds/gltf/ico.gltf")).n_faces(), 80u);
  EXPECT_GT(load_mesh(test::source_path("assets/meshes/AnimatedMorphCube.gltf")).n_faces(), 0u);
}

}  // namespace
}  // namespace primo
