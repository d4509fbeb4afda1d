// Scenario format: parsing the spec's examples, strict validation with JSON paths in the
// messages, the writer's round trip, and resolving selections, regions and handles on meshes
// built here (so these tests do not depend on the mesh loader).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "primo/util/error.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/model/prism_layer.h"
#include "primo/scenario/scenario.h"
#include "support/test_support.h"

namespace fs = std::filesystem;

namespace primo {
namespace {

// A grid of quads in the z = 0 plane with the given x and y coordinate lines. Face (i, j) has
// index j * (xs.size() - 1) + i; vertex (i, j) has index j * xs.size() + i.
Mesh grid_mesh(const std::vector<double>& xs, const std::vector<double>& ys) {
  Mesh mesh;
  std::vector<Mesh::VertexHandle> vertices;
  for (double y : ys)
    for (double x : xs) vertices.push_back(mesh.add_vertex(Vec3(x, y, 0.0)));
  const size_t row = xs.size();
  for (size_t j = 0; j + 1 < ys.size(); ++j)
    for (size_t i = 0; i + 1 < xs.size(); ++i)
      mesh.add_face(std::vector<Mesh::VertexHandle>{
          vertices[j * row + i], vertices[j * row + i + 1], vertices[(j + 1) * row + i + 1],
          vertices[(j + 1) * row + i]});
  return mesh;
}

// 4 x 4 unit quads over [0, 4]^2: face (i, j) has centroid (i + 0.5, j + 0.5, 0).
Mesh unit_grid() { return grid_mesh({0, 1, 2, 3, 4}, {0, 1, 2, 3, 4}); }

// The message of the Error `action` throws; fails the test if it throws nothing.
std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  }
  ADD_FAILURE() << "no primo::Error was thrown";
  return "";
}

void expect_contains(const std::string& message, std::initializer_list<const char*> parts) {
  for (const char* part : parts)
    EXPECT_NE(message.find(part), std::string::npos)
        << "message \"" << message << "\" lacks \"" << part << "\"";
}

// Loads `text` from a file named bad.json and returns the error, which must name the file.
std::string load_error(const std::string& text) {
  const std::string path = test::temp_dir() + "/bad.json";
  test::write_text(path, text);
  const std::string message = error_of([&] { load_scenario(path); });
  expect_contains(message, {"bad.json: "});
  return message;
}

const std::string kHead = R"("format": "primo-scenario/1", "mesh": "m.obj")";

// A scenario text with the given extra top-level members.
std::string scenario_text(const std::string& members = "") {
  return "{" + kHead + (members.empty() ? "" : ", " + members) + "}";
}

// One handle around `handle_body` (the members of handles[0]).
std::string handle_text(const std::string& handle_body) {
  return scenario_text(R"("handles": [{)" + handle_body + "}]");
}

void expect_same_vec(const Vec3& a, const Vec3& b, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_EQ(a[k], b[k]) << what << "[" << k << "]";
}

void expect_same_selection(const Selection& a, const Selection& b, const std::string& what) {
  EXPECT_EQ(a.kind, b.kind) << what;
  EXPECT_EQ(a.indices, b.indices) << what;
  expect_same_vec(a.min, b.min, what + ".min");
  expect_same_vec(a.max, b.max, what + ".max");
  expect_same_vec(a.center, b.center, what + ".center");
  EXPECT_EQ(a.radius, b.radius) << what;
}

void expect_same_scenario(const Scenario& a, const Scenario& b) {
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.mesh, b.mesh);
  EXPECT_EQ(a.mesh_path, b.mesh_path);
  EXPECT_EQ(a.prisms.height, b.prisms.height);
  EXPECT_EQ(a.prisms.normal_blend, b.prisms.normal_blend);
  EXPECT_EQ(a.prisms.width, b.prisms.width);
  ASSERT_EQ(a.regions.size(), b.regions.size());
  for (size_t i = 0; i < a.regions.size(); ++i) {
    const RegionSpec& x = a.regions[i];
    const RegionSpec& y = b.regions[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.where, y.where);
    expect_same_selection(x.select, y.select, x.where);
    EXPECT_EQ(x.height, y.height) << x.where;
    EXPECT_EQ(x.width, y.width) << x.where;
  }
  ASSERT_EQ(a.handles.size(), b.handles.size());
  for (size_t i = 0; i < a.handles.size(); ++i) {
    const HandleSpec& x = a.handles[i];
    const HandleSpec& y = b.handles[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.where, y.where);
    expect_same_selection(x.select, y.select, x.where);
    EXPECT_EQ(x.fix, y.fix) << x.where;
    expect_same_vec(x.transform.translate, y.transform.translate, x.where + ".translate");
    expect_same_vec(x.transform.axis, y.transform.axis, x.where + ".axis");
    EXPECT_EQ(x.transform.angle_deg, y.transform.angle_deg) << x.where;
    ASSERT_EQ(x.transform.center.has_value(), y.transform.center.has_value()) << x.where;
    if (x.transform.center)
      expect_same_vec(*x.transform.center, *y.transform.center, x.where + ".center");
  }
  ASSERT_EQ(a.forces.size(), b.forces.size());
  for (size_t i = 0; i < a.forces.size(); ++i) {
    const ForceSpec& x = a.forces[i];
    const ForceSpec& y = b.forces[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.where, y.where);
    expect_same_selection(x.select, y.select, x.where);
    expect_same_vec(x.target_offset, y.target_offset, x.where + ".target_offset");
    EXPECT_EQ(x.stiffness, y.stiffness) << x.where;
  }
  EXPECT_EQ(a.solver.max_iterations, b.solver.max_iterations);
  EXPECT_EQ(a.solver.tolerance, b.solver.tolerance);
  EXPECT_EQ(a.solver.method, b.solver.method);
}

// --- the shipped examples --------------------------------------------------------------

