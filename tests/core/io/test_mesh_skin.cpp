// A skinned character through reading and writing (docs/mesh-io.md, "Attributes"): the FBX
// character's bones, their hierarchy and its vertex weights are read, a posed copy written as
// GLB carries them (read back through Assimp, which PriMo's writer does not share), OBJ says it
// leaves the skin out, and bad skin data is refused with the file named.

#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/mesh_attributes.h"
#include "primo/util/error.h"
#include "support/test_support.h"

using primo::test::read_text;
using primo::test::temp_dir;
using primo::test::write_text;

namespace {

std::string character() { return primo::test::source_path("assets/meshes/huesitos.fbx"); }

// Bone name -> the name of its nearest ancestor that is a bone ("" for a root), as Assimp reads
// the file.
std::map<std::string, std::string> bone_parents(const aiScene& scene) {
  std::set<std::string> bones;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    for (unsigned b = 0; b < scene.mMeshes[m]->mNumBones; ++b)
      bones.insert(scene.mMeshes[m]->mBones[b]->mName.C_Str());
  std::map<std::string, std::string> parents;
  for (const std::string& bone : bones) {
    const aiNode* node = scene.mRootNode->FindNode(bone.c_str());
    EXPECT_NE(node, nullptr) << bone;
    std::string parent;
    for (const aiNode* up = node ? node->mParent : nullptr; up && parent.empty(); up = up->mParent)
      if (bones.count(up->mName.C_Str())) parent = up->mName.C_Str();
    parents[bone] = parent;
  }
  return parents;
}

// A vertex's weights by bone name.
using NamedWeights = std::map<std::string, double>;

NamedWeights named_weights(const primo::MeshSkin& skin, size_t v) {
  NamedWeights out;
  for (int k = 0; k < primo::kSkinInfluences; ++k)
    if (skin.vertex_weights[v][size_t(k)] > 0)
      out[skin.joints[size_t(skin.vertex_joints[v][size_t(k)])].name] +=
          skin.vertex_weights[v][size_t(k)];
  return out;
}

std::array<float, 3> float_position(const primo::Vec3& p) {
  return {float(p.x()), float(p.y()), float(p.z())};
}

Eigen::Matrix4d matrix_of(const std::array<double, 16>& m) {
  return Eigen::Map<const Eigen::Matrix4d>(m.data());
}

// A bend the deformer could make: the part above the waist turned about z and moved.
primo::Mesh posed(const primo::Mesh& rest) {
  primo::Mesh out = rest;
  const double middle = [&] {
    double low = 1e300, high = -1e300;
    for (auto v : rest.vertices()) low = std::min(low, rest.point(v).y()), high = std::max(high, rest.point(v).y());
    return (low + high) / 2;
  }();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (auto v : out.vertices())
    if (rest.point(v).y() > middle) out.set_point(v, turn * rest.point(v) + primo::Vec3(3, 1, 0));
  return out;
}

TEST(MeshSkinImport, FbxCharacterKeepsNineBonesTheirHierarchyAndWeights) {
  const primo::LoadedMesh loaded = primo::load_mesh_noted(character());
  const primo::MeshSkin& skin = loaded.attributes.skin;
  ASSERT_EQ(skin.joints.size(), 9u);
  EXPECT_NE(loaded.note.find("kept the skin of 'Cylinder' (9 bones)"), std::string::npos)
      << loaded.note;
  EXPECT_EQ(loaded.note.find("ignored: the skin"), std::string::npos) << loaded.note;

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(character(), 0);
  ASSERT_NE(scene, nullptr);
  std::map<std::string, std::string> parents;
  for (const primo::SkinJoint& joint : skin.joints)
    parents[joint.name] = joint.parent < 0 ? "" : skin.joints[size_t(joint.parent)].name;
  EXPECT_EQ(parents, bone_parents(*scene));

  ASSERT_EQ(skin.vertex_weights.size(), loaded.mesh.n_vertices());
  for (size_t v = 0; v < skin.vertex_weights.size(); ++v) {
    double sum = 0;
    for (double w : skin.vertex_weights[v]) sum += w;
    EXPECT_NEAR(sum, 1.0, 1e-12) << "vertex " << v;
  }
  // The rig in its rest pose holds the mesh where PriMo shows it: the inverse bind matrices
  // have the mesh node's transform folded in.
  std::vector<Eigen::Matrix4d> globals;
  for (const primo::SkinJoint& joint : skin.joints)
    globals.push_back(joint.parent < 0 ? matrix_of(joint.rest)
                                       : Eigen::Matrix4d(globals[size_t(joint.parent)] *
                                                         matrix_of(joint.rest)));
  double worst = 0, size = 0;
  for (auto v : loaded.mesh.vertices()) {
    const primo::Vec3& p = loaded.mesh.point(v);
    Eigen::Vector4d skinned = Eigen::Vector4d::Zero();
    for (int k = 0; k < primo::kSkinInfluences; ++k) {
      const size_t j = size_t(skin.vertex_joints[size_t(v.idx())][size_t(k)]);
      skinned += skin.vertex_weights[size_t(v.idx())][size_t(k)] * globals[j] *
                 matrix_of(skin.joints[j].inverse_bind) * Eigen::Vector4d(p.x(), p.y(), p.z(), 1);
    }
    worst = std::max(worst, (skinned.head<3>() - p).norm());
    size = std::max(size, p.norm());
  }
  EXPECT_LT(worst, 1e-6 * size);
}

TEST(MeshSkinExport, PosedFbxCharacterAsGlbKeepsBonesHierarchyWeightsAndPosedPositions) {
  const primo::LoadedMesh rest = primo::load_mesh_noted(character());
  const primo::Mesh pose = posed(rest.mesh);
  const std::string output = temp_dir() + "/posed.glb";
  primo::save_mesh(pose, rest.attributes, output);

  Assimp::Importer source_importer, importer;
  const aiScene* source = source_importer.ReadFile(character(), 0);
  const aiScene* scene = importer.ReadFile(output, 0);
  ASSERT_NE(source, nullptr);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  EXPECT_EQ(bone_parents(*scene), bone_parents(*source));

  // Every vertex of the file is a posed vertex with its weights; every posed vertex is there.
  std::map<std::array<float, 3>, size_t> vertex_at;
  for (auto v : pose.vertices()) vertex_at.emplace(float_position(pose.point(v)), size_t(v.idx()));
  ASSERT_EQ(vertex_at.size(), pose.n_vertices());
  std::set<size_t> seen;
  size_t checked = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    ASSERT_GT(mesh.mNumBones, 0u);
    std::vector<NamedWeights> weights(mesh.mNumVertices);
    for (unsigned b = 0; b < mesh.mNumBones; ++b)
      for (unsigned w = 0; w < mesh.mBones[b]->mNumWeights; ++w)
        weights[mesh.mBones[b]->mWeights[w].mVertexId][mesh.mBones[b]->mName.C_Str()] +=
            mesh.mBones[b]->mWeights[w].mWeight;
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D& p = mesh.mVertices[i];
      const auto found = vertex_at.find({p.x, p.y, p.z});
      ASSERT_NE(found, vertex_at.end()) << "vertex " << i << " is not a posed position";
      seen.insert(found->second);
      const NamedWeights expected = named_weights(rest.attributes.skin, found->second);
      double sum = 0;
      for (const auto& [bone, w] : weights[i]) sum += w;
      EXPECT_NEAR(sum, 1.0, 1e-6);
      for (const auto& [bone, w] : expected) {
        const auto got = weights[i].find(bone);
        ASSERT_NE(got, weights[i].end()) << bone;
        EXPECT_NEAR(got->second, w, 1e-6) << "vertex " << i << " bone " << bone;
      }
      for (const auto& [bone, w] : weights[i]) EXPECT_TRUE(expected.count(bone) || w == 0) << bone;
      ++checked;
    }
  }
  EXPECT_EQ(seen.size(), pose.n_vertices());
  EXPECT_GT(checked, 0u);

  // PriMo reads its own file back with the same skin (float32 matrices and weights).
  const primo::LoadedMesh again = primo::load_mesh_noted(output);
  const primo::MeshSkin& a = rest.attributes.skin;
  const primo::MeshSkin& b = again.attributes.skin;
  ASSERT_EQ(b.joints.size(), a.joints.size());
  for (size_t j = 0; j < b.joints.size(); ++j) {
    EXPECT_EQ(b.joints[j].name, a.joints[j].name);
    EXPECT_EQ(b.joints[j].parent, a.joints[j].parent);
    for (size_t k = 0; k < 16; ++k) {
      EXPECT_NEAR(b.joints[j].rest[k], a.joints[j].rest[k], 1e-6 * (1 + std::abs(a.joints[j].rest[k])));
      EXPECT_NEAR(b.joints[j].inverse_bind[k], a.joints[j].inverse_bind[k],
                  1e-6 * (1 + std::abs(a.joints[j].inverse_bind[k])));
    }
  }
  ASSERT_EQ(again.mesh.n_vertices(), pose.n_vertices());
  for (auto v : again.mesh.vertices()) {
    const size_t original = vertex_at.at(float_position(again.mesh.point(v)));
    const NamedWeights expected = named_weights(a, original), got = named_weights(b, size_t(v.idx()));
    ASSERT_EQ(got.size(), expected.size()) << "vertex " << v.idx();
    for (const auto& [bone, w] : expected) EXPECT_NEAR(got.at(bone), w, 1e-6) << bone;
  }
}

