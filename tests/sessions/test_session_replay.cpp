// Headless replay of sessions (docs/sessions.md), without the editor: deterministic, ending
// where a solve from rest ends, and `primo replay` end to end (results, frames, nothing written
// on bad files, a finer mesh).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_replay.h"
#include "support/session_support.h"
#include "support/test_support.h"

using primo::test::CommandResult;
using primo::test::read_text;
using primo::test::record_bar_session;
using primo::test::RecordedSession;
using primo::test::run_primo;

using namespace primo;
namespace fs = std::filesystem;

namespace {

double bbox_diagonal(const std::vector<Vec3>& p) {
  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& x : p) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  return (hi - lo).norm();
}

}  // namespace

TEST(SessionReplay, IsDeterministicAndEndsWhereASolveFromRestEnds) {
  const RecordedSession r = record_bar_session("bar.obj");
  const Mesh& mesh = r.mesh;
  int frames_seen = 0;
  ReplayOptions opt;
  opt.every = 5;
  opt.on_frame = [&](int frame, const Deformer&) { EXPECT_EQ(frame % 5, 0); ++frames_seen; };
  const ReplayResult a = replay_session(r.session, mesh, opt);
  const ReplayResult b = replay_session(r.session, mesh);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (size_t v = 0; v < a.positions.size(); ++v)
    ASSERT_TRUE(a.positions[v] == b.positions[v]) << "vertex " << v << " differs between replays";
  EXPECT_TRUE(a.converged);
  EXPECT_EQ(frames_seen, (r.session.frames() + 4) / 5);
  EXPECT_GE(a.rebuilds, 4);  // two handles, a stroke, the prism width (and its undo/redo)
  // The editor settles where a solve from rest ends (docs/editor.md): so does the replay.
  EXPECT_TRUE(a.state == r.final_state);
  const std::vector<Vec3> rest = solve_from_rest(r.final_state, mesh, r.session.solver);
  double worst = 0.0;
  for (size_t v = 0; v < rest.size(); ++v) worst = std::max(worst, (rest[v] - a.positions[v]).norm());
  EXPECT_LT(worst, 1e-6 * bbox_diagonal(rest));
  // And the pose moved: the top went right.
  EXPECT_GT(bbox_diagonal(a.positions), 0.0);
  std::vector<Vec3> rest_points;
  for (auto v : mesh.vertices()) rest_points.push_back(mesh.point(v));
  EXPECT_FALSE(a.positions == rest_points);
}

TEST(SessionReplay, FramesThatMoveTheTargetsAreDragFrames) {
  // With two iterations a frame, a frame whose events moved handles is solved as the editor's
  // batch while dragging where two fit: a hierarchical cycle and a Newton-Krylov step
  // (SolveOptions::drag_frame); with one, a cycle.
  RecordedSession r = record_bar_session("bar.obj");
  r.session.solver.method = SolverMethod::Hierarchical;
  std::vector<int> target_frames;  // frames whose only events move targets: no rebuild
  for (const SessionEvent& e : r.session.events) {
    const bool targets_only = std::all_of(
        r.session.events.begin(), r.session.events.end(), [&](const SessionEvent& other) {
          return other.frame != e.frame || other.type == SessionEvent::Type::Targets;
        });
    if (targets_only && (target_frames.empty() || target_frames.back() != e.frame))
      target_frames.push_back(e.frame);
  }
  ASSERT_GE(target_frames.size(), 10u);
  auto steps_in_target_frames = [&](int iterations_per_frame) {
    int steps = 0, last = 0;
    ReplayOptions opt;
    opt.iterations_per_frame = iterations_per_frame;
    opt.every = 1;
    opt.on_frame = [&](int frame, const Deformer& d) {
      const int now =
          d.hierarchical_solver() ? d.hierarchical_solver()->timings().newton_krylov_steps : 0;
      if (std::find(target_frames.begin(), target_frames.end(), frame) != target_frames.end())
        steps += now - last;
      last = now;
    };
    EXPECT_TRUE(replay_session(r.session, r.mesh, opt).converged);
    return steps;
  };
  EXPECT_EQ(steps_in_target_frames(1), 0);
  EXPECT_EQ(steps_in_target_frames(2), int(target_frames.size()));
}

