// A recorded session as one animated glTF (primo/sessions/session_animation.h, `primo replay
// --animation`): read back through Assimp, rest + target i is the replay's frame i, the
// weights show one frame at a time at the session's times; a request too large is refused
// before anything is solved.

#include "primo/sessions/session_animation.h"

#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <filesystem>

#include "primo/mesh/mesh_generators.h"
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
