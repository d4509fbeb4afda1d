// Hostile scenarios, sessions, scripts and numbers (issue 16): what the fuzzing pass crashed,
// hung or silently got wrong outside the mesh readers (tests/test_hostile_meshes.cpp). Each is
// one clear error naming the file, or the right result.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "primo/deformer.h"
#include "primo/error.h"
#include "primo/mesh_generators.h"
#include "primo/mesh_io.h"
#include "primo/scenario.h"
#include "primo/session.h"
#include "primo/session_replay.h"
#include "script.h"
#include "session_support.h"
#include "test_support.h"

namespace {

using namespace primo;
using Clock = std::chrono::steady_clock;

template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(std::string::npos, text.find(part)) << "'" << part << "' not in: " << text;
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A recorded bar session as text, and where its files are.
struct SessionText {
  std::string dir, text;
};
SessionText bar_session() {
  SessionText s;
  s.dir = test::temp_dir();
  const test::RecordedSession r = test::record_bar_session(s.dir + "/bar.obj");
  save_mesh(r.mesh, s.dir + "/bar.obj");
  s.text = session_to_json(r.session, s.dir + "/pose.session.json");
  return s;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(std::string::npos, at) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// --- sessions -------------------------------------------------------------------------------

TEST(HostileSessions, HugeInitialFactorFacesAreErrorsNotCrashes) {
  const SessionText s = bar_session();
  for (const std::string face : {"2147483647", "2000000000"}) {
    const std::string text = replaced(s.text, "\"height_factors\":{\"faces\":[]",
                                      "\"height_factors\":{\"faces\":[" + face + "]");
    const std::string bad =
        replaced(text, "\"height_factors\":{\"faces\":[" + face + "],\"values\":[]",
                 "\"height_factors\":{\"faces\":[" + face + "],\"values\":[0.5]");
    const auto start = Clock::now();
    const std::string message = error_of([&] { parse_session(bad, "big.session.json"); });
    expect_contains(message, "big.session.json: initial.height_factors.faces[0]: face " + face +
                                 " is beyond the largest mesh");
    EXPECT_LT(seconds_since(start), 1.0);
  }
}

TEST(HostileSessions, InitialFactorFacesMeetTheMeshBeforeAnyArrayIsMade) {
  // Face 16,777,215 is within the session limit but not on the 168-face bar: reading keeps the
  // list (an array up to that face was 134 MB), and the check against the mesh names the key.
  const SessionText s = bar_session();
  const std::string face = std::to_string(kMaxSessionFaces - 1);
  const std::string bad =
      replaced(s.text, "\"width_factors\":{\"faces\":[],\"values\":[]",
               "\"width_factors\":{\"faces\":[3," + face + "],\"values\":[2,0.5]");
  const Session session = parse_session(bad, s.dir + "/big.session.json");
  EXPECT_EQ(nullptr, session.initial.width_factor);
  EXPECT_EQ(2u, session.initial.listed_width.faces.size());
  const Mesh mesh = load_mesh(s.dir + "/bar.obj");
  const std::string expected = s.dir + "/big.session.json: initial.width_factors.faces[1]: face " +
                               face + " out of range (the mesh has " +
                               std::to_string(mesh.n_faces()) + " faces)";
  EXPECT_EQ(expected, error_of([&] { validate_session(session, int(mesh.n_faces())); }));
  EXPECT_EQ(expected, error_of([&] { replay_session(session, mesh); }));
  // Written again without meeting the mesh, the list is kept as it was read.
  expect_contains(session_to_json(session, s.dir + "/big.session.json"),
                  "\"width_factors\":{\"faces\":[3," + face + "],\"values\":[2.0,0.5]}");
  // Faces on the mesh become the array once the mesh is known.
  const Session good =
      parse_session(replaced(s.text, "\"width_factors\":{\"faces\":[],\"values\":[]",
                             "\"width_factors\":{\"faces\":[3],\"values\":[2]"),
                    "good.session.json");
  const SessionState state = initial_state(good, int(mesh.n_faces()));
  ASSERT_NE(nullptr, state.width_factor);
  EXPECT_EQ(mesh.n_faces(), state.width_factor->size());
  EXPECT_EQ(2.0, (*state.width_factor)[3]);
  EXPECT_EQ(1.0, (*state.width_factor)[4]);
}

TEST(HostileSessions, FramesBeyondTheLimitAreErrors) {
  const SessionText s = bar_session();
  const size_t last = s.text.rfind("\"frame\":");
  ASSERT_NE(std::string::npos, last);
  std::string bad = s.text;
  const size_t comma = bad.find(',', last);
  bad.replace(last, comma - last, "\"frame\":2147483647");
  expect_contains(error_of([&] { parse_session(bad, "long.session.json"); }),
                  "frame: 2147483647 is beyond the last frame");
}

TEST(HostileSessions, AnIdleStretchOfTenMillionFramesReplaysAtOnce) {
  const SessionText s = bar_session();
  Session session = parse_session(s.text, s.dir + "/pose.session.json");
  session.events.back().frame = kMaxSessionFrame;
  const Mesh mesh = load_mesh(s.dir + "/bar.obj");
  const auto start = Clock::now();
  const ReplayResult r = replay_session(session, mesh);
  EXPECT_LT(seconds_since(start), 20.0);
  EXPECT_EQ(kMaxSessionFrame + 1, r.frames);
  EXPECT_TRUE(r.converged);
}

TEST(HostileSessions, NumberOverflowNamesTheFile) {
  const SessionText s = bar_session();
  const std::string bad = replaced(s.text, "\"tolerance\":", "\"tolerance\":1e999,\"x\":");
  const std::string message = error_of([&] { parse_session(bad, "big.session.json"); });
  expect_contains(message, "big.session.json: ");
  EXPECT_EQ(std::string::npos, message.find("[json.exception")) << message;
}

TEST(HostileSessions, DeepNestingIsRefusedQuickly) {
  const std::string deep = std::string(30000, '[') + std::string(30000, ']');
  const auto start = Clock::now();
  expect_contains(error_of([&] { parse_session(deep, "deep.session.json"); }),
                  "deep.session.json: (root): arrays and objects nested deeper than 64 levels");
  expect_contains(error_of([&] { parse_scenario("{\"a\":" + deep + "}", "deep.json"); }),
                  "deep.json: (root): arrays and objects nested deeper than 64 levels");
  EXPECT_LT(seconds_since(start), 1.0);
}

// --- scenarios ------------------------------------------------------------------------------

std::string scenario_with(const std::string& handles, const std::string& rest = "") {
  return R"({"format": "primo-scenario/1", "mesh": "m.obj", "handles": [)" + handles + "]" + rest +
         "}";
}

TEST(HostileScenarios, HugeSettingsAreRejectedWhereTheyEnter) {
  const std::string fixed = R"({"select": {"faces": [0]}, "fix": "all"})";
  expect_contains(error_of([&] {
                    parse_scenario(scenario_with(fixed, R"(, "forces": [{"select": {"all": true},
                      "target_offset": [0, 1, 0], "stiffness": 1e308}])"),
                                   "s.json");
                  }),
                  "s.json: forces[0].stiffness: must be between -1e15 and 1e15");
  expect_contains(error_of([&] {
                    parse_scenario(scenario_with(fixed, R"(, "prisms": {"height": 1e308})"),
                                   "s.json");
                  }),
                  "s.json: prisms.height: must be between");
  // A 1e308 axis used to overflow its norm and be called zero.
  expect_contains(error_of([&] {
                    parse_scenario(scenario_with(R"({"select": {"faces": [0]}, "fix": "all",
                      "transform": {"axis": [1e308, 0, 0], "angle_deg": 90}})"),
                                   "s.json");
                  }),
                  "s.json: handles[0].transform.axis[0]: must be between");
}