TEST(ScenarioExamples, CylinderBendParsesWithMeshBesideIt) {
  const std::string path = test::shared_path("spec/examples/cylinder-small-bend-45.json");
  if (!test::exists(path)) GTEST_SKIP() << "shared examples not present: " << path;
  const Scenario s = load_scenario(path);
  EXPECT_EQ(s.source, path);
  EXPECT_EQ(s.mesh, "cylinder-small.obj");
  EXPECT_EQ(fs::path(s.mesh_path), fs::path(path).parent_path() / "cylinder-small.obj");
  EXPECT_TRUE(fs::exists(s.mesh_path)) << s.mesh_path;
  EXPECT_EQ(s.prisms.height, 1.0);
  EXPECT_EQ(s.prisms.normal_blend, 0.0);
  EXPECT_EQ(s.prisms.width, 1.0);
  ASSERT_EQ(s.handles.size(), 2u);
  EXPECT_EQ(s.handles[0].name, "bottom");
  EXPECT_EQ(s.handles[0].select.kind, Selection::Kind::Box);
  expect_same_vec(s.handles[0].select.max, Vec3(1, 0.05, 1), "bottom.max");
  EXPECT_EQ(s.handles[0].transform.angle_deg, 0.0);
  const HandleSpec& top = s.handles[1];
  EXPECT_EQ(top.name, "top");
  EXPECT_EQ(top.where, "handles[1]");
  EXPECT_EQ(top.fix, Fix::All);
  expect_same_vec(top.transform.translate, Vec3(0.3729232285780566, -0.09968368384289394, 0),
                  "top.translate");
  expect_same_vec(top.transform.axis, Vec3(0, 0, 1), "top.axis");
  EXPECT_EQ(top.transform.angle_deg, -45.0);
  ASSERT_TRUE(top.transform.center.has_value());
  expect_same_vec(*top.transform.center, Vec3(0, 1, 0), "top.center");
  EXPECT_TRUE(s.regions.empty());
  EXPECT_TRUE(s.forces.empty());
}

TEST(ScenarioExamples, HexsphereOrientationParsesWithMeshBesideIt) {
  const std::string path = test::shared_path("spec/examples/hexsphere-orientation.json");
  if (!test::exists(path)) GTEST_SKIP() << "shared examples not present: " << path;
  const Scenario s = load_scenario(path);
  EXPECT_EQ(fs::path(s.mesh_path), fs::path(path).parent_path() / "hexsphere.off");
  EXPECT_TRUE(fs::exists(s.mesh_path)) << s.mesh_path;
  EXPECT_EQ(s.prisms.height, 2.0);
  ASSERT_EQ(s.regions.size(), 1u);
  EXPECT_EQ(s.regions[0].select.kind, Selection::Kind::Sphere);
  expect_same_vec(s.regions[0].select.center, Vec3(1, 0, 0), "region.center");
  EXPECT_EQ(s.regions[0].select.radius, 0.8);
  EXPECT_FALSE(s.regions[0].height.has_value());
  EXPECT_EQ(s.regions[0].width, std::optional<double>(1.2));
  ASSERT_EQ(s.handles.size(), 2u);
  EXPECT_EQ(s.handles[1].name, "north");
  EXPECT_EQ(s.handles[1].fix, Fix::Orientation);
  EXPECT_EQ(s.handles[1].transform.angle_deg, 45.0);
  expect_same_vec(s.handles[1].transform.axis, Vec3(0, 1, 0), "north.axis");
  expect_same_vec(s.handles[1].transform.translate, Vec3::Zero(), "north.translate");
  EXPECT_FALSE(s.handles[1].transform.center.has_value());
}

// --- parsing -----------------------------------------------------------------------------

TEST(ScenarioParse, DefaultsWhenOptionalKeysAreAbsent) {
  const Scenario s = parse_scenario(scenario_text(), "");
  EXPECT_EQ(s.source, "");
  EXPECT_EQ(s.mesh, "m.obj");
  EXPECT_EQ(s.mesh_path, "m.obj");  // relative to the current folder
  EXPECT_EQ(s.prisms.height, 1.0);
  EXPECT_EQ(s.prisms.normal_blend, 0.0);
  EXPECT_EQ(s.prisms.width, 1.0);
  EXPECT_TRUE(s.regions.empty());
  EXPECT_TRUE(s.handles.empty());
  EXPECT_TRUE(s.forces.empty());
  EXPECT_EQ(s.solver.max_iterations, 100);
  EXPECT_EQ(s.solver.tolerance, 1e-8);
  EXPECT_EQ(s.solver.method, SolverMethod::Default);
}

TEST(ScenarioParse, MeshPathIsRelativeToTheScenarioFolder) {
  EXPECT_EQ(fs::path(parse_scenario(scenario_text(), "cases/a/s.json").mesh_path),
            fs::path("cases/a/m.obj"));
  const std::string absolute = R"({"format": "primo-scenario/1", "mesh": "/data/m.obj"})";
  EXPECT_EQ(parse_scenario(absolute, "cases/a/s.json").mesh_path, "/data/m.obj");
}

