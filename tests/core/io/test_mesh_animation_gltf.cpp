// Vertex animations as glTF morph targets (primo/io/mesh_animation_gltf.h), read back through
// Assimp as another tool reads them: targets sparse where few vertices move, dense otherwise,
// the weights and times of the animation, and the rest mesh as save_mesh writes it, with its
// attributes (whose size the bound counts).

#include "primo/io/mesh_animation_gltf.h"

#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "primo/io/output_files.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::error_of;

namespace {

std::vector<Vec3> points_of(const Mesh& mesh) {
  std::vector<Vec3> out;
  for (auto v : mesh.vertices()) out.push_back(mesh.point(v));
  return out;
}

// The JSON chunk of a GLB.
nlohmann::json glb_json(const std::string& bytes) {
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

}  // namespace

TEST(MeshAnimationGltf, TargetsWeightsAndTimesReadBackThroughAssimp) {
  const Mesh bar = make_bar(0.2, 1.0, 2, 4);
  const std::vector<Vec3> rest = points_of(bar);
  const size_t n = rest.size();
  // Three frames: nothing moved, one vertex moved (sparse), every vertex moved (dense).
  std::vector<std::vector<Vec3>> frames(3, rest);
  frames[1][5] += Vec3(0.1, -0.2, 0.3);
  for (size_t v = 0; v < n; ++v) frames[2][v] = 1.5 * rest[v] + Vec3(0.01 * double(v), 0.0, 0.25);
  const std::vector<double> times = {0.0, 0.5, 1.25};
  MeshAnimation animation(bar);
  for (size_t i = 0; i < frames.size(); ++i)
    animation.add_frame(times[i], frames[i], "frame_" + std::to_string(i));
  const std::string dir = primo::test::temp_dir();
  const std::string path = dir + "/bar-anim.glb";
  const std::string bytes = animation.file_bytes(path);
  write_text_atomically(path, bytes);

  const nlohmann::json json = glb_json(bytes);
  const auto& targets = json["meshes"][0]["primitives"][0]["targets"];
  ASSERT_EQ(targets.size(), 3u);
  const auto& accessors = json["accessors"];
  EXPECT_FALSE(accessors[targets[0]["POSITION"].get<size_t>()].contains("bufferView"));
  EXPECT_EQ(accessors[targets[0]["POSITION"].get<size_t>()]["sparse"]["count"], 1);
  EXPECT_EQ(accessors[targets[1]["POSITION"].get<size_t>()]["sparse"]["count"], 1);
  EXPECT_TRUE(accessors[targets[2]["POSITION"].get<size_t>()].contains("bufferView"));
  EXPECT_EQ(accessors[targets[1]["POSITION"].get<size_t>()]["max"][2].get<float>(), float(0.3 + rest[5].z()) - float(rest[5].z()));
  EXPECT_EQ(json["meshes"][0]["extras"]["targetNames"][1], "frame_1");

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh* mesh = scene->mMeshes[0];
  ASSERT_EQ(mesh->mNumVertices, n);
  ASSERT_EQ(mesh->mNumAnimMeshes, 3u);
  for (size_t i = 0; i < frames.size(); ++i) {
    const aiAnimMesh* target = mesh->mAnimMeshes[i];
    ASSERT_EQ(target->mNumVertices, n);
    for (size_t v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(target->mVertices[v][unsigned(k)], frames[i][v][k], 1e-6 * (1 + std::abs(frames[i][v][k])))
            << "frame " << i << " vertex " << v;
  }
  ASSERT_EQ(scene->mNumAnimations, 1u);
  const aiAnimation* clip = scene->mAnimations[0];
  ASSERT_EQ(clip->mNumMorphMeshChannels, 1u);
  const aiMeshMorphAnim* channel = clip->mMorphMeshChannels[0];
  ASSERT_EQ(channel->mNumKeys, 3u);
  const double ticks = clip->mTicksPerSecond > 0 ? clip->mTicksPerSecond : 1.0;
  for (unsigned k = 0; k < channel->mNumKeys; ++k) {
    const aiMeshMorphKey& key = channel->mKeys[k];
    EXPECT_NEAR(key.mTime / ticks, times[k], 1e-6);
    ASSERT_EQ(key.mNumValuesAndWeights, 3u);
    for (unsigned j = 0; j < key.mNumValuesAndWeights; ++j)
      EXPECT_EQ(key.mWeights[j], key.mValues[j] == k ? 1.0 : 0.0) << "key " << k << " target " << key.mValues[j];
  }
  // And PriMo reads the rest mesh back with its faces as they were.
  const Mesh back = load_mesh(path);
  EXPECT_EQ(back.n_faces(), bar.n_faces());
}

TEST(MeshAnimationGltf, BadFramesAreRefusedNamingThem) {
  const Mesh bar = make_bar(0.2, 1.0, 2, 4);
  std::vector<Vec3> frame = points_of(bar);
  MeshAnimation animation(bar);
  EXPECT_NE(error_of([&] { animation.file_bytes("a.glb"); }).find("a.glb: cannot save an animation without frames"),
            std::string::npos);
  EXPECT_NE(error_of([&] { animation.add_frame(0.0, {Vec3::Zero()}, "f0"); }).find("1 positions for a mesh of"),
            std::string::npos);
  animation.add_frame(1.0, frame, "f0");
  EXPECT_NE(error_of([&] { animation.add_frame(0.5, frame, "f1"); }).find("goes back"), std::string::npos);
  frame[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_of([&] { animation.add_frame(2.0, frame, "f1"); }).find("(f1): vertex 3 has a coordinate"),
            std::string::npos);
  frame[3].y() = 1e300;
  EXPECT_NE(error_of([&] { animation.add_frame(2.0, frame, "f1"); }).find("vertex 3"), std::string::npos);
  EXPECT_EQ(animation.frames(), 1u);
  EXPECT_NE(error_of([&] { animation.file_bytes("a.obj"); }).find("a.obj: an animation is written as glTF"),
            std::string::npos);
  // Equal times become increasing ones, as glTF requires.
  frame = points_of(bar);
  animation.add_frame(1.0, frame, "f1");
  const nlohmann::json json = nlohmann::json::parse(animation.file_bytes("a.gltf"));
  const size_t input = json["animations"][0]["samplers"][0]["input"];
  EXPECT_GT(json["accessors"][input]["max"][0].get<float>(), 1.0f);
}

TEST(MeshAnimationGltf, TheSizeBoundCoversTheFile) {
  const Mesh bar = make_bar(0.2, 1.0, 2, 4);
  MeshAnimation animation(bar);
  std::vector<Vec3> frame = points_of(bar);
  for (int i = 0; i < 20; ++i) {
    for (Vec3& p : frame) p += Vec3(0.01, 0.02, -0.01);
    animation.add_frame(0.1 * i, frame, "frame");
  }
  for (const std::string path : {"x.glb", "x.gltf"}) {
    const std::uint64_t bound = mesh_animation_size_bound(bar, 20, path);
    const std::uint64_t size = animation.file_bytes(path).size();
    EXPECT_LE(size, bound) << path;
    EXPECT_GT(size, bound / 2) << path << ": a bound, but not a wild one";
  }
}

TEST(MeshAnimationGltf, TheSizeBoundCoversAFileWithUvsMaterialsAndAnEmbeddedImage) {
  // BoxTextured.glb: a UV seam at every edge (24 corners' copies of 8 vertices), a material
  // and the texture its GLB embeds.
  const LoadedMesh box = load_mesh_noted(primo::test::source_path("tests/data/scenes/BoxTextured.glb"));
  ASSERT_FALSE(box.attributes.images.empty());
  ASSERT_FALSE(box.attributes.images[0].bytes.empty());
  MeshAnimation animation(box.mesh, box.attributes);
  std::vector<Vec3> frame = points_of(box.mesh);
  for (int i = 0; i < 20; ++i) {
    for (Vec3& p : frame) p = 1.01 * p + Vec3(0.01, 0.02, -0.01);
    animation.add_frame(0.1 * i, frame, "frame");
  }
  for (const std::string path : {"x.glb", "x.gltf"}) {
    const std::uint64_t bound = mesh_animation_size_bound(box.mesh, 20, path, box.attributes);
    const std::uint64_t size = animation.file_bytes(path).size();
    EXPECT_LE(size, bound) << path;
    EXPECT_GT(size, bound / 2) << path << ": a bound, but not a wild one";
    // Without the attributes the bound would be too small: the copies, UVs and image count.
    EXPECT_GT(size, mesh_animation_size_bound(box.mesh, 20, path)) << path;
  }
  // Attributes of another mesh are refused naming what they belong to.
  MeshAttributes wrong = box.attributes;
  wrong.texcoords[0].corner.pop_back();
  EXPECT_NE(error_of([&] { MeshAnimation(box.mesh, wrong); }).find("the animation's rest mesh"),
            std::string::npos);
}