// --- numbers in the solver ------------------------------------------------------------------

TEST(HostileNumbers, ASolveThatOverflowsKeepsTheLastGoodState) {
  const Mesh grid = make_grid(1.0, 1.0, 6, 6, FaceShape::Quads);
  Handle fixed{"fixed", {0}, Fix::All, {}};
  Handle moved{"moved", {35}, Fix::All, {}};
  Deformer d(grid, PrismParameters{}, {fixed, moved});
  RigidTransform far;
  far.translation = Vec3(1e200, 0, 0);
  d.set_handle_transform(1, far);
  SolveOptions options;
  const SolveReport report = d.solve(options);
  EXPECT_EQ("not finite", report.stop_reason);
  EXPECT_FALSE(report.converged);
  for (const Vec3& p : d.vertex_positions()) EXPECT_TRUE(p.allFinite());
  size_t finite = 0;
  for (const BodyState& b : d.body_states()) finite += b.rotation.allFinite();
  EXPECT_EQ(d.body_states().size(), finite);
}

TEST(HostileNumbers, AnUnusedFarVertexDoesNotStopTheSolveAtIterationZero) {
  // One unused vertex at 1e7 inflated the bounding-box diagonal behind the energy floor: the
  // solve stopped at once as "converged".
  PolygonSoup soup;
  const Mesh grid = make_grid(1.0, 1.0, 6, 6, FaceShape::Quads);
  for (auto v : grid.vertices()) soup.points.push_back(grid.point(v));
  for (auto f : grid.faces()) {
    soup.faces.emplace_back();
    for (auto v : f.vertices()) soup.faces.back().push_back(v.idx());
  }
  soup.points.push_back(Vec3(1e7, 1e7, 1e7));
  const Mesh with_far = mesh_from_soup(soup, "far.obj");
  RigidTransform lift;
  lift.translation = Vec3(0, 0, 0.01);
  for (const Mesh* mesh : {&grid, &with_far}) {
    Deformer d(*mesh, PrismParameters{}, {{"a", {0}, Fix::All, {}}, {"b", {35}, Fix::All, lift}});
    const SolveReport r = d.solve(SolveOptions{});
    EXPECT_GT(r.iterations, 0);
    EXPECT_EQ("tolerance", r.stop_reason) << r.stop_reason;
  }
}

