// `primo deform` end to end: results, statistics, and one clear error line (with no output
// file left behind) for every kind of bad input.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <sstream>
#include <nlohmann/json.hpp>

#include "primo/io/mesh_io.h"
#include "support/test_support.h"

using primo::test::CommandResult;
using primo::test::read_text;
using primo::test::run_primo;

namespace fs = std::filesystem;
using primo::test::write_text;

namespace {

int count_lines(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

const char* kCube = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

std::string scenario_json(const std::string& mesh, const std::string& extra = "") {
  return R"({"format": "primo-scenario/1", "mesh": ")" + mesh + R"(",
  "handles": [
    {"name": "bottom", "select": {"faces": [0]}, "fix": "all"},
    {"name": "top", "select": {"faces": [1]}, "fix": "all",
     "transform": {"translate": [0.2, 0, 0], "axis": [0, 0, 1], "angle_deg": 20}}
  ])" + extra + "}";
}

class DeformCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = primo::test::temp_dir();
    write_text(dir + "/cube.obj", kCube);
    write_text(dir + "/ok.json", scenario_json("cube.obj"));
  }
  // Asserts a failure: non-zero exit, exactly one line on stderr that contains `needle`, and
  // no file at `output`.
  void expect_error(const std::string& arguments, const std::string& needle,
                    const std::string& output) {
    const CommandResult r = run_primo(arguments);
    EXPECT_NE(r.exit_code, 0) << arguments;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(output)) << output;
    // No temporary files either, in the nearest folder that exists.
    fs::path folder = fs::path(output).parent_path();
    while (!fs::exists(folder)) folder = folder.parent_path();
    for (const auto& entry : fs::directory_iterator(folder))
      EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
  std::string dir;
};

}  // namespace

