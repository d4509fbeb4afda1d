// A glTF asset's buffers, buffer views, accessors, primitives, skins and animation samplers are
// checked before Assimp reads them (src/core/io/scene/checks/gltf_accessor_checks.h): each file
// below made Assimp 5.2 allocate gigabytes, crash, write or read past its arrays, read overlapping
// or foreign bytes, or drop a face without a word. Each is refused in one line naming the rule,
// whether its bytes come in a data: URI, a .glb's binary chunk or a .bin file beside the .gltf, and
// sound assets (sparse, skinned and animated ones, PriMo's own files) still load.

#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

namespace primo {
namespace {

using Json = nlohmann::json;

std::string pad4(std::string bytes, char with = '\0') {
  while (bytes.size() % 4) bytes += with;
  return bytes;
}

std::string floats(const std::vector<float>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * 4);
}

std::string u16s(const std::vector<uint16_t>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * 2);
}

std::string u32(uint32_t v) {
  std::string out;
  for (int k = 0; k < 4; ++k) out += char((v >> (8 * k)) & 0xFF);
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

// A glTF asset before it is written: its JSON without "buffers", and its one buffer's bytes.
struct Asset {
  Json json;
  std::string bin;
  std::optional<uint64_t> declared;  // the buffer's byteLength when not bin's size

  // `bytes` (padded to 4) as a new buffer view; its index.
  int add_view(const std::string& bytes) {
    json["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
    bin += pad4(bytes);
    return int(json["bufferViews"].size()) - 1;
  }
  int add_accessor(const Json& accessor) {
    json["accessors"].push_back(accessor);
    return int(json["accessors"].size()) - 1;
  }
  // Makes accessor `a` sparse: its elements `at` replaced by `values`.
  void make_sparse(int a, const std::vector<uint16_t>& at, const std::string& values) {
    json["accessors"][size_t(a)]["sparse"] = {
        {"count", at.size()},
        {"indices", {{"bufferView", add_view(u16s(at))}, {"componentType", 5123}}},
        {"values", {{"bufferView", add_view(values)}}}};
  }
  uint64_t byte_length() const { return declared ? *declared : bin.size(); }
};

// One triangle: positions (view 0: 36 bytes, or 3 x `stride`), indices 0 1 2 (view 1: 6 bytes).
Asset triangle(int stride = 0) {
  Asset a;
  a.json = Json::parse(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": []})");
  std::string positions;
  for (const auto& p : std::vector<std::vector<float>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})
    positions += floats(p) + std::string(stride ? size_t(stride) - 12 : 0, '\0');
  a.add_view(positions);
  if (stride) a.json["bufferViews"][0]["byteStride"] = stride;
  a.add_view(u16s({0, 1, 2}));
  return a;
}

// The asset as one .gltf, its buffer a base64 data: URI.
std::string as_gltf(const Asset& a) {
  Json json = a.json;
  json["buffers"] =
      Json::array({{{"byteLength", a.byte_length()},
                    {"uri", "data:application/octet-stream;base64," + base64(a.bin)}}});
  return json.dump();
}

// The asset as a .glb: its buffer the binary chunk (the buffer naming `uri` when given).
// `pad_json`: the JSON chunk padded to 4 bytes with spaces, as glTF requires (readers find the
// binary chunk after the padding).
std::string as_glb(const Asset& a, bool pad_json = true, const std::string& uri = "") {
  Json json = a.json;
  json["buffers"] = Json::array({{{"byteLength", a.byte_length()}}});
  if (!uri.empty()) json["buffers"][0]["uri"] = uri;
  const std::string text = pad_json ? pad4(json.dump(), ' ') : json.dump();
  const std::string bin = pad4(a.bin);
  const size_t padded_text = (text.size() + 3) / 4 * 4;
  return "glTF" + u32(2) + u32(uint32_t(12 + 8 + padded_text + 8 + bin.size())) +
         u32(uint32_t(text.size())) + u32(0x4E4F534A) + pad4(text, ' ') +
         u32(uint32_t(bin.size())) + u32(0x004E4942) + bin;
}

// The asset as `dir`/`name`.gltf with its buffer in `name`.bin beside it; the .gltf's path.
std::string write_with_bin(const Asset& a, const std::string& dir, const std::string& name) {
  Json json = a.json;
  json["buffers"] = Json::array({{{"byteLength", a.byte_length()}, {"uri", name + ".bin"}}});
  test::write_text(dir + "/" + name + ".bin", a.bin);
  test::write_text(dir + "/" + name + ".gltf", json.dump());
  return dir + "/" + name + ".gltf";
}

// Refused with `needle` from a .gltf (file and bytes), a .glb (file and bytes) and a .gltf with
// its .bin beside it (Assimp finds that file only beside a file).
void expect_refused_in_every_form(const Asset& a, const std::string& name,
                                  const std::string& needle) {
  const std::string dir = test::temp_dir();
  SCOPED_TRACE(name);
  test::expect_refused_from_file_and_bytes(dir + "/" + name + ".gltf", as_gltf(a), needle);
  test::expect_refused_from_file_and_bytes(dir + "/" + name + ".glb", as_glb(a), needle);
  const std::string beside = write_with_bin(a, dir, name + "-bin");
  test::expect_one_line_error([&] { load_mesh(beside); }, beside, needle);
  const std::string message = test::error_of([&] { load_mesh(beside); });
  EXPECT_NE(message.find(": cannot read: not a glTF file PriMo accepts ("), std::string::npos)
      << message;
}

Asset skinned(int joints, const Json& matrices) {
  Asset a = triangle();
  a.json["nodes"] = Json::array({{{"mesh", 0}, {"skin", 0}, {"children", Json::array()}}});
  Json skin = {{"joints", Json::array()}};
  for (int j = 1; j <= joints; ++j) {
    a.json["nodes"].push_back({{"name", "joint" + std::to_string(j)}});
    a.json["nodes"][0]["children"].push_back(j);
    skin["joints"].push_back(j);
  }
  if (!matrices.is_null()) skin["inverseBindMatrices"] = matrices;
  a.json["skins"] = Json::array({skin});
  return a;
}

int identity_matrices(Asset& a, int count, int component = 5126) {
  std::string bytes;
  for (int k = 0; k < count; ++k)
    bytes += component == 5126 ? floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1})
                               : std::string(32, '\0');  // 16 shorts
  return a.add_accessor({{"bufferView", a.add_view(bytes)},
                         {"componentType", component},
                         {"count", count},
                         {"type", "MAT4"}});
}

