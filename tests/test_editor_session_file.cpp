// Deformation sessions (docs/sessions.md): recording a posing session from the editor model,
// the session file round trip, validation errors naming the event, deterministic headless
// replay, and `primo replay` end to end (results, frames, nothing written on bad files).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "paint.h"
#include "primo/error.h"
#include "primo/mesh_generators.h"
#include "primo/mesh_io.h"
#include "session.h"
#include "session_replay.h"
#include "test_support.h"

using primo::test::CommandResult;
using primo::test::read_text;
using primo::test::run_primo;

using namespace primo;
using namespace primo::editor;
namespace fs = std::filesystem;

namespace {

std::vector<int> faces_with(const Document& doc, double y_min, double y_max) {
  std::vector<int> out;
  for (auto f : doc.mesh->faces()) {
    Vec3 c = Vec3::Zero();
    int n = 0;
    for (auto v : doc.mesh->fv_range(f)) c += doc.mesh->point(v), ++n;
    c /= n;
    if (c.y() >= y_min && c.y() <= y_max) out.push_back(f.idx());
  }
  return out;
}

// A bar posed the way a user would: a fixed base, a handle on top dragged over 12 frames and
// rotated, a stroke of softer joints, a prism setting change, then an undo and a redo.
struct Recorded {
  std::unique_ptr<Document> doc;
  Session session;
};

Recorded record_bar_session(const std::string& mesh_path) {
  Recorded r;
  r.doc = make_document(make_bar(0.2, 1.0, 2, 10), mesh_path);
  Document& doc = *r.doc;
  SessionRecorder rec;
  double t = 0.0;
  rec.start(doc, t);
  auto frame = [&] { t += 1.0 / 60.0; rec.observe(doc, t); };
  frame();  // nothing changed: no event
  add_handle(doc.state, *doc.topology, doc.topology->rest_points, faces_with(doc, -1.0, 0.05), HandleMode::Fixed);
  doc.commit("fixed");
  frame();
  const int top = add_handle(doc.state, *doc.topology, doc.topology->rest_points,
                             faces_with(doc, 0.95, 2.0), HandleMode::Pose);
  doc.commit("handle");
  frame();
  for (int k = 1; k <= 12; ++k) {
    doc.state.handles[size_t(top)].pose.translate = Vec3(0.02 * k, 0.0, 0.01 * k);
    doc.state.handles[size_t(top)].pose.rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.03 * k, Vec3::UnitZ()));
    frame();
  }
  doc.commit("drag");
  doc.state.height_factor = paint_factors(doc.state.height_factor, doc.n_faces(), faces_with(doc, 0.4, 0.6), 0.5);
  doc.commit("paint");
  frame();
  doc.state.prisms.width = 0.9;
  doc.commit("width");
  frame();
  doc.state = doc.history.undo();
  frame();
  doc.state = doc.history.redo();
  frame();
  r.session = rec.stop(doc, t);
  return r;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Equal edit states but for the selection, which sessions do not record.
bool same_pose_state(const EditState& replayed, EditState editor) {
  editor.selection = replayed.selection;
  return replayed == editor;
}

double bbox_diagonal(const std::vector<Vec3>& p) {
  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& x : p) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  return (hi - lo).norm();
}

}  // namespace

TEST(SessionFile, RecorderTurnsEditsIntoEvents) {
  const Recorded r = record_bar_session("bar.obj");
  std::vector<std::string> types;
  for (const SessionEvent& e : r.session.events) types.push_back(event_type_name(e.type));
  const std::vector<std::string> expected = {
      "handles", "handles", "targets", "targets", "targets", "targets", "targets", "targets",
      "targets", "targets", "targets", "targets", "targets", "targets", "factors", "prisms",
      "undo",    "prisms",  "redo",    "prisms"};
  EXPECT_EQ(types, expected);
  // Targets carry only the handle that moved, one event per frame, with times and frames.
  EXPECT_EQ(r.session.events[2].poses.size(), 1u);
  EXPECT_EQ(r.session.events[2].poses[0].handle, 1);
  EXPECT_EQ(r.session.events[0].frame, 1);
  EXPECT_EQ(r.session.events[3].frame, r.session.events[2].frame + 1);
  EXPECT_GT(r.session.events.back().t, r.session.events.front().t);
  // Replaying the events on the initial state gives the editor's final state exactly.
  EXPECT_TRUE(same_pose_state(validate_session(r.session, r.doc->n_faces()), r.doc->state));
}

TEST(SessionFile, RoundTripIsExact) {
  const Recorded r = record_bar_session("bar.obj");
  const std::string dir = primo::test::temp_dir();
  const std::string text = session_to_json(r.session, dir + "/a.session.json");
  const Session back = parse_session(text, dir + "/a.session.json");
  EXPECT_EQ(session_to_json(back, dir + "/a.session.json"), text);
  ASSERT_EQ(back.events.size(), r.session.events.size());
  EXPECT_TRUE(same_pose_state(validate_session(back, r.doc->n_faces()), r.doc->state));
  EXPECT_NE(text.find("\"format\": \"primo-session/1\""), std::string::npos);
}