TEST(ScenarioParse, ReadsEveryKeyOfTheSpecExample) {
  const std::string text = R"({
    "format": "primo-scenario/1",
    "mesh": "meshes/bar.obj",
    "prisms": { "height": 0.0, "normal_blend": -0.5, "width": 0.75 },
    "regions": [
      { "name": "soft", "select": { "sphere": { "center": [0, 1, 0], "radius": 0.2 } }, "height": 0.25 }
    ],
    "handles": [
      { "name": "base", "select": { "box": { "min": [-1, -1, -1], "max": [1, -0.9, 1] } }, "fix": "all" },
      { "select": { "vertices": [4, 2] }, "fix": "position",
        "transform": { "translate": [0.5, 0, 0], "axis": [0, 0, 1], "angle_deg": 90, "center": [0, 1, 0] } },
      { "select": { "all": true }, "fix": "orientation", "transform": { "axis": [0, 0, 0] } }
    ],
    "forces": [
      { "name": "pull", "select": { "faces": [12, 13] }, "target_offset": [0, 0.3, 0], "stiffness": 10.0 }
    ],
    "solver": { "max_iterations": 7.0, "tolerance": 0, "method": "local" }
  })";
  const Scenario s = parse_scenario(text, "dir/s.json");
  EXPECT_EQ(fs::path(s.mesh_path), fs::path("dir/meshes/bar.obj"));
  EXPECT_EQ(s.prisms.height, 0.0);  // a flat membrane is allowed
  EXPECT_EQ(s.prisms.normal_blend, -0.5);
  EXPECT_EQ(s.prisms.width, 0.75);
  ASSERT_EQ(s.regions.size(), 1u);
  EXPECT_EQ(s.regions[0].name, "soft");
  EXPECT_EQ(s.regions[0].where, "regions[0]");
  EXPECT_EQ(s.regions[0].height, std::optional<double>(0.25));
  EXPECT_FALSE(s.regions[0].width.has_value());
  ASSERT_EQ(s.handles.size(), 3u);
  EXPECT_EQ(s.handles[0].fix, Fix::All);
  EXPECT_FALSE(s.handles[0].transform.center.has_value());
  EXPECT_EQ(s.handles[1].name, "");
  EXPECT_EQ(s.handles[1].select.kind, Selection::Kind::Vertices);
  EXPECT_EQ(s.handles[1].select.indices, (std::vector<int>{4, 2}));
  EXPECT_EQ(s.handles[1].fix, Fix::Position);
  EXPECT_EQ(s.handles[1].transform.angle_deg, 90.0);
  expect_same_vec(s.handles[1].transform.translate, Vec3(0.5, 0, 0), "translate");
  EXPECT_EQ(s.handles[2].select.kind, Selection::Kind::All);
  EXPECT_EQ(s.handles[2].fix, Fix::Orientation);
  ASSERT_EQ(s.forces.size(), 1u);
  EXPECT_EQ(s.forces[0].name, "pull");
  EXPECT_EQ(s.forces[0].where, "forces[0]");
  EXPECT_EQ(s.forces[0].select.indices, (std::vector<int>{12, 13}));
  expect_same_vec(s.forces[0].target_offset, Vec3(0, 0.3, 0), "target_offset");
  EXPECT_EQ(s.forces[0].stiffness, 10.0);
  EXPECT_EQ(s.solver.max_iterations, 7);  // 7.0 is an integer in JSON's eyes
  EXPECT_EQ(s.solver.tolerance, 0.0);
  EXPECT_EQ(s.solver.method, SolverMethod::Local);
}

TEST(ScenarioParse, HierarchicalMethodRoundTrips) {
  const Scenario s = parse_scenario(
      R"({"format": "primo-scenario/1", "mesh": "m.obj", "solver": {"method": "hierarchical"}})", "");
  EXPECT_EQ(s.solver.method, SolverMethod::Hierarchical);
  EXPECT_EQ(parse_scenario(scenario_to_json(s), "").solver.method, SolverMethod::Hierarchical);
}

// --- writing -----------------------------------------------------------------------------

TEST(ScenarioRoundTrip, WriteThenParseGivesAnEqualScenario) {
  Scenario s;
  s.source = "";
  s.mesh = "sub dir/mesh \"quoted\".obj";
  s.mesh_path = s.mesh;
  s.prisms.height = 1.0 / 3.0;
  s.prisms.normal_blend = -0.1;
  s.prisms.width = std::nextafter(1.0, 2.0);

  RegionSpec region;
  region.where = "regions[0]";
  region.select.kind = Selection::Kind::Sphere;
  region.select.center = Vec3(0.1, 0.2, 0.3);
  region.select.radius = 1e-300;
  region.height = 0.0;
  s.regions.push_back(region);
  region.name = "wide";
  region.where = "regions[1]";
  region.select = Selection{};  // all
  region.height.reset();
  region.width = 2.0 / 7.0;
  s.regions.push_back(region);

  HandleSpec handle;
  handle.name = "base";
  handle.where = "handles[0]";
  handle.select.kind = Selection::Kind::Box;
  handle.select.min = Vec3(-1, -std::sqrt(2.0), -1e10);
  handle.select.max = Vec3(1, -0.9, 1e10);
  s.handles.push_back(handle);
  handle.name = "";
  handle.where = "handles[1]";
  handle.select = Selection{};
  handle.select.kind = Selection::Kind::Faces;
  handle.select.indices = {5, 3, 3};
  handle.fix = Fix::Position;
  handle.transform.translate = Vec3(0.3729232285780566, -0.09968368384289394, 0.0);
  handle.transform.axis = Vec3(1, 2, 3);
  handle.transform.angle_deg = -45.123456789012345;
  handle.transform.center = Vec3(M_PI, -M_E, 1e-17);
  s.handles.push_back(handle);
  handle.where = "handles[2]";
  handle.select.kind = Selection::Kind::Vertices;
  handle.select.indices = {0};
  handle.fix = Fix::Orientation;
  handle.transform = TransformSpec{};
  handle.transform.axis = Vec3::Zero();  // allowed: the angle is 0
  s.handles.push_back(handle);

  ForceSpec force;
  force.name = "pull";
  force.where = "forces[0]";
  force.select.kind = Selection::Kind::Faces;
  force.select.indices = {12, 13};
  force.target_offset = Vec3(0, 0.3, -1e-5);
  force.stiffness = 10.5;
  s.forces.push_back(force);

  s.solver.max_iterations = 0;
  s.solver.tolerance = 1.2345678901234567e-9;
  s.solver.method = SolverMethod::Global;

  const std::string json = scenario_to_json(s);
  expect_same_scenario(s, parse_scenario(json, ""));

  // Written explicitly, pretty-printed with a 2-space indent.
  expect_contains(json, {"\n  \"format\": \"primo-scenario/1\"", "\"prisms\"", "\"normal_blend\"",
                         "\"solver\"", "\"max_iterations\": 0", "\"method\": \"global\"",
                         "\"translate\"", "\"angle_deg\"", "\"name\": \"base\""});
}

TEST(ScenarioRoundTrip, ParsedExampleSurvivesAndDefaultMethodStaysDefault) {
  const std::string text = handle_text(
      R"("name": "top", "select": {"box": {"min": [-1, 0.95, -1], "max": [1, 2, 1]}},
         "fix": "all", "transform": {"axis": [0, 0, 1], "angle_deg": 90})");
  const Scenario s = parse_scenario(text, "a/b.json");
  const std::string json = scenario_to_json(s);
  const Scenario again = parse_scenario(json, "a/b.json");
  expect_same_scenario(s, again);
  EXPECT_EQ(again.solver.method, SolverMethod::Default);
  EXPECT_EQ(json.find("\"method\""), std::string::npos) << json;
  EXPECT_EQ(json.find("\"center\""), std::string::npos) << json;
}

