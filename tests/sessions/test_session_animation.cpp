// A recorded session as one animated glTF (primo/sessions/session_animation.h, `primo replay
// --animation`): read back through Assimp, rest + target i is the replay's frame i, the
// weights show one frame at a time at the session's times, the mesh's UVs and materials are
// kept in the animation and in the frames; a request too large is refused before anything is
// solved.

#include "primo/sessions/session_animation.h"

#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <filesystem>

#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_replay.h"
#include "support/session_support.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::CommandResult;
using primo::test::record_bar_session;
using primo::test::RecordedSession;
using primo::test::run_primo;
namespace fs = std::filesystem;

TEST(SessionAnimation, FrameTimesComeFromTheTimeline) {
  Session s;
  SessionEvent e;
  e.type = SessionEvent::Type::Undo;
  e.frame = 4, e.t = 1.0;
  s.events.push_back(e);
  e.t = 1.5;  // a second event in the same frame: the frame's time is its first
  s.events.push_back(e);
  e.frame = 8, e.t = 3.0;
  s.events.push_back(e);
  EXPECT_EQ(session_frame_time(s, 0), 0.0);
  EXPECT_EQ(session_frame_time(s, 2), 0.5);  // evenly spaced from frame 0 at 0
  EXPECT_EQ(session_frame_time(s, 4), 1.0);
  EXPECT_EQ(session_frame_time(s, 6), 2.0);
  EXPECT_EQ(session_frame_time(s, 8), 3.0);
  s.events.front().frame = 0;  // frame 0 with an event: that event's time
  s.events.front().t = 0.25;
  EXPECT_EQ(session_frame_time(s, 0), 0.25);
}

namespace {

// The replay's frames (every `every`) as replay_session gives them to --frames.
std::vector<std::vector<Vec3>> replayed_frames(const Session& session, const Mesh& mesh, int every) {
  std::vector<std::vector<Vec3>> frames;
  ReplayOptions options;
  options.every = every;
  options.on_frame = [&](int, const Deformer& d) { frames.push_back(d.vertex_positions()); };
  replay_session(session, mesh, options);
  return frames;
}

}  // namespace