TEST(SessionFile, PrismsKeepTheirHeightUnit) {
  const Recorded r = record_bar_session("bar.obj");
  const std::string text = session_to_json(r.session, "");
  // The editor's default material is written as half_thickness (a fraction of the diagonal).
  ASSERT_NE(text.find("\"half_thickness\""), std::string::npos);
  // A session of the format's height in mean edge lengths reads back in that unit.
  std::string legacy = text;
  for (size_t at; (at = legacy.find("\"half_thickness\"")) != std::string::npos;)
    legacy.replace(at, 16, "\"height\"");
  const Session back = parse_session(legacy, "s.json");
  EXPECT_EQ(back.initial.prisms.height_unit, HeightUnit::MeanEdgeLength);
  EXPECT_EQ(back.initial.prisms.height, r.session.initial.prisms.height);
  // Both keys at once are an error naming where.
  std::string both = text;
  both.insert(both.find("\"half_thickness\""), "\"height\": 1, ");
  EXPECT_NE(error_of([&] { parse_session(both, "s.json"); }).find("exactly one of"), std::string::npos);
}

TEST(SessionFile, AcceptsEveryMaterialTheEditorCanMake) {
  // The Shell/plate slider goes below 0 (detail enhancement) and the thickness slider to 0
  // (a membrane): a session recorded with those loads and validates, as a scenario would.
  Recorded r = record_bar_session("bar.obj");
  r.session.initial.prisms.normal_blend = -0.47;
  r.session.initial.prisms.height = 0.0;
  for (SessionEvent& event : r.session.events)
    if (event.type == SessionEvent::Type::Prisms) event.prisms.normal_blend = 1.4;
  const std::string text = session_to_json(r.session, "");
  const Session back = parse_session(text, "s.json");
  EXPECT_EQ(back.initial.prisms.normal_blend, -0.47);
  EXPECT_NO_THROW(validate_session(back, r.doc->n_faces()));
  // Out of every range still is an error naming the key.
  Session negative = r.session;
  negative.initial.prisms.width = -1.0;
  const std::string bad = session_to_json(negative, "");
  EXPECT_NE(error_of([&] { parse_session(bad, "s.json"); }).find("width: must be positive"),
            std::string::npos);
}

TEST(SessionFile, ErrorsNameTheEvent) {
  const Recorded r = record_bar_session("bar.obj");
  const std::string text = session_to_json(r.session, "");
  const int n = r.doc->n_faces();
  auto parse_error = [&](const std::string& t) { return error_of([&] { parse_session(t, "s.json"); }); };
  // An unknown key in event 3 (a targets event).
  std::string bad = text;
  const size_t p3 = bad.find("\"type\":\"targets\"", bad.find("\"type\":\"targets\"") + 1);
  bad.insert(p3, "\"speed\":1,");
  EXPECT_EQ(parse_error(bad), "s.json: events[3] (targets): speed: unknown key");
  // A truncated file names the event it stops in.
  const size_t cut = text.find("\"type\":\"factors\"") + 30;
  const std::string truncated = parse_error(text.substr(0, cut));
  EXPECT_NE(truncated.find("s.json: events[14] (factors): the file ends early"), std::string::npos) << truncated;
  // An unknown event type.
  std::string unknown = text;
  unknown.replace(unknown.find("\"type\":\"prisms\""), 15, "\"type\":\"prismz\"");
  EXPECT_NE(parse_error(unknown).find("events[15] (prismz): type: unknown event type"), std::string::npos);
  // A bad quaternion.
  Session s = r.session;
  std::string q = session_to_json(s, "");
  const size_t rot = q.find("\"rotation\":[", q.find("\"type\":\"targets\""));
  q.replace(rot + 12, q.find(',', rot) - rot - 12, "2");
  EXPECT_NE(parse_error(q).find("events[3] (targets): poses[0].rotation: not a unit quaternion"), std::string::npos)
      << parse_error(q);
  // Events that parse but do not fit the state or the mesh.
  s.events[5].poses[0].handle = 7;
  EXPECT_EQ(error_of([&] { validate_session(s, n); }),
            "session: events[5] (targets): poses[0].handle: no handle 7 (there are 2)");
  s = r.session;
  s.events[14].faces[0] = n + 3;
  EXPECT_NE(error_of([&] { validate_session(s, n); }).find("events[14] (factors): faces[0]: face "),
            std::string::npos);
  s = r.session;
  s.events[1].handles[1].faces = s.events[1].handles[0].faces;
  EXPECT_NE(error_of([&] { validate_session(s, n); }).find("events[1] (handles): handles[1].faces: face"),
            std::string::npos);
  EXPECT_NE(parse_error("{\"format\": \"primo-session/2\"}").find("format"), std::string::npos);
}

TEST(SessionReplay, IsDeterministicAndEndsWhereASolveFromRestEnds) {
  const Recorded r = record_bar_session("bar.obj");
  const Mesh& mesh = *r.doc->mesh;
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
  EXPECT_TRUE(same_pose_state(a.state, r.doc->state));
  const std::vector<Vec3> rest = solve_from_rest(r.doc->state, mesh, r.session.solver);
  double worst = 0.0;
  for (size_t v = 0; v < rest.size(); ++v) worst = std::max(worst, (rest[v] - a.positions[v]).norm());
  EXPECT_LT(worst, 1e-6 * bbox_diagonal(rest));
  // And the pose moved: the top went right.
  EXPECT_GT(bbox_diagonal(a.positions), 0.0);
  EXPECT_FALSE(a.positions == r.doc->topology->rest_points);
}

// --- primo replay ------------------------------------------------------------------------

namespace {

class ReplayCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = primo::test::temp_dir();
    Recorded r = record_bar_session(dir + "/bar.obj");
    save_mesh(*r.doc->mesh, dir + "/bar.obj");
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