TEST(ScenarioRoundTrip, RefusesToWriteNonFiniteNumbers) {
  Scenario s = parse_scenario(scenario_text(), "");
  s.prisms.normal_blend = std::nan("");
  expect_contains(error_of([&] { scenario_to_json(s); }), {"prisms.normal_blend"});
}

// --- validation errors -------------------------------------------------------------------

TEST(ScenarioErrors, MalformedJsonReportsLineAndColumn) {
  const std::string message = load_error("{\n  \"format\": \"primo-scenario/1\",\n  \"mesh\" 2\n}");
  expect_contains(message, {"malformed JSON", "line 3, column 10"});
  expect_contains(load_error(""), {"malformed JSON", "line 1"});
  expect_contains(load_error(scenario_text() + "\n}"), {"malformed JSON", "line 2"});
  expect_contains(load_error("{\"format\": \"primo-scenario/1\",\n\"mesh\": \"m\", \"x\": 1e999}"),
                  {"malformed JSON", "line 2", "1e999"});
}

TEST(ScenarioErrors, MissingFileNamesThePath) {
  const std::string path = test::temp_dir() + "/absent.json";
  expect_contains(error_of([&] { load_scenario(path); }), {"absent.json"});
}

TEST(ScenarioErrors, RootMustBeAnObject) {
  expect_contains(load_error("[1, 2]"), {"(root): expected an object"});
}

TEST(ScenarioErrors, UnknownKeysAtEveryLevel) {
  expect_contains(load_error(scenario_text(R"("meshes": "x")")), {": meshes: unknown key"});
  expect_contains(load_error(scenario_text(R"("prisms": {"heigth": 1})")),
                  {": prisms.heigth: unknown key"});
  expect_contains(load_error(handle_text(R"("selectt": {"all": true}, "fix": "all")")),
                  {": handles[0].selectt: unknown key"});
  expect_contains(
      load_error(handle_text(R"("select": {"all": true}, "fix": "all", "transform": {"scale": 2})")),
      {": handles[0].transform.scale: unknown key"});
  expect_contains(
      load_error(handle_text(R"("select": {"box": {"min": [0,0,0], "mx": [1,1,1]}}, "fix": "all")")),
      {": handles[0].select.box.mx: unknown key"});
  expect_contains(load_error(scenario_text(R"("solver": {"max_iter": 3})")),
                  {": solver.max_iter: unknown key"});
  expect_contains(load_error(scenario_text(
                      R"("forces": [{"select": {"all": true}, "target_offset": [0,0,0], "stiffness": 1, "k": 2}])")),
                  {": forces[0].k: unknown key"});
  expect_contains(load_error(scenario_text(R"("regions": [{"select": {"all": true}, "hight": 2}])")),
                  {": regions[0].hight: unknown key"});
}

TEST(ScenarioErrors, DuplicateKeysAreNotSilentlyDropped) {
  expect_contains(load_error(scenario_text(R"("prisms": {"height": 1, "height": 2})")),
                  {": prisms.height: duplicate key"});
  expect_contains(
      load_error(scenario_text(R"("handles": [{"select": {"all": true}, "fix": "all"},)"
                               R"({"select": {"all": true}, "fix": "all", "fix": "position"}])")),
      {": handles[1].fix: duplicate key"});
}

TEST(ScenarioErrors, FormatMustBeVersion1) {
  expect_contains(load_error(R"({"format": "primo-scenario/2", "mesh": "m.obj"})"),
                  {": format: ", "primo-scenario/1"});
  expect_contains(load_error(R"({"mesh": "m.obj"})"), {": format: missing required key"});
}

TEST(ScenarioErrors, MeshIsARequiredString) {
  expect_contains(load_error(R"({"format": "primo-scenario/1"})"), {": mesh: missing required key"});
  expect_contains(load_error(R"({"format": "primo-scenario/1", "mesh": 3})"),
                  {": mesh: expected a string"});
  expect_contains(load_error(R"({"format": "primo-scenario/1", "mesh": ""})"), {": mesh: "});
}

TEST(ScenarioErrors, WrongTypesNameThePath) {
  expect_contains(load_error(scenario_text(R"("prisms": {"height": "1"})")),
                  {": prisms.height: expected a number"});
  expect_contains(load_error(scenario_text(R"("prisms": [])")), {": prisms: expected an object"});
  expect_contains(load_error(scenario_text(R"("handles": {})")), {": handles: expected an array"});
  expect_contains(load_error(scenario_text(R"("regions": [3])")), {": regions[0]: expected an object"});
  expect_contains(load_error(handle_text(
                      R"("select": {"all": true}, "fix": "all", "transform": {"translate": [1, 2]})")),
                  {": handles[0].transform.translate: expected an array of 3 numbers"});
  expect_contains(load_error(handle_text(
                      R"("select": {"all": true}, "fix": "all", "transform": {"center": [1, "2", 3]})")),
                  {": handles[0].transform.center[1]: expected a number"});
  expect_contains(load_error(handle_text(R"("name": 7, "select": {"all": true}, "fix": "all")")),
                  {": handles[0].name: expected a string"});
  expect_contains(load_error(handle_text(R"("select": {"all": true}, "fix": true)")),
                  {": handles[0].fix: expected a string"});
}

TEST(ScenarioErrors, ValueRanges) {
  expect_contains(load_error(scenario_text(R"("prisms": {"height": -0.1})")), {": prisms.height: "});
  expect_contains(load_error(scenario_text(R"("prisms": {"width": 0})")), {": prisms.width: "});
  expect_contains(load_error(scenario_text(R"("regions": [{"select": {"all": true}, "width": 0}])")),
                  {": regions[0].width: "});
  expect_contains(load_error(scenario_text(R"("regions": [{"select": {"all": true}, "height": -1}])")),
                  {": regions[0].height: "});
  expect_contains(load_error(scenario_text(R"("solver": {"tolerance": -1e-9})")),
                  {": solver.tolerance: "});
  expect_contains(load_error(scenario_text(R"("solver": {"method": "multigrid"})")),
                  {": solver.method: "});
  expect_contains(load_error(scenario_text(
                      R"("forces": [{"select": {"all": true}, "target_offset": [0,0,0], "stiffness": -2}])")),
                  {": forces[0].stiffness: "});
  expect_contains(load_error(scenario_text(R"("forces": [{"select": {"all": true}, "stiffness": 2}])")),
                  {": forces[0].target_offset: missing required key"});
  // The boundary values themselves are fine.
  EXPECT_NO_THROW(parse_scenario(
      scenario_text(R"("prisms": {"height": 0}, "regions": [{"select": {"all": true}, "height": 0}],)"
                    R"("solver": {"max_iterations": 0, "tolerance": 0})"),
      ""));
}