// --- primo replay ------------------------------------------------------------------------

namespace {

class ReplayCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = primo::test::temp_dir();
    const RecordedSession r = record_bar_session(dir + "/bar.obj");
    save_mesh(r.mesh, dir + "/bar.obj");
    save_session(r.session, dir + "/pose.session.json");
    text = read_text(dir + "/pose.session.json");
  }
  size_t files_in(const std::string& d) {
    if (!fs::exists(d)) return 0;
    return size_t(std::distance(fs::directory_iterator(d), fs::directory_iterator()));
  }
  std::string dir, text;
};

}  // namespace

TEST_F(ReplayCli, WritesTheFinalMeshAndFrames) {
  EXPECT_NE(text.find("\"mesh\": \"bar.obj\""), std::string::npos);  // relative to the session
  const CommandResult a = run_primo("replay " + dir + "/pose.session.json -o " + dir + "/a.obj --frames " +
                                    dir + "/frames --every 4");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_TRUE(fs::exists(dir + "/frames/frame_000000.obj"));
  EXPECT_TRUE(fs::exists(dir + "/frames/frame_000004.obj"));
  EXPECT_FALSE(fs::exists(dir + "/frames/frame_000001.obj"));
  const int frames = load_session(dir + "/pose.session.json").frames();
  EXPECT_EQ(files_in(dir + "/frames"), size_t((frames + 3) / 4));
  const CommandResult b = run_primo("replay " + dir + "/pose.session.json -o " + dir + "/b.obj");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(read_text(dir + "/a.obj"), read_text(dir + "/b.obj"));  // bitwise the same
}

TEST_F(ReplayCli, FramesNeverReplaceInputsOrOutputs) {
  // The session's own mesh, -o and --stats under a frame's name in the frames folder, a
  // --frames that is a file, a folder where a frame goes: each refused before anything is
  // written, and the file that was there kept.
  fs::create_directories(dir + "/fr");
  fs::copy_file(dir + "/bar.obj", dir + "/fr/frame_000000.obj");
  std::string moved = text;
  moved.replace(moved.find("\"mesh\": \"bar.obj\""), 17, "\"mesh\": \"fr/frame_000000.obj\"");
  primo::test::write_text(dir + "/moved.session.json", moved);
  const std::string mesh_before = read_text(dir + "/fr/frame_000000.obj");
  CommandResult r = run_primo("replay " + dir + "/moved.session.json -o " + dir + "/out.obj --frames " + dir + "/fr");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("the session's mesh lies in --frames"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(dir + "/fr/frame_000000.obj"), mesh_before);
  EXPECT_FALSE(fs::exists(dir + "/out.obj"));

  for (const std::string& option : {std::string("-o"), std::string("--stats")}) {
    fs::create_directories(dir + "/fr2");
    const std::string target = dir + "/fr2/frame_000004.obj";
    primo::test::write_text(target, "kept");
    const std::string args = option == "-o" ? "-o " + target : "-o " + dir + "/out.obj --stats " + target;
    r = run_primo("replay " + dir + "/pose.session.json " + args + " --frames " + dir + "/fr2 --every 4");
    EXPECT_NE(r.exit_code, 0) << option;
    EXPECT_NE(r.err.find(option + " lies in --frames"), std::string::npos) << r.err;
    EXPECT_EQ(read_text(target), "kept");
    EXPECT_FALSE(fs::exists(dir + "/out.obj"));
  }

  primo::test::write_text(dir + "/not-a-folder", "x");
  r = run_primo("replay " + dir + "/pose.session.json -o " + dir + "/out.obj --frames " + dir + "/not-a-folder");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--frames names a file, not a folder"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;

  primo::test::write_text(dir + "/final.obj", "kept");
  fs::create_directories(dir + "/fr3/frame_000000.obj");
  r = run_primo("replay " + dir + "/pose.session.json -o " + dir + "/final.obj --frames " + dir + "/fr3");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("a folder is where the frame goes"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(dir + "/final.obj"), "kept");
  EXPECT_EQ(files_in(dir + "/fr3"), 1u);  // no frame and no temporary folder left
}