TEST_F(DeformCli, SolvesAScenarioAndWritesStatistics) {
  const CommandResult r = run_primo("deform " + dir + "/ok.json -o " + dir + "/out.obj --stats " + dir + "/s.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const primo::Mesh out = primo::load_mesh(dir + "/out.obj");
  EXPECT_EQ(out.n_vertices(), 8u);
  EXPECT_EQ(out.n_faces(), 6u);
  const auto stats = nlohmann::json::parse(read_text(dir + "/s.json"));
  for (const char* key : {"energy", "iterations", "converged", "seconds", "faces", "vertices"})
    EXPECT_TRUE(stats.contains(key)) << key;
  EXPECT_EQ(stats["faces"], 6);
  EXPECT_EQ(stats["vertices"], 8);
  EXPECT_TRUE(stats["converged"].get<bool>());
  EXPECT_GT(stats["energy"].get<double>(), 0.0);
}

TEST_F(DeformCli, LocalAndGlobalSolversAgree) {
  const CommandResult g = run_primo("deform " + dir + "/ok.json -o " + dir + "/g.off --stats " + dir + "/g.json");
  write_text(dir + "/local.json", scenario_json("cube.obj", R"(, "solver": {"max_iterations": 100000, "tolerance": 1e-13})"));
  const CommandResult l = run_primo("deform " + dir + "/local.json -o " + dir + "/l.off --solver local --stats " + dir + "/l.json");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  ASSERT_EQ(l.exit_code, 0) << l.err;
  const auto gs = nlohmann::json::parse(read_text(dir + "/g.json"));
  const auto ls = nlohmann::json::parse(read_text(dir + "/l.json"));
  EXPECT_EQ(ls["solver"], "local");
  EXPECT_EQ(gs["solver"], "global");
  EXPECT_NEAR(ls["energy"].get<double>(), gs["energy"].get<double>(), 1e-6 * gs["energy"].get<double>());
}

TEST_F(DeformCli, ReproducesTheSpecificationExample) {
  const std::string scenario = primo::test::shared_path("spec/examples/cylinder-small-bend-45.json");
  if (!primo::test::exists(scenario)) GTEST_SKIP() << "skipped: " << scenario << " is not present";
  const CommandResult r = run_primo("deform " + scenario + " -o " + dir + "/c.obj --stats " + dir + "/c.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto stats = nlohmann::json::parse(read_text(dir + "/c.json"));
  EXPECT_NEAR(stats["energy"].get<double>(), 0.008368710955476165, 1e-6 * 0.008368710955476165);
  // The default solve: the 45-degree turn in sub-steps, hierarchical cycles, a Newton polish.
  EXPECT_GT(stats["path_steps"].get<int>(), 0);
  EXPECT_GT(stats["hierarchical_cycles"].get<int>(), 0);
  // --one-step starts from the format's literal state and reaches the same (unique) minimum.
  const CommandResult one = run_primo("deform " + scenario + " -o " + dir + "/d.obj --one-step --stats " +
                                      dir + "/d.json");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto direct = nlohmann::json::parse(read_text(dir + "/d.json"));
  EXPECT_EQ(direct["path_steps"], 0);
  EXPECT_NEAR(direct["energy"].get<double>(), 0.008368710955476165, 1e-6 * 0.008368710955476165);
}

TEST_F(DeformCli, MissingScenarioFile) {
  expect_error("deform " + dir + "/nope.json -o " + dir + "/o.obj", "nope.json", dir + "/o.obj");
}

TEST_F(DeformCli, MalformedScenario) {
  write_text(dir + "/bad.json", "{\"format\": \"primo-scenario/1\",\n \"mesh\": \"cube.obj\",,}");
  expect_error("deform " + dir + "/bad.json -o " + dir + "/o.obj", "bad.json", dir + "/o.obj");
}

TEST_F(DeformCli, UnknownKeyNamesItsPath) {
  write_text(dir + "/k.json", scenario_json("cube.obj", R"(, "prisms": {"heigth": 2})"));
  expect_error("deform " + dir + "/k.json -o " + dir + "/o.obj", "prisms.heigth", dir + "/o.obj");
}

TEST_F(DeformCli, MissingMeshFile) {
  write_text(dir + "/m.json", scenario_json("absent.obj"));
  expect_error("deform " + dir + "/m.json -o " + dir + "/o.obj", "absent.obj", dir + "/o.obj");
}

TEST_F(DeformCli, NonManifoldMesh) {
  // A fin: three faces on edge 1-2.
  write_text(dir + "/fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nv 1 1 1\n"
                               "f 1 2 3\nf 2 1 4\nf 1 2 5\nf 3 2 6\n");
  write_text(dir + "/fin.json", R"({"format": "primo-scenario/1", "mesh": "fin.obj"})");
  expect_error("deform " + dir + "/fin.json -o " + dir + "/o.obj", "fin.obj", dir + "/o.obj");
}

TEST_F(DeformCli, NonFiniteCoordinate) {
  std::string cube = kCube;
  cube.replace(cube.find("v 1 1 1"), 7, "v 1 nan 1");
  write_text(dir + "/nan.obj", cube);
  write_text(dir + "/nan.json", scenario_json("nan.obj"));
  expect_error("deform " + dir + "/nan.json -o " + dir + "/o.obj", "nan.obj", dir + "/o.obj");
}

TEST_F(DeformCli, FaceInTwoHandles) {
  write_text(dir + "/two.json", R"({"format": "primo-scenario/1", "mesh": "cube.obj",
    "handles": [{"name": "a", "select": {"faces": [0, 1]}, "fix": "all"},
                {"name": "b", "select": {"faces": [1]}, "fix": "all"}]})");
  expect_error("deform " + dir + "/two.json -o " + dir + "/o.obj", "'b'", dir + "/o.obj");
}

TEST_F(DeformCli, EmptySelectionNamesTheForce) {
  write_text(dir + "/f.json", scenario_json("cube.obj", R"(, "forces": [{"select": {"sphere": {"center": [9, 9, 9], "radius": 0.1}}, "target_offset": [0, 1, 0], "stiffness": 1}])"));
  expect_error("deform " + dir + "/f.json -o " + dir + "/o.obj", "forces[0]", dir + "/o.obj");
}

TEST_F(DeformCli, PipesFoldersAndDevicesAsInputsFailAtOnce) {
  ASSERT_EQ(0, ::mkfifo((dir + "/pipe.json").c_str(), 0600));
  ASSERT_EQ(0, ::mkfifo((dir + "/pipe.obj").c_str(), 0600));
  fs::create_directory(dir + "/folder.json");
  write_text(dir + "/piped-mesh.json", scenario_json("pipe.obj"));
  fs::create_symlink("/dev/urandom", dir + "/random.json");
  const struct {
    std::string scenario, needle;
  } cases[] = {
      {dir + "/pipe.json", "pipe.json: not a regular file (a named pipe)"},
      {dir + "/folder.json", "folder.json: not a regular file (a folder)"},
      {dir + "/piped-mesh.json", "pipe.obj: not a regular file (a named pipe)"},
      {dir + "/random.json", "random.json: not a regular file (a character device)"},
  };
  for (const auto& c : cases) {
    // Before the check, primo waited for a writer to the pipe, or read /dev/urandom, for ever.
    const CommandResult r =
        primo::test::run_primo_within(20, "deform " + c.scenario + " -o " + dir + "/out.obj");
    EXPECT_EQ(r.exit_code, 1) << c.scenario << " (124: still running after 20 s)";
    EXPECT_EQ(r.err, "primo deform: error: " + dir + "/" + c.needle + "\n");
    EXPECT_FALSE(fs::exists(dir + "/out.obj"));
  }
}

TEST_F(DeformCli, UnknownOutputFormatFailsBeforeSolving) {
  expect_error("deform " + dir + "/ok.json -o " + dir + "/o.xyz", "o.xyz", dir + "/o.xyz");
}

TEST_F(DeformCli, MissingOutputFolder) {
  expect_error("deform " + dir + "/ok.json -o " + dir + "/no/such/o.obj", "o.obj",
               dir + "/no/such/o.obj");
}

TEST_F(DeformCli, FailureKeepsAnExistingOutputFile) {
  write_text(dir + "/keep.obj", "precious");
  write_text(dir + "/bad.json", "{");
  const CommandResult r = run_primo("deform " + dir + "/bad.json -o " + dir + "/keep.obj");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(read_text(dir + "/keep.obj"), "precious");
}

TEST_F(DeformCli, StatisticsFailureRemovesTheMesh) {
  const CommandResult r = run_primo("deform " + dir + "/ok.json -o " + dir + "/o.obj --stats " + dir + "/missing/s.json");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/o.obj"));
}

TEST_F(DeformCli, AnyThreadCountWritesTheSameBytes) {
  // The Figure 2 tube (4,800 triangles) bent 90 degrees: enough work to be cut in chunks.
  const std::string scenario = primo::test::source_path("assets/scenarios/quality/fig2-bend-90.json");
  std::string first;
  for (const char* threads : {"1", "3"}) {
    const std::string out = dir + "/bend-" + threads + ".obj";
    const CommandResult r = run_primo("deform " + scenario + " -o " + out + " --threads " + threads);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string text = read_text(out);
    if (first.empty())
      first = text;
    else
      EXPECT_TRUE(text == first) << "--threads " << threads << " wrote other vertices";
  }
  const CommandResult bad = run_primo("deform " + scenario + " -o " + dir + "/x.obj --threads -2");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--threads"), std::string::npos) << bad.err;
}

TEST_F(DeformCli, GenerateLoopSubdividesTrianglesAndRefusesQuads) {
  const CommandResult tube = run_primo("generate cylinder --segments 8 --bands 6 --triangles -o " +
                                       dir + "/tube.obj");
  ASSERT_EQ(tube.exit_code, 0) << tube.err;
  const CommandResult r = run_primo("generate loop " + dir + "/tube.obj --steps 2 -o " + dir + "/fine.obj");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(primo::load_mesh(dir + "/fine.obj").n_faces(), size_t(16 * 8 * 6 * 2));
  expect_error("generate loop " + dir + "/cube.obj -o " + dir + "/cube-fine.obj", "triangle",
               dir + "/cube-fine.obj");
}

namespace {

// The file without its `v` and `vn` lines, and the `v` lines' numbers.
std::pair<std::string, std::vector<double>> split_positions(const std::string& text) {
  std::string rest;
  std::vector<double> positions;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("vn ", 0) == 0) continue;
    if (line.rfind("v ", 0) != 0) {
      rest += line + "\n";
      continue;
    }
    std::istringstream words(line.substr(2));
    for (std::string word; words >> word;) positions.push_back(std::stod(word));
  }
  return {rest, positions};
}

}  // namespace