TEST(MeshSkinExport, SkinnedGltfStatesItsSkinAsTheSpecificationAsks) {
  const primo::LoadedMesh rest = primo::load_mesh_noted(character());
  const std::string output = temp_dir() + "/character.gltf";
  primo::save_mesh(rest.mesh, rest.attributes, output);
  const nlohmann::json gltf = nlohmann::json::parse(read_text(output));
  ASSERT_EQ(gltf["skins"].size(), 1u);
  const auto& skin = gltf["skins"][0];
  const auto& matrices = gltf["accessors"][skin["inverseBindMatrices"].get<size_t>()];
  EXPECT_EQ(matrices["count"], skin["joints"].size());
  EXPECT_EQ(matrices["type"], "MAT4");
  EXPECT_EQ(matrices["componentType"], 5126);
  // Joints are nodes of the scene: each root joint is a scene node, every other one a child.
  std::set<size_t> reached;
  std::vector<size_t> stack = gltf["scenes"][0]["nodes"].get<std::vector<size_t>>();
  while (!stack.empty()) {
    const size_t n = stack.back();
    stack.pop_back();
    reached.insert(n);
    if (gltf["nodes"][n].contains("children"))
      for (size_t c : gltf["nodes"][n]["children"].get<std::vector<size_t>>()) stack.push_back(c);
  }
  for (size_t joint : skin["joints"].get<std::vector<size_t>>()) EXPECT_TRUE(reached.count(joint));
  for (const auto& node : gltf["nodes"])
    if (node.contains("mesh")) {
      EXPECT_EQ(node["skin"], 0);
      EXPECT_FALSE(node.contains("matrix") || node.contains("translation"));
      const auto& attributes = gltf["meshes"][node["mesh"].get<size_t>()]["primitives"][0]["attributes"];
      EXPECT_EQ(gltf["accessors"][attributes["JOINTS_0"].get<size_t>()]["componentType"], 5123);
      EXPECT_EQ(gltf["accessors"][attributes["WEIGHTS_0"].get<size_t>()]["componentType"], 5126);
    }
}