TEST(HostileNumbers, EngineErrorsNameTheScenarioFile) {
  // Two triangles folded flat onto each other: the vertex normals on the fold cancel.
  const std::string dir = test::temp_dir();
  test::write_text(dir + "/fold.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0.5 1 0\nf 1 2 3\nf 2 1 4\n");
  test::write_text(dir + "/fold.json", R"({"format": "primo-scenario/1", "mesh": "fold.obj",
    "handles": [{"select": {"faces": [0]}, "fix": "all"}]})");
  const test::CommandResult r =
      test::run_primo("deform " + dir + "/fold.json -o " + dir + "/out.obj");
  EXPECT_NE(0, r.exit_code);
  expect_contains(r.err, dir + "/fold.json: face ");
  expect_contains(r.err, "extrusion direction has zero length");
}

TEST(HostileNumbers, ControlBytesFromJsonStringsAreNotPrinted) {
  const std::string dir = test::temp_dir();
  test::write_text(dir + "/esc.json", R"({"format": "primo-scenario/1", "mesh": "m.obj",
    "handles": [{"select": {"faces": [0]}, "fix": "\u001b[2J\nall"}]})");
  const test::CommandResult r = test::run_primo("deform " + dir + "/esc.json -o " + dir + "/o.obj");
  EXPECT_NE(0, r.exit_code);
  expect_contains(r.err, "\\x1B[2J\\x0Aall");
  EXPECT_EQ(1, std::count(r.err.begin(), r.err.end(), '\n')) << r.err;
  EXPECT_EQ(std::string::npos, r.err.find('\x1b')) << r.err;
}

// --- editor scripts -------------------------------------------------------------------------

TEST(HostileScripts, DurationsMustBeFiniteAndBounded) {
  using editor::parse_script;
  expect_contains(error_of([] { parse_script("wait nan\n", "s.txt"); }),
                  "s.txt:1: expected a finite number, got 'nan'");
  expect_contains(error_of([] { parse_script("echo hi\nmove 10 10 over inf\n", "s.txt"); }),
                  "s.txt:2: expected a finite");
  expect_contains(error_of([] { parse_script("wait -1\n", "s.txt"); }), "from 0 to 86400");
  expect_contains(error_of([] { parse_script("wait-settled 1e9\n", "s.txt"); }), "from 0 to 86400");
  expect_contains(error_of([] { parse_script("wait 1e300\n", "s.txt"); }),
                  "s.txt:1: expected seconds");
  expect_contains(error_of([] { parse_script("\nwait-file f.txt inf\n", "s.txt"); }),
                  "s.txt:2: expected a finite number, got 'inf'");
  expect_contains(error_of([] { parse_script("\x1b[2Jboom\n", "s.txt"); }),
                  "unknown command '\\x1B[2Jboom'");
}

}  // namespace