TEST_F(DeformCli, ObjAttributesSurviveAPose) {
  // The textured cube of tests/data/textured_cube: UVs, normals, materials, groups.
  const std::string cube = read_text(primo::test::source_path("tests/data/textured_cube/cube.obj"));
  write_text(dir + "/textured.obj", cube);
  write_text(dir + "/cube.mtl", read_text(primo::test::source_path("tests/data/textured_cube/cube.mtl")));
  write_text(dir + "/still.json", R"({"format": "primo-scenario/1", "mesh": "textured.obj",
    "handles": [{"name": "bottom", "select": {"faces": [0]}, "fix": "all"}]})");
  write_text(dir + "/posed.json", scenario_json("textured.obj"));
  const CommandResult still = run_primo("deform " + dir + "/still.json -o " + dir + "/still.obj");
  ASSERT_EQ(still.exit_code, 0) << still.err;
  const auto input = split_positions(cube);
  const auto unposed = split_positions(read_text(dir + "/still.obj"));
  EXPECT_EQ(unposed.first, input.first);    // byte for byte
  EXPECT_EQ(unposed.second, input.second);  // bit for bit

  const CommandResult posed = run_primo("deform " + dir + "/posed.json -o " + dir + "/posed.obj");
  ASSERT_EQ(posed.exit_code, 0) << posed.err;
  const auto moved = split_positions(read_text(dir + "/posed.obj"));
  EXPECT_EQ(moved.first, input.first);
  EXPECT_NE(moved.second, input.second);
}