TEST(MeshSkinExport, ObjSaveSaysItLeavesTheSkinOut) {
  const primo::LoadedMesh rest = primo::load_mesh_noted(character());
  const std::string output = temp_dir() + "/character.obj";
  EXPECT_NE(primo::save_note(rest.attributes, output).find("the skin (9 joints) is not saved"),
            std::string::npos)
      << primo::save_note(rest.attributes, output);
  EXPECT_EQ(primo::save_note(rest.attributes, temp_dir() + "/character.glb"), "");
  EXPECT_EQ(primo::save_note(primo::MeshAttributes(), output), "");
}

// A valid skin of `mesh`: every vertex on joint 0.
primo::MeshSkin one_joint_skin(const primo::Mesh& mesh) {
  primo::MeshSkin skin;
  skin.joints.push_back({"root", -1, {}, {}});
  skin.joints[0].rest = skin.joints[0].inverse_bind = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  skin.vertex_joints.assign(mesh.n_vertices(), {0, 0, 0, 0});
  skin.vertex_weights.assign(mesh.n_vertices(), {1, 0, 0, 0});
  return skin;
}

TEST(MeshSkinCheck, BadSkinDataIsRefusedWithTheFileNamed) {
  const primo::Mesh mesh = primo::load_mesh(character());
  const std::string output = temp_dir() + "/bad.glb";
  const auto expect_refused = [&](const primo::MeshSkin& skin, const std::string& why) {
    primo::MeshAttributes attributes;
    attributes.skin = skin;
    try {
      primo::save_mesh(mesh, attributes, output);
      ADD_FAILURE() << "saved: " << why;
    } catch (const primo::Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(output + ": cannot save", 0), 0u) << message;
      EXPECT_NE(message.find(why), std::string::npos) << message;
    }
  };
  primo::MeshSkin skin = one_joint_skin(mesh);
  skin.vertex_weights[5] = {std::nan(""), 0, 0, 0};
  expect_refused(skin, "vertex 5 has skin weight nan");
  skin = one_joint_skin(mesh);
  skin.vertex_weights[6] = {1.5, -0.5, 0, 0};
  expect_refused(skin, "vertex 6 has skin weight -0.5");
  skin = one_joint_skin(mesh);
  skin.vertex_joints[7] = {3, 0, 0, 0};
  expect_refused(skin, "vertex 7 is weighed by joint 3 of 1");
  skin = one_joint_skin(mesh);
  skin.vertex_weights[8] = {0.5, 0, 0, 0};
  expect_refused(skin, "the skin weights of vertex 8 sum to 0.5");
  skin = one_joint_skin(mesh);
  skin.joints[0].inverse_bind[12] = INFINITY;
  expect_refused(skin, "skin joint 0: its inverse bind matrix is not finite");
  skin = one_joint_skin(mesh);
  skin.joints[0].parent = 0;
  expect_refused(skin, "skin joint 0 has parent 0");
  skin = one_joint_skin(mesh);
  skin.vertex_weights.pop_back();
  expect_refused(skin, "the skin weighs");
  skin = one_joint_skin(mesh);
  skin.joints[0].inverse_bind[0] = 1e300;
  expect_refused(skin, "the inverse bind matrix of joint 0 has a value that float32 cannot hold");
  primo::MeshAttributes fine;
  fine.skin = one_joint_skin(mesh);
  EXPECT_NO_THROW(primo::save_mesh(mesh, fine, output));
}