TEST(ScenarioErrors, FixIsRequiredAndOneOfThree) {
  expect_contains(load_error(handle_text(R"("select": {"all": true}, "fix": "rigid")")),
                  {": handles[0].fix: ", "\"rigid\""});
  expect_contains(load_error(handle_text(R"("select": {"all": true})")),
                  {": handles[0].fix: missing required key"});
  expect_contains(load_error(handle_text(R"("fix": "all")")),
                  {": handles[0].select: missing required key"});
}

TEST(ScenarioErrors, MaxIterationsMustBeANonNegativeInteger) {
  expect_contains(load_error(scenario_text(R"("solver": {"max_iterations": 10.5})")),
                  {": solver.max_iterations: "});
  expect_contains(load_error(scenario_text(R"("solver": {"max_iterations": -1})")),
                  {": solver.max_iterations: "});
  expect_contains(load_error(scenario_text(R"("solver": {"max_iterations": 1e12})")),
                  {": solver.max_iterations: "});
  EXPECT_EQ(parse_scenario(scenario_text(R"("solver": {"max_iterations": 1e3})"), "")
                .solver.max_iterations,
            1000);
}

TEST(ScenarioErrors, RotationNeedsANonZeroAxis) {
  expect_contains(load_error(handle_text(R"("select": {"all": true}, "fix": "all",)"
                                         R"("transform": {"axis": [0, 0, 0], "angle_deg": 30})")),
                  {": handles[0].transform.axis: "});
  expect_contains(load_error(handle_text(R"("select": {"all": true}, "fix": "all",)"
                                         R"("transform": {"angle_deg": 30})")),
                  {": handles[0].transform.axis: "});
  EXPECT_NO_THROW(parse_scenario(handle_text(R"("select": {"all": true}, "fix": "all",)"
                                             R"("transform": {"axis": [0, 0, 0], "angle_deg": 0})"),
                                 ""));
}

TEST(ScenarioErrors, SelectNeedsExactlyOneKind) {
  expect_contains(load_error(handle_text(R"("select": {"all": true, "faces": [1]}, "fix": "all")")),
                  {": handles[0].select: ", "exactly one"});
  expect_contains(load_error(handle_text(R"("select": {}, "fix": "all")")),
                  {": handles[0].select: ", "exactly one"});
  expect_contains(load_error(handle_text(R"("select": {"all": false}, "fix": "all")")),
                  {": handles[0].select.all: expected true"});
  expect_contains(load_error(handle_text(R"("select": "all", "fix": "all")")),
                  {": handles[0].select: expected an object"});
}

TEST(ScenarioErrors, SelectionContents) {
  expect_contains(load_error(handle_text(R"("select": {"faces": [1, -2]}, "fix": "all")")),
                  {": handles[0].select.faces[1]: "});
  expect_contains(load_error(handle_text(R"("select": {"vertices": [0.5]}, "fix": "all")")),
                  {": handles[0].select.vertices[0]: "});
  expect_contains(load_error(handle_text(R"("select": {"faces": 3}, "fix": "all")")),
                  {": handles[0].select.faces: expected an array"});
  expect_contains(
      load_error(handle_text(R"("select": {"box": {"min": [0, 2, 0], "max": [1, 1, 1]}}, "fix": "all")")),
      {": handles[0].select.box: ", "min > max in y"});
  expect_contains(load_error(handle_text(R"("select": {"box": {"min": [0, 0, 0]}}, "fix": "all")")),
                  {": handles[0].select.box.max: missing required key"});
  expect_contains(load_error(handle_text(
                      R"("select": {"sphere": {"center": [0, 0, 0], "radius": -1}}, "fix": "all")")),
                  {": handles[0].select.sphere.radius: "});
}

// --- resolving on a mesh -----------------------------------------------------------------

std::vector<int> resolve_on_grid(const std::string& select_json) {
  const Mesh mesh = unit_grid();
  const Scenario s =
      parse_scenario(handle_text(R"("select": )" + select_json + R"(, "fix": "all")"), "");
  return resolve_selection(s.handles[0].select, mesh, compute_face_geometry(mesh), "test");
}

TEST(ScenarioResolve, SelectionKinds) {
  EXPECT_EQ(resolve_on_grid(R"({"faces": [3, 1, 1]})"), (std::vector<int>{1, 3}));
  // Vertex (1, 1) is index 6 and touches faces 0, 1, 4, 5.
  EXPECT_EQ(resolve_on_grid(R"({"vertices": [6, 0]})"), (std::vector<int>{0, 1, 4, 5}));
  // Closed box: the centroid (1.5, 0.5) on its boundary is inside.
  EXPECT_EQ(resolve_on_grid(R"({"box": {"min": [0, 0, -1], "max": [1.5, 0.5, 1]}})"),
            (std::vector<int>{0, 1}));
  // Closed ball: centroids at distance exactly 1 are inside.
  EXPECT_EQ(resolve_on_grid(R"({"sphere": {"center": [0.5, 0.5, 0], "radius": 1}})"),
            (std::vector<int>{0, 1, 4}));
  EXPECT_EQ(resolve_on_grid(R"({"all": true})").size(), 16u);
}