TEST(SessionAnimation, ReplayWritesTheFramesAsMorphTargetsAtTheSessionsTimes) {
  const std::string dir = primo::test::temp_dir();
  const RecordedSession r = record_bar_session(dir + "/bar.obj");
  save_mesh(r.mesh, dir + "/bar.obj");
  save_session(r.session, dir + "/pose.session.json");
  const int every = 2;
  const CommandResult run = run_primo("replay " + dir + "/pose.session.json -o " + dir +
                                      "/final.obj --every 2 --animation " + dir + "/pose.glb");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Mesh mesh = load_mesh(dir + "/bar.obj");
  const std::vector<std::vector<Vec3>> frames = replayed_frames(r.session, mesh, every);
  ASSERT_GE(frames.size(), 5u);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(dir + "/pose.glb", 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  const aiMesh* m = scene->mMeshes[0];
  ASSERT_EQ(m->mNumAnimMeshes, frames.size());
  ASSERT_EQ(m->mNumVertices, mesh.n_vertices());
  for (size_t i = 0; i < frames.size(); ++i)
    for (size_t v = 0; v < frames[i].size(); ++v)
      for (unsigned k = 0; k < 3; ++k) {
        const double expected = frames[i][v][int(k)];
        // Float precision: the rest and the displacement are float32, each within half an ulp.
        ASSERT_NEAR(m->mAnimMeshes[i]->mVertices[v][k], expected, 2.5e-7 * (1.0 + std::abs(expected)))
            << "target " << i << " vertex " << v;
      }
  // The rest is the session's mesh.
  for (auto v : mesh.vertices())
    for (unsigned k = 0; k < 3; ++k)
      ASSERT_EQ(m->mVertices[v.idx()][k], float(mesh.point(v)[int(k)]));

  ASSERT_EQ(scene->mNumAnimations, 1u);
  const aiAnimation* clip = scene->mAnimations[0];
  ASSERT_EQ(clip->mNumMorphMeshChannels, 1u);
  const aiMeshMorphAnim* channel = clip->mMorphMeshChannels[0];
  ASSERT_EQ(channel->mNumKeys, frames.size());
  const double ticks = clip->mTicksPerSecond > 0 ? clip->mTicksPerSecond : 1.0;
  for (unsigned key = 0; key < channel->mNumKeys; ++key) {
    const aiMeshMorphKey& k = channel->mKeys[key];
    EXPECT_NEAR(k.mTime / ticks, session_frame_time(r.session, int(key) * every), 1e-6) << "key " << key;
    double sum = 0.0;
    for (unsigned j = 0; j < k.mNumValuesAndWeights; ++j) {
      sum += k.mWeights[j];
      if (k.mValues[j] == key) EXPECT_EQ(k.mWeights[j], 1.0) << "key " << key;
    }
    EXPECT_EQ(sum, 1.0) << "key " << key << ": one frame at a time";
  }

  // save_session_animation (the editor's export) writes the same file (under the same name:
  // the node is named after the file).
  fs::create_directories(dir + "/same");
  save_session_animation(r.session, mesh, every, dir + "/same/pose.glb");
  EXPECT_TRUE(primo::test::read_text(dir + "/same/pose.glb") == primo::test::read_text(dir + "/pose.glb"));
}

TEST(SessionAnimation, AFileTooLargeIsRefusedBeforeSolvingNamingItsSizeAndEvery) {
  const std::string dir = primo::test::temp_dir();
  RecordedSession r = record_bar_session(dir + "/bar.obj");
  save_mesh(r.mesh, dir + "/bar.obj");
  // A finer bar, and one more event at frame 60,000: 60,001 frames of a mesh of ~2,000
  // vertices would weigh some 3 GB.
  const Mesh fine = make_bar(0.2, 1.0, 10, 40);
  ASSERT_GT(fine.n_vertices(), 1500u);
  save_mesh(fine, dir + "/fine.obj");
  SessionEvent late;
  late.type = SessionEvent::Type::Undo;
  late.frame = 60000;
  late.t = 1000.0;
  r.session.events.push_back(late);
  save_session(r.session, dir + "/long.session.json");
  const CommandResult run = run_primo("replay " + dir + "/long.session.json --mesh " + dir +
                                      "/fine.obj -o " + dir + "/out.obj --animation " + dir + "/long.glb");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("long.glb: the animation of 60001 frames of"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("more than the 1 GiB limit"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("--every"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir + "/long.glb"));
  EXPECT_FALSE(fs::exists(dir + "/out.obj"));
  // With --every 100 it would fit.
  EXPECT_LE(mesh_animation_size_bound(fine, 601, "x.glb"), kMaxAnimationFileBytes);

  // Ten million frames (their weights alone would be 4e14 bytes), and a name that is no glTF.
  const Mesh bar = load_mesh(dir + "/bar.obj");
  r.session.events.back().frame = 9000000;
  EXPECT_NE(primo::test::error_of([&] { SessionAnimation(r.session, bar, 1, dir + "/x.glb"); })
                .find("x.glb: the animation of 9000001 frames of"),
            std::string::npos);
  EXPECT_NE(primo::test::error_of([&] { SessionAnimation(r.session, bar, 1000, dir + "/x.obj"); })
                .find("x.obj: an animation is written as glTF"),
            std::string::npos);
}

namespace {

// The bar with a UV per face corner (every corner its own value, so a lost or shuffled corner
// shows) and two materials, the first half of the faces red, the rest blue.
MeshAttributes bar_attributes(const Mesh& mesh) {
  MeshAttributes a;
  a.texcoords.resize(1);
  for (auto f : mesh.faces()) {
    int k = 0;
    for (auto v : f.vertices()) {
      (void)v;
      a.texcoords[0].corner.push_back(int(a.texcoords[0].values.size()));
      a.texcoords[0].values.push_back({(f.idx() + 0.5) / double(mesh.n_faces()), 0.125 + 0.25 * k++});
    }
  }
  MeshMaterial red, blue;
  red.name = "red", red.base_color = {1, 0, 0, 1};
  blue.name = "blue", blue.base_color = {0, 0, 1, 1};
  a.materials = {red, blue};
  for (auto f : mesh.faces()) a.face_material.push_back(2 * size_t(f.idx()) < mesh.n_faces() ? 0 : 1);
  return a;
}

// Every face corner of `read` has the UV and the material of the same corner of `source`, and
// the position `positions` gives its vertex (to float32's precision for a glTF).
void expect_corners_like(const LoadedMesh& read, const Mesh& source, const MeshAttributes& expected,
                         const std::vector<Vec3>& positions, const std::string& what) {
  ASSERT_EQ(read.mesh.n_faces(), source.n_faces()) << what;
  ASSERT_EQ(read.attributes.texcoords.size(), 1u) << what;
  ASSERT_EQ(read.attributes.face_material.size(), source.n_faces()) << what;
  const CornerValues<2>& uvs = read.attributes.texcoords[0];
  size_t c = 0;
  for (auto f : read.mesh.faces()) {
    const auto expected_face = source.face_handle(f.idx());
    const int m = read.attributes.face_material[size_t(f.idx())];
    ASSERT_GE(m, 0) << what;
    EXPECT_EQ(read.attributes.materials[size_t(m)].name,
              expected.materials[size_t(expected.face_material[size_t(f.idx())])].name)
        << what << " face " << f.idx();
    auto sv = source.cfv_iter(expected_face);
    for (auto v : f.vertices()) {
      ASSERT_GE(uvs.corner[c], 0) << what;
      const auto uv = uvs.values[size_t(uvs.corner[c])];
      const auto want = expected.texcoords[0].values[size_t(expected.texcoords[0].corner[c])];
      EXPECT_NEAR(uv[0], want[0], 1e-6) << what << " corner " << c;
      EXPECT_NEAR(uv[1], want[1], 1e-6) << what << " corner " << c;
      EXPECT_LT((read.mesh.point(v) - positions[size_t(sv->idx())]).norm(), 1e-6)
          << what << " corner " << c;
      ++sv, ++c;
    }
  }
}

}  // namespace

TEST(SessionAnimation, FramesAndTheAnimationCarryTheMeshsUvsAndMaterials) {
  const std::string dir = primo::test::temp_dir();
  const RecordedSession r = record_bar_session(dir + "/bar.obj");
  const MeshAttributes attributes = bar_attributes(r.mesh);
  save_mesh(r.mesh, attributes, dir + "/bar.obj");
  save_session(r.session, dir + "/pose.session.json");
  const int every = 4;
  for (const char* format : {"obj", "glb"}) {
    const CommandResult run = run_primo("replay " + dir + "/pose.session.json -o " + dir +
                                        "/final." + format + " --every 4 --frames " + dir + "/" +
                                        format + " --frame-format " + format + " --animation " +
                                        dir + "/pose.glb");
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  const LoadedMesh source = load_mesh_noted(dir + "/bar.obj");
  const std::vector<std::vector<Vec3>> frames = replayed_frames(r.session, source.mesh, every);
  ASSERT_GE(frames.size(), 4u);
  // Frames in both formats, and the final mesh.
  for (const char* format : {"obj", "glb"}) {
    const std::string name = std::string(format) + "/frame_000008." + format;
    expect_corners_like(load_mesh_noted(dir + "/" + name), source.mesh, attributes, frames[2], name);
  }
  const LoadedMesh final_mesh = load_mesh_noted(dir + "/final.glb");
  EXPECT_EQ(final_mesh.attributes.materials.size(), 2u);
  // The animation: its rest mesh has them, and every mesh (one per material) morphs to each
  // frame, its copies of a vertex together.
  const LoadedMesh rest = load_mesh_noted(dir + "/pose.glb");
  std::vector<Vec3> rest_points;
  for (auto v : source.mesh.vertices()) rest_points.push_back(source.mesh.point(v));
  expect_corners_like(rest, source.mesh, attributes, rest_points, "pose.glb");
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(dir + "/pose.glb", 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 2u);
  size_t checked = 0;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh* m = scene->mMeshes[i];
    ASSERT_TRUE(m->HasTextureCoords(0));
    ASSERT_EQ(m->mNumAnimMeshes, frames.size());
    for (unsigned j = 0; j < m->mNumVertices; ++j) {
      // The mesh vertex this copy is of: the one at its rest position.
      const Vec3 at(m->mVertices[j].x, m->mVertices[j].y, m->mVertices[j].z);
      size_t v = 0;
      for (size_t w = 1; w < rest_points.size(); ++w)
        if ((rest_points[w] - at).norm() < (rest_points[v] - at).norm()) v = w;
      ASSERT_LT((rest_points[v] - at).norm(), 1e-6);
      for (size_t f = 0; f < frames.size(); ++f) {
        const aiVector3D& p = m->mAnimMeshes[f]->mVertices[j];
        ASSERT_LT((Vec3(p.x, p.y, p.z) - frames[f][v]).norm(), 1e-6) << "frame " << f;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, source.mesh.n_vertices());  // copies per UV seam
  ASSERT_EQ(scene->mNumAnimations, 1u);
  EXPECT_EQ(scene->mAnimations[0]->mNumMorphMeshChannels, 2u);
}