TEST_F(ReplayCli, BadSessionWritesNothing) {
  std::string bad = text;
  bad.replace(bad.find("\"handle\":1"), 10, "\"handle\":9");
  primo::test::write_text(dir + "/bad.session.json", bad);
  const CommandResult r = run_primo("replay " + dir + "/bad.session.json -o " + dir + "/out.obj --frames " +
                                    dir + "/frames");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("events[2] (targets): poses[0].handle: no handle 9"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out.obj"));
  EXPECT_EQ(files_in(dir + "/frames"), 0u);
}

TEST_F(ReplayCli, TruncatedSessionWritesNothing) {
  primo::test::write_text(dir + "/cut.session.json", text.substr(0, text.size() * 2 / 3));
  const CommandResult r = run_primo("replay " + dir + "/cut.session.json -o " + dir + "/out.obj");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("the file ends early"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("events["), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out.obj"));
}

TEST_F(ReplayCli, SameResultWhateverTheLibrariesThreadCount) {
  const CommandResult a = run_primo("replay " + dir + "/pose.session.json -o " + dir + "/a.obj");
  const CommandResult b = run_primo("replay " + dir + "/pose.session.json -o " + dir + "/b.obj");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const std::string env = "OMP_NUM_THREADS=2 OPENBLAS_NUM_THREADS=2 ";
  const int status = std::system((env + PRIMO_EXECUTABLE + " replay " + dir + "/pose.session.json -o " + dir +
                                  "/c.obj > /dev/null 2>&1").c_str());
  ASSERT_EQ(status, 0);
  EXPECT_EQ(read_text(dir + "/a.obj"), read_text(dir + "/b.obj"));
  EXPECT_EQ(read_text(dir + "/a.obj"), read_text(dir + "/c.obj"));
}

TEST_F(ReplayCli, ReplaysOnAFinerVersionOfTheMesh) {
  save_mesh(make_bar(0.2, 1.0, 4, 20), dir + "/bar-fine.obj");  // every quad split in four
  const CommandResult c = run_primo("replay " + dir + "/pose.session.json -o " + dir + "/coarse.obj");
  const CommandResult f = run_primo("replay " + dir + "/pose.session.json --mesh " + dir +
                                    "/bar-fine.obj -o " + dir + "/fine.obj --frames " + dir + "/ff --every 8");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const Mesh coarse = load_mesh(dir + "/coarse.obj"), fine = load_mesh(dir + "/fine.obj");
  EXPECT_EQ(fine.n_faces(), 4 * coarse.n_faces());
  auto box = [](const Mesh& m) {
    Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
    for (auto v : m.vertices()) lo = lo.cwiseMin(m.point(v)), hi = hi.cwiseMax(m.point(v));
    return std::make_pair(lo, hi);
  };
  const auto [clo, chi] = box(coarse);
  const auto [flo, fhi] = box(fine);
  EXPECT_GT(chi.x(), 0.2);  // the top moved right...
  EXPECT_LT((chi - fhi).norm(), 0.03);  // ...and the finer bar follows the same pose
  EXPECT_LT((clo - flo).norm(), 0.03);
  EXPECT_TRUE(fs::exists(dir + "/ff/frame_000008.obj"));
}

TEST_F(ReplayCli, FramesInAnotherFormat) {
  const CommandResult r = run_primo("replay " + dir + "/pose.session.json -o " + dir +
                                    "/final.glb --frames " + dir + "/frames --every 4 --frame-format glb");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/frames/frame_000000.glb"));
  EXPECT_FALSE(fs::exists(dir + "/frames/frame_000000.obj"));
  const Mesh rest = load_mesh(dir + "/bar.obj");
  const Mesh frame = load_mesh(dir + "/frames/frame_000004.glb");
  EXPECT_EQ(frame.n_faces(), rest.n_faces());
  EXPECT_EQ(load_mesh(dir + "/final.glb").n_vertices(), rest.n_vertices());
  const CommandResult bad = run_primo("replay " + dir + "/pose.session.json -o " + dir +
                                      "/x.obj --frames " + dir + "/f2 --frame-format fbx");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir + "/f2"));
}