// The GLB PriMo writes for the character, with the first value of `attribute`'s accessor
// overwritten by `bytes`.
std::string damaged_glb(const std::string& attribute, const void* bytes, size_t size) {
  const primo::LoadedMesh rest = primo::load_mesh_noted(character());
  const std::string path = temp_dir() + "/damaged.glb";
  primo::save_mesh(rest.mesh, rest.attributes, path);
  std::string glb = read_text(path);
  uint32_t json_length;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const nlohmann::json json = nlohmann::json::parse(glb.substr(20, json_length));
  const auto& accessor =
      json["accessors"][json["meshes"][0]["primitives"][0]["attributes"][attribute].get<size_t>()];
  const size_t offset =
      json["bufferViews"][accessor["bufferView"].get<size_t>()]["byteOffset"].get<size_t>();
  std::memcpy(glb.data() + 20 + json_length + 8 + offset, bytes, size);
  write_text(path, glb);
  return path;
}

void expect_read_refused(const std::string& path, const std::string& why) {
  try {
    primo::load_mesh_noted(path);
    ADD_FAILURE() << "read: " << why;
  } catch (const primo::Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": cannot read", 0), 0u) << message;
    EXPECT_NE(message.find(why), std::string::npos) << message;
  }
}

// A GLB of `json` with `bin` as its binary chunk.
std::string glb_of(const nlohmann::json& json, std::string bin) {
  std::string text = json.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  bin.append((4 - bin.size() % 4) % 4, '\0');
  std::string out;
  const auto u32 = [&](uint32_t value) { out.append(reinterpret_cast<const char*>(&value), 4); };
  u32(0x46546C67);
  u32(2);
  u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  u32(uint32_t(text.size()));
  u32(0x4E4F534A);
  out += text;
  u32(uint32_t(bin.size()));
  u32(0x004E4942);
  return out + bin;
}