TEST(ScenarioResolve, IndexOutOfRangeNamesOwnerAndIndex) {
  const Mesh mesh = unit_grid();
  const Scenario faces = parse_scenario(
      handle_text(R"("name": "top", "select": {"faces": [2, 16]}, "fix": "all")"), "cases/s.json");
  expect_contains(error_of([&] { resolve_scenario(faces, mesh); }),
                  {"cases/s.json: ", "handle 'top'", "16"});
  const Scenario vertices =
      parse_scenario(handle_text(R"("select": {"vertices": [25]}, "fix": "all")"), "cases/s.json");
  expect_contains(error_of([&] { resolve_scenario(vertices, mesh); }),
                  {"cases/s.json: ", "handles[0]", "vertex index 25"});
}

TEST(ScenarioResolve, EmptySelectionNamesTheOwner) {
  const Mesh mesh = unit_grid();
  const std::string far_box = R"({"box": {"min": [10, 10, 10], "max": [11, 11, 11]}})";
  const std::string dir = test::temp_dir();
  test::write_text(dir + "/empty.json",
                   scenario_text(R"("handles": [{"select": {"all": true}, "fix": "all"},)"
                                 R"({"name": "top", "select": )" + far_box + R"(, "fix": "all"}])"));
  expect_contains(error_of([&] { resolve_scenario(load_scenario(dir + "/empty.json"), mesh); }),
                  {"empty.json: ", "handle 'top'", "selects no face"});

  const Scenario unnamed = parse_scenario(
      scenario_text(R"("handles": [{"select": {"faces": [0]}, "fix": "all"},)"
                    R"({"select": )" + far_box + R"(, "fix": "all"}])"),
      "s.json");
  expect_contains(error_of([&] { resolve_scenario(unnamed, mesh); }),
                  {"s.json: ", "handles[1] selects no face"});

  const Scenario force = parse_scenario(
      scenario_text(R"("forces": [{"select": {"faces": []}, "target_offset": [0,0,0], "stiffness": 1}])"),
      "s.json");
  expect_contains(error_of([&] { resolve_scenario(force, mesh); }), {"forces[0] selects no face"});

  const Scenario region = parse_scenario(
      scenario_text(R"("regions": [{"name": "soft", "select": )" + far_box + R"(, "height": 2}])"),
      "s.json");
  expect_contains(error_of([&] { resolve_scenario(region, mesh); }),
                  {"region 'soft'", "selects no face"});
}

TEST(ScenarioResolve, FaceInTwoHandlesNamesBoth) {
  const Mesh mesh = unit_grid();
  const Scenario s = parse_scenario(
      scenario_text(R"("handles": [{"name": "left", "select": {"faces": [4, 5]}, "fix": "all"},)"
                    R"({"name": "right", "select": {"faces": [5, 6]}, "fix": "all"}])"),
      "s.json");
  expect_contains(error_of([&] { resolve_scenario(s, mesh); }),
                  {"s.json: ", "handle 'left'", "handle 'right'", "face 5"});
}

TEST(ScenarioResolve, LaterRegionWinsPerKey) {
  const Mesh mesh = unit_grid();
  const Scenario s = parse_scenario(
      scenario_text(R"("prisms": {"height": 0.5, "normal_blend": 0.25, "width": 0.9},)"
                    R"("regions": [{"select": {"faces": [0, 1]}, "height": 0.5, "width": 2},)"
                    R"({"select": {"faces": [1, 2]}, "height": 0.25},)"
                    R"({"select": {"faces": [15]}}])"),
      "");
  const ResolvedScenario r = resolve_scenario(s, mesh);
  EXPECT_EQ(r.prisms.height, 0.5);
  EXPECT_EQ(r.prisms.normal_blend, 0.25);
  EXPECT_EQ(r.prisms.width, 0.9);
  ASSERT_EQ(r.prisms.face_height_factor.size(), 16u);
  ASSERT_EQ(r.prisms.face_width_factor.size(), 16u);
  std::vector<double> height(16, 1.0), width(16, 1.0);
  height[0] = 0.5;
  height[1] = 0.25;
  height[2] = 0.25;
  width[0] = 2.0;
  width[1] = 2.0;
  EXPECT_EQ(r.prisms.face_height_factor, height);
  EXPECT_EQ(r.prisms.face_width_factor, width);
}

