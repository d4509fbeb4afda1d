// Hostile scenarios, sessions, scripts and numbers: what the fuzzing pass crashed,
// hung or silently got wrong outside the mesh readers (tests/core/io/test_hostile_meshes.cpp). Each
// is one clear error naming the file, or the right result.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "user_files/preferences.h"
#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/io/input_files.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/scenario/scenario.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_replay.h"
#include "input/script.h"
#include "support/session_support.h"
#include "support/test_support.h"

namespace {

using namespace primo;
using Clock = std::chrono::steady_clock;

using primo::test::error_of;

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

// --- files that are not regular files, or too large -----------------------------------------

// A named pipe that cannot hang the test: should a reader wait in open() for a writer (what
// PriMo did before it checked its inputs), a writer comes after 10 s, the reader sees an empty
// file and the test fails on its message instead of hanging.
class GuardedFifo {
 public:
  explicit GuardedFifo(const std::string& path) : path_(path) {
    EXPECT_EQ(0, ::mkfifo(path.c_str(), 0600)) << path;
    writer_ = std::thread([this] {
      std::unique_lock<std::mutex> lock(mutex_);
      if (stopped_.wait_for(lock, std::chrono::seconds(10), [this] { return stop_; })) return;
      while (!stop_) {  // the open fails (ENXIO) until a reader waits
        const int fd = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
        stopped_.wait_for(lock, std::chrono::milliseconds(20), [this] { return stop_; });
      }
    });
  }
  ~GuardedFifo() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    stopped_.notify_all();
    writer_.join();
  }

 private:
  std::string path_;
  std::mutex mutex_;
  std::condition_variable stopped_;
  bool stop_ = false;
  std::thread writer_;
};

// Every reader of a user's file: meshes (PriMo's own readers and Assimp's), scenarios, sessions.
void expect_every_reader_refuses(const std::string& stem, const std::string& problem) {
  for (const std::string ext : {".obj", ".ply", ".gltf", ".dae"})
    expect_contains(error_of([&] { load_mesh(stem + ext); }), stem + ext + ": " + problem);
  expect_contains(error_of([&] { load_scenario(stem + ".json"); }), stem + ".json: " + problem);
  expect_contains(error_of([&] { load_session(stem + ".session.json"); }),
                  stem + ".session.json: " + problem);
}

TEST(HostileFiles, PipesFoldersAndDevicesAreRefusedBeforeTheyAreOpened) {
  const std::string dir = test::temp_dir();
  std::vector<std::unique_ptr<GuardedFifo>> pipes;
  for (const char* ext : {".obj", ".ply", ".gltf", ".dae", ".json", ".session.json"}) {
    pipes.push_back(std::make_unique<GuardedFifo>(dir + "/pipe" + ext));
    std::filesystem::create_directory(dir + "/folder" + ext);
    std::filesystem::create_symlink("/dev/zero", dir + "/zero" + ext);
  }
  const Clock::time_point start = Clock::now();
  expect_every_reader_refuses(dir + "/pipe", "not a regular file (a named pipe)");
  expect_every_reader_refuses(dir + "/folder", "not a regular file (a folder)");
  expect_every_reader_refuses(dir + "/zero", "not a regular file (a character device)");
  expect_contains(error_of([] { check_input_file("/dev/urandom"); }),
                  "/dev/urandom: not a regular file (a character device)");
  EXPECT_LT(seconds_since(start), 2.0);

  // Preferences are a convenience: the defaults, and the problem said.
  const editor::Preferences preferences = editor::load_preferences(dir + "/pipe.json");
  EXPECT_EQ(preferences.brush_radius, editor::Preferences{}.brush_radius);
  ASSERT_EQ(1u, preferences.problems.size());
  expect_contains(preferences.problems[0], "pipe.json: not a regular file (a named pipe)");
}

TEST(HostileFiles, ALinkToARegularFileIsRead) {
  const std::string dir = test::temp_dir();
  save_mesh(make_bar(0.2, 1.0, 1, 2), dir + "/bar.obj");
  std::filesystem::create_symlink(dir + "/bar.obj", dir + "/link.obj");
  EXPECT_EQ(make_bar(0.2, 1.0, 1, 2).n_faces(), load_mesh(dir + "/link.obj").n_faces());
}

TEST(HostileFiles, FilesLargerThanAnInputMayBeAreRefusedUnread) {
  const std::string dir = test::temp_dir();
  // Sparse: no disk space, and a reader that did read it would take seconds and gigabytes.
  for (const char* name : {"/big.obj", "/big.json", "/big.session.json"}) {
    test::write_text(dir + name, "");
    std::filesystem::resize_file(dir + name, kMaxInputFileBytes + 1);
  }
  const Clock::time_point start = Clock::now();
  const std::string problem =
      ": the file is 2147483649 bytes, more than an input may be (2 GiB = 2147483648 bytes)";
  expect_contains(error_of([&] { load_mesh(dir + "/big.obj"); }), dir + "/big.obj" + problem);
  expect_contains(error_of([&] { load_scenario(dir + "/big.json"); }), dir + "/big.json" + problem);
  expect_contains(error_of([&] { load_session(dir + "/big.session.json"); }),
                  dir + "/big.session.json" + problem);
  EXPECT_LT(seconds_since(start), 1.0);
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