template <typename T>
std::string bytes_of(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// Two triangles of a square whose corner at the origin is two vertices (a seam) with different
// weights, every vertex weighed by 5 joints through JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1.
std::string five_joint_square() {
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 0};
  const std::vector<uint16_t> indices = {0, 1, 2, 4, 2, 3};
  std::vector<uint16_t> joints0, joints1;
  std::vector<float> weights0, weights1;
  for (int v = 0; v < 5; ++v) {
    joints0.insert(joints0.end(), {0, 1, 2, 3});
    weights0.insert(weights0.end(), {0.3f, 0.2f, 0.2f, 0.1f});
    joints1.insert(joints1.end(), {4, 0, 0, 0});
    weights1.insert(weights1.end(), {v == 4 ? 0.6f : 0.2f, 0, 0, 0});
  }
  std::vector<float> matrices;
  for (int j = 0; j < 5; ++j) matrices.insert(matrices.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
  nlohmann::json json = {{"asset", {{"version", "2.0"}}}, {"scene", 0},
                         {"scenes", {{{"nodes", {0, 1}}}}}};
  json["nodes"] = {{{"name", "square"}, {"mesh", 0}, {"skin", 0}},
                   {{"name", "j0"}, {"children", {2, 3, 4, 5}}},
                   {{"name", "j1"}}, {{"name", "j2"}}, {{"name", "j3"}}, {{"name", "j4"}}};
  json["skins"] = {{{"joints", {1, 2, 3, 4, 5}}, {"inverseBindMatrices", 6}}};
  json["meshes"] = nlohmann::json::parse(R"([{"primitives": [{"attributes": {"POSITION": 0,
      "JOINTS_0": 1, "WEIGHTS_0": 2, "JOINTS_1": 3, "WEIGHTS_1": 4}, "indices": 5}]}])");
  std::string bin;
  json["bufferViews"] = nlohmann::json::array();
  json["accessors"] = nlohmann::json::array();
  const auto add = [&](const std::string& bytes, int component, const char* type, size_t count) {
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
    json["accessors"].push_back({{"bufferView", json["bufferViews"].size() - 1},
                                 {"componentType", component}, {"type", type}, {"count", count}});
    bin += bytes;
  };
  add(bytes_of(positions), 5126, "VEC3", 5);
  json["accessors"][0]["min"] = {0, 0, 0};
  json["accessors"][0]["max"] = {1, 1, 0};
  add(bytes_of(joints0), 5123, "VEC4", 5);
  add(bytes_of(weights0), 5126, "VEC4", 5);
  add(bytes_of(joints1), 5123, "VEC4", 5);
  add(bytes_of(weights1), 5126, "VEC4", 5);
  add(bytes_of(indices), 5123, "SCALAR", 6);
  add(bytes_of(matrices), 5126, "MAT4", 5);
  json["buffers"] = {{{"byteLength", bin.size()}}};
  return glb_of(json, bin);
}

TEST(MeshSkinImport, MoreThanFourWeightsKeepTheLargestAndCopiesKeepTheFirstsSaidInTheNote) {
  const std::string path = temp_dir() + "/square.glb";
  write_text(path, five_joint_square());
  const primo::LoadedMesh square = primo::load_mesh_noted(path);
  ASSERT_EQ(square.mesh.n_vertices(), 4u);
  const primo::MeshSkin& skin = square.attributes.skin;
  ASSERT_EQ(skin.joints.size(), 5u);
  EXPECT_NE(square.note.find("4 vertices had more than 4 bone weights: the 4 largest kept, "
                             "renormalised to sum 1"),
            std::string::npos)
      << square.note;
  EXPECT_NE(square.note.find("1 merged vertex copy had other bone weights than the first copy: "
                             "the first copy's kept"),
            std::string::npos)
      << square.note;
  // 0.3, then the three weights of 0.2 (joint 3's 0.1 dropped), over their sum 0.9.
  for (size_t v = 0; v < 4; ++v) {
    const NamedWeights w = named_weights(skin, v);
    EXPECT_EQ(w.size(), 4u);
    EXPECT_NEAR(w.at("j0"), 0.3 / 0.9, 1e-6);
    EXPECT_NEAR(w.at("j4"), 0.2 / 0.9, 1e-6);
    EXPECT_EQ(w.count("j3"), 0u);
  }
}

TEST(MeshSkinCheck, HostileSkinnedGlbIsRefusedWithTheFileNamed) {
  const float negative = -0.25f, not_a_number = std::nanf("");
  expect_read_refused(damaged_glb("WEIGHTS_0", &negative, 4), "weight");
  expect_read_refused(damaged_glb("WEIGHTS_0", &not_a_number, 4), "weight");
  const uint16_t far_joint = 900;
  expect_read_refused(damaged_glb("JOINTS_0", &far_joint, 2), "joint");
}

}  // namespace