TEST(ScenarioResolve, DefaultCenterIsTheAreaWeightedCentroid) {
  // Uneven columns, so the area-weighted centroid differs from the plain one.
  const Mesh mesh = grid_mesh({0, 1, 3, 6, 10}, {0, 1, 2});
  const Scenario s = parse_scenario(
      scenario_text(R"("handles": [{"name": "row", "select": {"faces": [0, 1, 2, 3]}, "fix": "position",)"
                    R"("transform": {"translate": [0, 0, 2], "axis": [1, 1, 0], "angle_deg": 60}},)"
                    R"({"select": {"faces": [4]}, "fix": "all",)"
                    R"("transform": {"axis": [0, 0, 1], "angle_deg": 90, "center": [0, 0, 0]}}])"),
      "");
  const ResolvedScenario r = resolve_scenario(s, mesh);
  ASSERT_EQ(r.handles.size(), 2u);
  const Handle& row = r.handles[0];
  EXPECT_EQ(row.name, "row");
  EXPECT_EQ(row.fix, Fix::Position);
  EXPECT_EQ(row.faces, (std::vector<int>{0, 1, 2, 3}));

  // Column widths 1, 2, 3, 4 with centres 0.5, 2, 4.5, 8: x = (0.5 + 4 + 13.5 + 32) / 10 = 5.
  const Vec3 centroid(5.0, 0.5, 0.0);
  const Vec3 moved = row.transform.apply(centroid);
  EXPECT_NEAR((moved - (centroid + Vec3(0, 0, 2))).norm(), 0.0, 1e-12) << moved.transpose();
  // The full rotation is kept for a "position" handle.
  EXPECT_NEAR((row.transform.rotation * Vec3(1, 1, 0).normalized() -
               Vec3(1, 1, 0).normalized()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(std::acos((row.transform.rotation.trace() - 1.0) / 2.0), M_PI / 3.0, 1e-12);

  // An explicit center is used as given: a quarter turn about the origin.
  const Handle& second = r.handles[1];
  EXPECT_EQ(second.name, "");
  EXPECT_NEAR((second.transform.apply(Vec3(1, 0, 0)) - Vec3(0, 1, 0)).norm(), 0.0, 1e-12);
}

TEST(ScenarioResolve, ForcesAndSolverAreCarriedOver) {
  const Mesh mesh = unit_grid();
  const Scenario s = parse_scenario(
      scenario_text(R"("forces": [{"name": "pull", "select": {"vertices": [24]},)"
                    R"("target_offset": [0, 0.3, 0], "stiffness": 10}],)"
                    R"("solver": {"max_iterations": 12, "tolerance": 1e-6, "method": "global"})"),
      "");
  const ResolvedScenario r = resolve_scenario(s, mesh);
  ASSERT_EQ(r.forces.size(), 1u);
  EXPECT_EQ(r.forces[0].name, "pull");
  EXPECT_EQ(r.forces[0].faces, (std::vector<int>{15}));
  expect_same_vec(r.forces[0].target_offset, Vec3(0, 0.3, 0), "target_offset");
  EXPECT_EQ(r.forces[0].stiffness, 10.0);
  EXPECT_EQ(r.solver.max_iterations, 12);
  EXPECT_EQ(r.solver.tolerance, 1e-6);
  EXPECT_EQ(r.solver.method, SolverMethod::Global);
  EXPECT_TRUE(r.handles.empty());
}

// --- resolution-independent thickness (our extension: prisms.half_thickness) -------------

TEST(ScenarioHalfThickness, IsAFractionOfTheDiagonalAndRoundTrips) {
  const std::string text = R"({"format": "primo-scenario/1", "mesh": "m.obj",
                               "prisms": {"half_thickness": 0.04, "width": 0.9}})";
  const Scenario s = parse_scenario(text, "");
  EXPECT_EQ(s.prisms.height, 0.04);
  EXPECT_EQ(s.prisms.height_unit, HeightUnit::Diagonal);
  const std::string json = scenario_to_json(s);
  EXPECT_NE(json.find("\"half_thickness\""), std::string::npos) << json;
  EXPECT_EQ(json.find("\"height\""), std::string::npos) << json;
  const Scenario again = parse_scenario(json, "");
  EXPECT_EQ(again.prisms.height, 0.04);
  EXPECT_EQ(again.prisms.height_unit, HeightUnit::Diagonal);
  // The format's key keeps its meaning, and is what a file without either key gets.
  EXPECT_EQ(parse_scenario(scenario_text(), "").prisms.height_unit, HeightUnit::MeanEdgeLength);
}

TEST(ScenarioHalfThickness, BothKeysOrANegativeValueAreErrors) {
  expect_contains(error_of([] {
                    parse_scenario(R"({"format": "primo-scenario/1", "mesh": "m.obj",
                      "prisms": {"height": 1, "half_thickness": 0.05}})", "s.json");
                  }),
                  {"s.json", "prisms", "height", "half_thickness"});
  expect_contains(error_of([] {
                    parse_scenario(R"({"format": "primo-scenario/1", "mesh": "m.obj",
                      "prisms": {"half_thickness": -0.05}})", "s.json");
                  }),
                  {"s.json", "prisms.half_thickness"});
}

TEST(ScenarioHalfThickness, SetsTheLayerToThatFractionOfTheDiagonal) {
  const Mesh mesh = make_cylinder(0.25, 2.0, 12, 16, FaceShape::Quads);
  PrismParameters p = PrismParameters::product_default();
  p.height = 0.05;
  const PrismLayer layer = build_prism_layer(mesh, p);
  // Every corner offset (blend 0: along the unit vertex normal) is 5% of the diagonal long.
  for (const Vec3& offset : layer.corner_offset)
    EXPECT_NEAR(offset.norm(), 0.05 * layer.bounding_box_diagonal, 1e-12);
  p.height_unit = HeightUnit::MeanEdgeLength;
  p.height = 1.0;
  EXPECT_NEAR(build_prism_layer(mesh, p).corner_offset[0].norm(), layer.mean_edge_length, 1e-12);
}

// --- solved state and editor metadata (our extensions) ------------------------------------