// A translation of node 0 over `inputs` keys with `outputs` values, interpolated `how`.
Asset animated(int inputs, int outputs, const std::string& how) {
  Asset a = triangle();
  std::vector<float> times, values;
  for (int k = 0; k < inputs; ++k) times.push_back(float(k));
  for (int k = 0; k < 3 * outputs; ++k) values.push_back(0.5f);
  const int input = a.add_accessor({{"bufferView", a.add_view(floats(times))},
                                    {"componentType", 5126},
                                    {"count", inputs},
                                    {"type", "SCALAR"},
                                    {"min", {0}},
                                    {"max", {inputs - 1}}});
  const int output = a.add_accessor({{"bufferView", a.add_view(floats(values))},
                                     {"componentType", 5126},
                                     {"count", outputs},
                                     {"type", "VEC3"}});
  a.json["animations"] = Json::array(
      {{{"samplers", Json::array({{{"input", input}, {"output", output}, {"interpolation", how}}})},
        {"channels",
         Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
  return a;
}

TEST(GltfAccessors, BuffersAndViewsThatPromiseMoreThanTheyHoldAreRefused) {
  Asset a = triangle();
  a.declared = 4000;  // Assimp itself refuses this one, in its own words
  expect_refused_in_every_form(a, "buffer-lies", "buffer 0 declares 4000 bytes but ");
  // Assimp 5.2 keeps where a data: URI's data begin in a char, and read from before the URI.
  Json long_uri = Json::parse(as_gltf(triangle()));
  std::string& uri = long_uri["buffers"][0]["uri"].get_ref<std::string&>();
  uri.insert(uri.find(';'), std::string(120, 'x'));
  test::expect_refused_from_file_and_bytes(
      test::temp_dir() + "/long-uri.gltf", long_uri.dump(),
      "buffer 0's data: URI begins its data after 157 characters (Assimp 5.2 finds them only "
      "within the first 127)");
  a = triangle();
  a.json["bufferViews"][1]["byteLength"] = 600;
  expect_refused_in_every_form(a, "view-past-buffer",
                               "buffer view 1 (bytes 36 + 600) runs past buffer 0 (44 bytes)");
  a = triangle();
  a.json["bufferViews"][1]["buffer"] = 3;
  expect_refused_in_every_form(a, "view-buffer", "buffer view 1 names buffer 3; the file has 1");
}

TEST(GltfAccessors, AccessorsReadingPastTheirViewsOrOverlappingAreRefused) {
  Asset a = triangle();
  a.json["accessors"][0]["count"] = 100000000;  // 100,000,000 vertices in 36 bytes
  expect_refused_in_every_form(a, "count", "accessor 0 reads 1200000000 bytes");
  a = triangle();
  a.json["accessors"][1]["byteOffset"] = 4;  // 4 + 3 x 2 bytes from a view of 6
  expect_refused_in_every_form(a, "offset",
                               "accessor 1 reads 10 bytes (offset 4, 3 elements of 2 bytes");
  a = triangle();
  a.json["accessors"][1]["count"] = 0;
  expect_refused_in_every_form(a, "count-zero", "accessor 1: count 0 is not from 1 to 4294967295");
  // Zeros without a view: 814 bytes made Assimp allocate 2.4 GB for 100,000,000 vertices
  // (a sparse accessor moving one of them).
  a = triangle();
  a.json["accessors"][0] = {{"componentType", 5126}, {"count", 100000000}, {"type", "VEC3"}};
  a.make_sparse(0, {1}, floats({5, 5, 5}));
  expect_refused_in_every_form(a, "viewless",
                               "accessor 0 has no buffer view and 100000000 elements, more than "
                               "the 3 of the largest accessor with data");
  a = triangle();  // as many as another accessor has, but more than 256 MiB of them
  a.add_accessor({{"bufferView", a.add_view(std::string(4200000, '\0'))},
                  {"componentType", 5121},
                  {"count", 4200000},
                  {"type", "SCALAR"}});
  a.add_accessor({{"componentType", 5126}, {"count", 4200000}, {"type", "MAT4"}});
  expect_refused_in_every_form(a, "viewless-large",
                               "accessor 3 has no buffer view and 4200000 elements of 64 bytes "
                               "(more than 268435456 bytes of zeros)");
  a = triangle();
  a.json["bufferViews"][0]["byteStride"] = 4;  // VEC3 floats 4 bytes apart overlap
  expect_refused_in_every_form(a, "stride",
                               "accessor 0 has elements of 12 bytes, but its buffer view's "
                               "byteStride is 4 (its elements would overlap)");
  a = triangle();
  a.json["bufferViews"][0]["byteStride"] = 14;
  expect_refused_in_every_form(a, "stride14",
                               "buffer view 0: byteStride 14 is not a multiple of 4 from 4 to 252");
  a = triangle();
  a.json["bufferViews"][0]["byteStride"] = 256;
  expect_refused_in_every_form(
      a, "stride256", "buffer view 0: byteStride 256 is not a multiple of 4 from 4 to 252");
  a = triangle();
  a.json["accessors"][0]["componentType"] = 1234;
  expect_refused_in_every_form(a, "component",
                               "accessor 0: componentType 1234 is not one glTF has");
  a = triangle();
  a.json["accessors"][1]["type"] = "VEC5";
  expect_refused_in_every_form(a, "type", "accessor 1: type 'VEC5' is not one glTF has");
  a = triangle();
  a.json["accessors"][1]["bufferView"] = 7;
  expect_refused_in_every_form(a, "view-index",
                               "accessor 1 names buffer view 7, but the file has 2");
}

TEST(GltfAccessors, SparseAccessorsAssimpWouldMisreadAreRefused) {
  // On a strided view Assimp 5.2 copied the base as if packed, then read it with the stride.
  Asset a = triangle(16);
  a.make_sparse(0, {1}, floats({5, 5, 5}));
  expect_refused_in_every_form(a, "sparse-strided",
                               "accessor 0 is sparse on a strided buffer view");
  a = triangle();
  a.make_sparse(0, {9}, floats({5, 5, 5}));
  expect_refused_in_every_form(
      a, "sparse-index", "accessor 0's sparse part: index 0 is 9, past the accessor's 3 elements");
  a = triangle();
  a.make_sparse(0, {0, 1, 2, 2}, floats({5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5}));
  expect_refused_in_every_form(
      a, "sparse-count", "accessor 0's sparse part: count 4 is not from 1 to the accessor's 3");
  a = triangle();
  a.make_sparse(0, {1}, floats({5, 5, 5}));
  a.json["accessors"][0]["sparse"]["indices"]["byteOffset"] = 100;
  expect_refused_in_every_form(a, "sparse-span",
                               "accessor 0's sparse part indices reads 102 bytes");
  a = triangle();
  a.make_sparse(0, {1}, floats({5, 5, 5}));
  a.json["bufferViews"][3]["byteStride"] = 12;
  expect_refused_in_every_form(a, "sparse-view-stride",
                               "the buffer view of its values has a byteStride (glTF forbids it");
  a = triangle();
  a.make_sparse(0, {1}, floats({5, 5, 5}));
  a.json["accessors"][0]["sparse"]["indices"]["componentType"] = 5122;
  expect_refused_in_every_form(a, "sparse-signed",
                               "accessor 0's sparse part: its indices are not unsigned integers");
}

TEST(GltfAccessors, PrimitivesAssimpWouldMisreadAreRefused) {
  Asset a = triangle();  // an index past the vertices: Assimp dropped the face
  a.bin.replace(36, 6, u16s({0, 1, 7}));
  expect_refused_in_every_form(a, "index", "mesh 0 primitive 0: index 2 is 7, past its 3 vertices");
  a = triangle();  // the same, by a sparse substitution over sound indices
  a.make_sparse(1, {2}, u16s({9}));
  expect_refused_in_every_form(
      a, "index-sparse",
      "mesh 0 primitive 0: index 2 is 9 (a sparse substitution), past its 3 vertices");
  a = triangle();
  a.json["accessors"][1]["componentType"] = 5122;  // signed
  expect_refused_in_every_form(a, "index-signed",
                               "mesh 0 primitive 0: its indices are not unsigned SCALAR");
  a = triangle();  // a strip of one index: Assimp asked for 2^64 faces
  a.json["meshes"][0]["primitives"][0]["mode"] = 5;
  a.json["accessors"][1]["count"] = 1;
  expect_refused_in_every_form(a, "strip",
                               "mesh 0 primitive 0 is a triangle strip of 1 vertices (at least 3)");
  a = triangle();
  a.json["meshes"][0]["primitives"][0]["mode"] = 6;
  a.json["accessors"][1]["count"] = 2;
  expect_refused_in_every_form(a, "fan",
                               "mesh 0 primitive 0 is a triangle fan of 2 vertices (at least 3)");
  a = triangle();  // a line strip of one index: Assimp wrote a segment into an array of none
  a.json["meshes"][0]["primitives"][0]["mode"] = 3;
  a.json["accessors"][1]["count"] = 1;
  expect_refused_in_every_form(a, "line-strip",
                               "mesh 0 primitive 0 is a line strip of 1 vertex (at least 2)");
  a = triangle();
  a.json["meshes"][0]["primitives"][0]["mode"] = 2;
  a.json["accessors"][1]["count"] = 1;
  expect_refused_in_every_form(a, "line-loop",
                               "mesh 0 primitive 0 is a line loop of 1 vertex (at least 2)");
  a = triangle();  // four corners: Assimp dropped the fourth
  a.bin.replace(36, 8, u16s({0, 1, 2, 1}));
  a.json["bufferViews"][1]["byteLength"] = 8;
  a.json["accessors"][1]["count"] = 4;
  expect_refused_in_every_form(a, "corners",
                               "mesh 0 primitive 0 has 4 triangle corners, not a multiple of 3 "
                               "(Assimp 5.2 drops the last 1)");
  a = triangle();
  a.json["meshes"][0]["primitives"][0]["mode"] = 9;
  expect_refused_in_every_form(a, "mode", "mesh 0 primitive 0: mode 9 is not one glTF has");
  a = triangle();
  a.json["meshes"][0]["primitives"][0]["attributes"] = {{"NORMAL", 0}};
  expect_refused_in_every_form(a, "no-position", "mesh 0 primitive 0 has no POSITION attribute");
  a = triangle();  // 16-bit positions (quantized): Assimp copied their bytes into floats
  a.json["accessors"][0]["componentType"] = 5123;
  expect_refused_in_every_form(a, "position-type",
                               "mesh 0 primitive 0: its POSITION accessor is not float VEC3");
  a = triangle();
  a.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
  expect_refused_in_every_form(a, "position-index",
                               "mesh 0 primitive 0 POSITION names accessor 9, but the file has 2");
  a = triangle();
  a.json["meshes"][0]["primitives"][0]["indices"] = 9;
  expect_refused_in_every_form(a, "indices-index",
                               "mesh 0 primitive 0 indices names accessor 9, but the file has 2");
  a = triangle();
  a.json["nodes"][0]["mesh"] = 5;
  expect_refused_in_every_form(a, "mesh-index", "node 0 names mesh 5, but the file has 1");
  // glTF gives every attribute and morph target POSITION's count: Assimp drops other normals,
  // coordinates and targets without a word, and reads a second set of joints or weights for the
  // first set's count.
  a = triangle();
  a.add_accessor({{"bufferView", 0}, {"componentType", 5126}, {"count", 1}, {"type", "VEC3"}});
  a.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
  expect_refused_in_every_form(a, "attribute",
                               "mesh 0 primitive 0 attribute NORMAL has 1 elements, POSITION 3");
  a = triangle();
  a.add_accessor({{"bufferView", 0}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
  a.json["meshes"][0]["primitives"][0]["targets"] = Json::array({{{"POSITION", 2}}});
  expect_refused_in_every_form(
      a, "target", "mesh 0 primitive 0 morph target 0 POSITION has 2 elements, POSITION 3");
}

TEST(GltfAccessors, SkinsAndAnimationsAssimpWouldOverrunAreRefused) {
  // A skinned mesh without inverse bind matrices: Assimp 5.2 dereferenced a null accessor.
  expect_refused_in_every_form(skinned(2, Json()), "skin-none",
                               "node 0's skin 0 has no inverseBindMatrices");
  Asset a = skinned(2, Json());
  a.json["skins"][0]["inverseBindMatrices"] = identity_matrices(a, 1);  // read for 2 joints
  expect_refused_in_every_form(a, "skin-short",
                               "node 0's skin 0 has 2 joints but 1 inverseBindMatrices");
  a = skinned(2, Json());
  a.json["skins"][0]["inverseBindMatrices"] = identity_matrices(a, 2, 5123);
  expect_refused_in_every_form(a, "skin-type",
                               "node 0's skin 0: its inverseBindMatrices are not float MAT4");
  a = skinned(2, Json());
  a.json["skins"][0]["inverseBindMatrices"] = 9;
  expect_refused_in_every_form(
      a, "skin-index", "node 0's skin 0 inverseBindMatrices names accessor 9, but the file has 2");
  // CUBICSPLINE reads 3 outputs per input: Assimp 5.2 read past 2.
  expect_refused_in_every_form(
      animated(2, 2, "CUBICSPLINE"), "cubic",
      "animation 0 sampler 0 is CUBICSPLINE with 2 outputs for 2 inputs (3 per input at least)");
}

TEST(GltfAccessors, TheBytesCheckedAreTheOnesAssimpReads) {
  const std::string dir = test::temp_dir();
  Asset bad = triangle();
  bad.bin.replace(36, 6, u16s({0, 1, 7}));
  const std::string needle = "mesh 0 primitive 0: index 2 is 7, past its 3 vertices";
  // In a .glb, Assimp's buffer 0 is the binary chunk, whatever uri the buffer names (here
  // sound indices) ...
  const std::string sound_uri = Json::parse(as_gltf(triangle()))["buffers"][0]["uri"];
  test::expect_refused_from_file_and_bytes(dir + "/uri-in-glb.glb", as_glb(bad, true, sound_uri),
                                           needle);
  // ... found after the JSON chunk's padding, also when its length leaves the padding out.
  test::expect_refused_from_file_and_bytes(dir + "/unpadded.glb", as_glb(bad, false), needle);
  // A data: URI as Assimp decodes it: raw bytes after the comma ...
  Json json = Json::parse(as_gltf(bad));
  std::string raw_bin = bad.bin;  // positions of 2.0 (bytes below 0x80 only)
  raw_bin.replace(12, 4, floats({2}));
  raw_bin.replace(28, 4, floats({2}));
  json["buffers"][0]["uri"] = "data:application/octet-stream," + raw_bin;
  test::expect_refused_from_file_and_bytes(dir + "/raw.gltf", json.dump(), needle);
  // ... and base64 with characters outside its alphabet, which Assimp reads as zeros.
  std::string uri = "data:application/octet-stream;base64," + base64(bad.bin);
  uri[uri.find(',') + 2] = '.';
  json["buffers"][0]["uri"] = uri;
  test::expect_refused_from_file_and_bytes(dir + "/stray.gltf", json.dump(), needle);
  // A buffer declaring more than it holds names where its bytes are.
  Asset lying = triangle();
  lying.declared = 4000;
  test::expect_refused_from_file_and_bytes(
      dir + "/lying.gltf", as_gltf(lying),
      "buffer 0 declares 4000 bytes but its data: URI holds 44");
  test::expect_refused_from_file_and_bytes(
      dir + "/lying.glb", as_glb(lying),
      "buffer 0 declares 4000 bytes but the GLB's binary chunk holds 44");
  const std::string beside = write_with_bin(lying, dir, "lying-bin");
  test::expect_one_line_error([&] { load_mesh(beside); }, beside,
                              "buffer 0 declares 4000 bytes but its file holds 44");
  // A .glb cut short: its binary chunk holds less than its buffer declares.
  const std::string whole = as_glb(triangle());
  test::expect_refused_from_file_and_bytes(
      dir + "/cut.glb", whole.substr(0, whole.size() - 10),
      "buffer 0 declares 44 bytes but the GLB's binary chunk holds 34");
}

TEST(GltfAccessors, DracoCompressedAccessorsAreLeftToTheDecoder) {
  // Accessors of a KHR_draco_mesh_compression primitive have no buffer view: Assimp fills them
  // from the decoded mesh (here not a Draco stream, which Assimp says), not with zeros.
  Asset a = triangle();
  const int compressed = a.add_view(std::string(16, '\x7f'));
  a.json["accessors"] =
      Json::array({{{"componentType", 5126}, {"count", 100000}, {"type", "VEC3"}},
                   {{"componentType", 5123}, {"count", 300000}, {"type", "SCALAR"}}});
  a.json["meshes"][0]["primitives"][0]["extensions"] = {
      {"KHR_draco_mesh_compression",
       {{"bufferView", compressed}, {"attributes", {{"POSITION", 0}}}}}};
  a.json["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  a.json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  const std::string dir = test::temp_dir();
  test::write_text(dir + "/draco.glb", as_glb(a));
  const std::string message = test::error_of([&] { load_mesh(dir + "/draco.glb"); });
  EXPECT_NE(message.find("draco.glb: cannot read: not a valid glTF file (Assimp: "),
            std::string::npos)
      << message;
  // Without the extension the same accessors are zeros, and refused.
  a.json["meshes"][0]["primitives"][0].erase("extensions");
  test::expect_refused_from_file_and_bytes(dir + "/zeros.glb", as_glb(a),
                                           "accessor 0 has no buffer view and 100000 elements, "
                                           "more than the 0 of the largest accessor with data");
}

TEST(GltfAccessors, SoundAssetsStillLoad) {
  const std::string dir = test::temp_dir();
  const Asset plain = triangle();
  test::write_text(dir + "/triangle.gltf", as_gltf(plain));
  test::write_text(dir + "/triangle.glb", as_glb(plain));
  for (const std::string& path :
       {dir + "/triangle.gltf", dir + "/triangle.glb", write_with_bin(plain, dir, "beside")})
    EXPECT_EQ(load_mesh(path).n_faces(), 1u) << path;
  // Sparse positions on a packed view (and on one whose stride is its element) move the vertex
  // they name; a sparse substitution of indices within range is read.
  for (int stride : {0, 12}) {
    Asset a = triangle(stride);
    a.make_sparse(0, {1}, floats({5, 5, 5}));
    a.make_sparse(1, {2}, u16s({2}));
    const std::string path = dir + "/sparse" + std::to_string(stride) + ".glb";
    test::write_text(path, as_glb(a));
    const Mesh mesh = load_mesh(path);
    ASSERT_EQ(mesh.n_vertices(), 3u);
    EXPECT_EQ(mesh.point(Mesh::VertexHandle(1)), Vec3(5, 5, 5));
  }
  // A skinned mesh with its inverse bind matrices, a cubic spline with its tangents, a triangle
  // strip, and a line strip of two vertices beside the triangle.
  Asset a = skinned(2, Json());
  a.json["skins"][0]["inverseBindMatrices"] = identity_matrices(a, 2);
  Asset cubic = animated(2, 6, "CUBICSPLINE");
  Asset strip = triangle();
  strip.json["meshes"][0]["primitives"][0]["mode"] = 5;
  Asset lines = triangle();
  lines.json["meshes"][0]["primitives"].push_back(
      {{"attributes", {{"POSITION", 0}}},
       {"indices",
        lines.add_accessor(
            {{"bufferView", 1}, {"componentType", 5123}, {"count", 2}, {"type", "SCALAR"}})},
       {"mode", 3}});
  for (const auto& [name, asset] : std::vector<std::pair<std::string, Asset>>{
           {"skinned", a}, {"cubic", cubic}, {"strip", strip}, {"lines", lines}}) {
    test::write_text(dir + "/" + name + ".gltf", as_gltf(asset));
    EXPECT_EQ(load_mesh(dir + "/" + name + ".gltf").n_faces(), 1u) << name;
  }
  // PriMo's own glTF and GLB, written and shipped, and the Khronos sample with its .bin beside it.
  const Mesh sphere = make_icosphere(2);
  for (const std::string ext : {".gltf", ".glb"}) {
    save_mesh(sphere, dir + "/sphere" + ext);
    EXPECT_EQ(load_mesh(dir + "/sphere" + ext).n_faces(), sphere.n_faces()) << ext;
  }
  EXPECT_EQ(load_mesh(test::source_path("fuzz/seeds/glb/quads.glb")).n_faces(), 6u);
  EXPECT_EQ(load_mesh(test::source_path("fuzz/seeds/gltf/ico.gltf")).n_faces(), 80u);
  EXPECT_GT(load_mesh(test::source_path("assets/meshes/AnimatedMorphCube.gltf")).n_faces(), 0u);
}

}  // namespace
}  // namespace primo
