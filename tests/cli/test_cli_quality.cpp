// `primo metrics` and `primo bench quality` (docs/quality.md): run headless on small meshes
// written here; nothing needs the shared meshes.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

using primo::test::CommandResult;
using primo::test::read_json;
using primo::test::run_primo;

namespace {


// A small triangle cylinder (radius 0.25, length 2, 8 around, 12 bands) and its scenario:
// bottom band fixed, top band moved by `transform` (scenario JSON).
std::string write_small_case(const std::string& dir, const std::string& name,
                             const std::string& transform) {
  primo::save_mesh(primo::make_cylinder(0.25, 2.0, 8, 12, primo::FaceShape::Triangles),
                   dir + "/small-cylinder.obj");
  const std::string path = dir + "/" + name + ".json";
  primo::test::write_text(path, R"({
  "format": "primo-scenario/1",
  "mesh": "small-cylinder.obj",
  "handles": [
    { "name": "bottom", "select": { "box": { "min": [-1, -0.01, -1], "max": [1, 0.17, 1] } }, "fix": "all" },
    { "name": "top", "select": { "box": { "min": [-1, 1.83, -1], "max": [1, 2.01, 1] } }, "fix": "all",
      "transform": )" + transform + R"( }
  ]
})");
  return path;
}

}  // namespace

TEST(MetricsCli, PrintsTheTableAndWritesEveryKey) {
  const std::string dir = primo::test::temp_dir();
  const primo::Mesh rest = primo::make_cylinder(0.25, 2.0, 10, 6, primo::FaceShape::Triangles);
  primo::Mesh doubled = rest;
  for (auto v : doubled.vertices()) doubled.point(v) *= 2.0;
  primo::save_mesh(rest, dir + "/rest.obj");
  primo::save_mesh(doubled, dir + "/doubled.obj");

  const CommandResult r =
      run_primo("metrics " + dir + "/rest.obj " + dir + "/doubled.obj --json " + dir + "/m.json");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  for (const char* row : {"volume change %", "area change %", "dihedral change RMS",
                          "edge length change max %", "fold-overs", "self-intersecting face pairs"})
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
  EXPECT_NE(r.out.find("+700.0"), std::string::npos) << r.out;  // volume x 8

  const nlohmann::json m = read_json(dir + "/m.json");
  for (const char* key :
       {"volume_change_percent", "area_change_percent", "dihedral_change_rms_deg",
        "dihedral_change_max_deg", "edge_change_rms_percent", "edge_change_max_percent",
        "fold_overs", "self_intersecting_pairs", "boundary_loops", "rest", "deformed"})
    EXPECT_TRUE(m.contains(key)) << key;
  EXPECT_NEAR(m["volume_change_percent"].get<double>(), 700.0, 1e-9);
  EXPECT_NEAR(m["area_change_percent"].get<double>(), 300.0, 1e-9);
  EXPECT_NEAR(m["edge_change_max_percent"].get<double>(), 100.0, 1e-9);
  EXPECT_EQ(m["self_intersecting_pairs"].get<int>(), 0);
  EXPECT_EQ(m["boundary_loops"].get<int>(), 2);
}

TEST(MetricsCli, MismatchedOrUnreadableMeshesAreOneLineErrors) {
  const std::string dir = primo::test::temp_dir();
  primo::save_mesh(primo::make_cylinder(0.25, 2.0, 10, 6, primo::FaceShape::Triangles),
                   dir + "/a.obj");
  primo::save_mesh(primo::make_cylinder(0.25, 2.0, 10, 7, primo::FaceShape::Triangles),
                   dir + "/b.obj");
  CommandResult r = run_primo("metrics " + dir + "/a.obj " + dir + "/b.obj --json " + dir + "/m.json");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(dir + "/b.obj"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("same connectivity"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(primo::test::exists(dir + "/m.json"));

  r = run_primo("metrics " + dir + "/a.obj " + dir + "/missing.obj");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(dir + "/missing.obj"), std::string::npos) << r.err;
}

TEST(BenchQualityCli, RunsPrimoAndBothPeersOnASmallCase) {
  const std::string dir = primo::test::temp_dir();
  const std::string scenario =
      write_small_case(dir, "small-shift", R"({ "translate": [0.3, 0, 0] })");
  const CommandResult r = run_primo("bench quality " + scenario + " --json " + dir +
                                    "/q.json --output-dir " + dir + "/meshes");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json q = read_json(dir + "/q.json");
  ASSERT_EQ(q["cases"].size(), 1u);
  const nlohmann::json& c = q["cases"][0];
  EXPECT_EQ(c["case"], "small-shift");
  ASSERT_EQ(c["runs"].size(), 3u) << c.dump(2);
  const char* methods[] = {"PriMo", "ARAP", "SR-ARAP"};
  for (int i = 0; i < 3; ++i) {
    const nlohmann::json& run = c["runs"][i];
    EXPECT_EQ(run["method"], methods[i]);
    EXPECT_GT(run["seconds"].get<double>(), 0.0);
    EXPECT_EQ(run["metrics"]["faces"].get<int>(), 192);
    EXPECT_EQ(run["metrics"]["self_intersecting_pairs"].get<int>(), 0);
    EXPECT_GT(run["metrics"]["edge_change_max_percent"].get<double>(), 0.0);  // it did deform
  }
  EXPECT_GT(c["runs"][0]["energy"].get<double>(), 0.0);
  EXPECT_TRUE(c["runs"][0]["converged"].get<bool>());
  EXPECT_GT(c["time_ratio_primo_over_sr_arap"].get<double>(), 0.0);
  for (const char* file : {"small-shift-primo.obj", "small-shift-arap.obj", "small-shift-sr-arap.obj"})
    EXPECT_TRUE(primo::test::exists(dir + "/meshes/" + file)) << file;
  // The table has a row per method.
  EXPECT_NE(r.out.find("SR-ARAP"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("small-shift"), std::string::npos) << r.out;
}

TEST(BenchQualityCli, PolygonMeshesAndMissingMeshesAreExplained) {
  const std::string dir = primo::test::temp_dir();
  // The shipped quad bar: PriMo only, with the reason.
  const std::string quad_case = dir + "/quad-bar.json";
  primo::test::write_text(quad_case, R"({
  "format": "primo-scenario/1",
  "mesh": ")" + primo::test::source_path("assets/meshes/bar.obj") + R"(",
  "handles": [
    { "select": { "box": { "min": [-1, -0.01, -1], "max": [1, 0.05, 1] } }, "fix": "all" },
    { "select": { "box": { "min": [-1, 0.95, -1], "max": [1, 1.01, 1] } }, "fix": "all",
      "transform": { "translate": [0.1, 0, 0] } }
  ]
})");
  const std::string missing_case = dir + "/missing.json";
  primo::test::write_text(missing_case, R"({
  "format": "primo-scenario/1", "mesh": "no-such-mesh.obj",
  "handles": [ { "select": { "all": true }, "fix": "all" } ]
})");
  const CommandResult r = run_primo("bench quality " + quad_case + " " + missing_case +
                                    " --mesh-dir " + dir + " --json " + dir + "/q.json");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("skipped: no-such-mesh.obj not found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no peers: polygon mesh"), std::string::npos) << r.out;
  const nlohmann::json q = read_json(dir + "/q.json");
  ASSERT_EQ(q["cases"].size(), 2u);
  EXPECT_EQ(q["cases"][0]["runs"].size(), 1u);
  EXPECT_TRUE(q["cases"][0]["time_ratio_primo_over_sr_arap"].is_null());
  EXPECT_TRUE(q["cases"][1].contains("skipped"));
}