TEST(ScenarioSolvedState, RoundTripsEveryDigitAndIsCheckedAgainstTheMesh) {
  Scenario s = parse_scenario(scenario_text(), "");
  RigidTransform m;
  m.rotation = Eigen::AngleAxisd(2.0, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  m.translation = Vec3(0.1, -1.0 / 3.0, 2e-17);
  s.solved_state = SolvedStateSpec{{m, RigidTransform::identity()}};
  s.editor = EditorSpec{};
  const Scenario again = parse_scenario(scenario_to_json(s), "");
  ASSERT_TRUE(again.solved_state.has_value());
  ASSERT_EQ(again.solved_state->face_motions.size(), 2u);
  EXPECT_LT((again.solved_state->face_motions[0].rotation - m.rotation).norm(), 1e-15);
  EXPECT_EQ(again.solved_state->face_motions[0].translation, m.translation);
  EXPECT_TRUE(again.editor.has_value());
  // Two motions for a mesh of one face: an error naming the key and both counts.
  const Mesh one = make_grid(1, 1, 1, 1, FaceShape::Quads);
  expect_contains(error_of([&] { resolve_scenario(again, one); }),
                  {"solved_state.face_motions", "2 motions", "1 faces"});
}

TEST(ScenarioSolvedState, BadMotionsAndFixedRegionsAreErrors) {
  auto error = [](const std::string& members) {
    return error_of([&] { parse_scenario(scenario_text(members), "s.json"); });
  };
  expect_contains(error(R"("solved_state": {"face_motions": [[1, 0, 0, 0, 0, 0]]})"),
                  {"s.json", "solved_state.face_motions[0]", "unit quaternion"});
  expect_contains(error(R"("solved_state": {"face_motions": [[2, 0, 0, 0, 0, 0, 0]]})"),
                  {"solved_state.face_motions[0]", "not a unit quaternion"});
  expect_contains(error(R"("solved_state": {"face_motions": [[1, 0, 0, 0, 0, 0, "x"]]})"),
                  {"solved_state.face_motions[0][6]", "expected a number"});
  expect_contains(error(R"("solved_state": {})"), {"solved_state.face_motions", "missing"});
  expect_contains(error(R"("editor": {"fixed_regions": [0]})"),
                  {"editor.fixed_regions[0]", "no handle 0"});
}

TEST(ScenarioEditorMirrorPairs, RoundTripAndBadPairsAreErrors) {
  const std::string two_handles = R"("handles": [
      {"name": "a", "select": {"faces": [0]}, "fix": "all"},
      {"name": "b", "select": {"faces": [1]}, "fix": "all"}])";
  const std::string one_force = R"("forces": [
      {"name": "f", "select": {"faces": [0]}, "stiffness": 1, "target_offset": [0, 0, 0]}])";
  auto with = [&](const std::string& editor) {
    return scenario_text(two_handles + ", " + one_force + ", \"editor\": " + editor);
  };
  Scenario s = parse_scenario(with(R"({"mirror_pairs": [{"handles": [1, 0], "axis": "y"}]})"), "");
  ASSERT_TRUE(s.editor);
  ASSERT_EQ(s.editor->mirror_pairs.size(), 1u);
  EXPECT_FALSE(s.editor->mirror_pairs[0].forces);
  EXPECT_EQ(s.editor->mirror_pairs[0].first, 1);
  EXPECT_EQ(s.editor->mirror_pairs[0].second, 0);
  EXPECT_EQ(s.editor->mirror_pairs[0].axis, 1);
  const Scenario again = parse_scenario(scenario_to_json(s), "");
  ASSERT_TRUE(again.editor);
  ASSERT_EQ(again.editor->mirror_pairs.size(), 1u);
  EXPECT_EQ(again.editor->mirror_pairs[0].axis, 1);
  EXPECT_TRUE(again.editor->fixed_regions.empty());

  auto error = [&](const std::string& pairs) {
    return error_of([&] { parse_scenario(with(R"({"mirror_pairs": )" + pairs + "}"), "m.json"); });
  };
  expect_contains(error(R"([{"handles": [0, 2], "axis": "x"}])"),
                  {"m.json", "editor.mirror_pairs[0].handles[1]", "no handle 2 (there are 2)"});
  expect_contains(error(R"([{"forces": [0, 1], "axis": "x"}])"),
                  {"editor.mirror_pairs[0].forces[1]", "no force 1 (there are 1)"});
  expect_contains(error(R"([{"handles": [0, 0], "axis": "x"}])"), {"its own mirror twin"});
  expect_contains(error(R"([{"handles": [0], "axis": "x"}])"), {"expected two indices"});
  expect_contains(error(R"([{"handles": [0, 1], "axis": "w"}])"),
                  {"editor.mirror_pairs[0].axis", "\"x\", \"y\" or \"z\""});
  expect_contains(error(R"([{"handles": [0, 1], "forces": [0, 0], "axis": "x"}])"),
                  {"exactly one of 'handles' and 'forces'"});
  expect_contains(error(R"([{"handles": [0, 1], "axis": "x"}, {"handles": [1, 0], "axis": "z"}])"),
                  {"editor.mirror_pairs[1]", "handle 1 is in two mirror pairs"});
}

TEST(ScenarioEditorOrientation, ParsesWritesAndReadsBack) {
  const Scenario plain = parse_scenario(scenario_text(), "");
  EXPECT_FALSE(plain.editor) << "no orientation unless the file gives one";
  Scenario s = parse_scenario(
      scenario_text(R"("editor": {"orientation": {"up": "+z", "front": "-y"}})"), "");
  ASSERT_TRUE(s.editor && s.editor->orientation);
  EXPECT_EQ(s.editor->orientation->up, (SignedAxis{2, 1}));
  EXPECT_EQ(s.editor->orientation->front, (SignedAxis{1, -1}));
  const Scenario again = parse_scenario(scenario_to_json(s), "");
  ASSERT_TRUE(again.editor && again.editor->orientation);
  EXPECT_EQ(*again.editor->orientation, *s.editor->orientation);
  // Every signed axis reads back as itself.
  for (int axis = 0; axis < 3; ++axis)
    for (const int sign : {1, -1}) {
      const SignedAxis a{axis, sign};
      const SignedAxis up{(axis + 1) % 3, 1};
      const ModelOrientation o = parse_model_orientation(
          R"({"up": ")" + signed_axis_name(up) + R"(", "front": ")" + signed_axis_name(a) + "\"}",
          "");
      EXPECT_EQ(o.front, a) << signed_axis_name(a);
      EXPECT_EQ(o.up, up);
    }
  EXPECT_EQ(signed_axis_name({0, -1}), "-x");
  // The default is the OBJ / glTF convention.
  EXPECT_EQ(ModelOrientation{}.up, (SignedAxis{1, 1}));
  EXPECT_EQ(ModelOrientation{}.front, (SignedAxis{2, 1}));
}

TEST(ScenarioEditorOrientation, BadOrientationsAreOneLineErrorsNamingTheKey) {
  auto error = [](const std::string& orientation) {
    return error_of([&] {
      parse_scenario(scenario_text(R"("editor": {"orientation": )" + orientation + "}"), "o.json");
    });
  };
  expect_contains(error(R"({"up": "y", "front": "+z"})"),
                  {"o.json", "editor.orientation.up", "\"+x\"", "got \"y\""});
  expect_contains(error(R"({"up": "+y", "front": "+w"})"),
                  {"editor.orientation.front", "got \"+w\""});
  expect_contains(error(R"({"up": "+y", "front": 2})"),
                  {"editor.orientation.front", "expected a string"});
  expect_contains(error(R"({"up": "+y"})"), {"editor.orientation.front", "missing required key"});
  expect_contains(error(R"({"up": "+y", "front": "-y"})"),
                  {"editor.orientation.front", "perpendicular to up (+y)", "got -y"});
  expect_contains(error(R"({"up": "+y", "front": "+z", "right": "+x"})"),
                  {"editor.orientation.right", "unknown key"});
  expect_contains(error(R"("+y")"), {"editor.orientation", "expected an object"});
  // The same object on its own (a mesh's orientation file): the same messages, from its root.
  expect_contains(error_of([] { parse_model_orientation(R"({"up": "+y", "front": "+y"})", "m.json"); }),
                  {"m.json: front:", "perpendicular"});
  expect_contains(error_of([] { parse_model_orientation("[1]", "m.json"); }),
                  {"m.json: (root): expected an object"});
}

}  // namespace
}  // namespace primo
