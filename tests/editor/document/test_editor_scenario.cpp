// Editor <-> scenario files: what the editor saves, `primo deform` reads back to the same
// handles, forces and per-face factors, and solves to the same mesh; opening it again gives
// back the editor's setup.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <iostream>
#include <thread>

#include "document/document.h"
#include "editor.h"
#include "support/editor_harness.h"
#include "document/paint.h"
#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/scenario/scenario.h"
#include "document/scenario_bridge.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;

namespace {

using harness::faces_where;

// A cylinder with a fixed base, a posed top, a position handle, a spring, and painted factors.
struct EditedCylinder {
  std::string dir = test::temp_dir();
  std::unique_ptr<Document> doc;
  EditedCylinder() {
    const std::string mesh_path = dir + "/meshes/cyl.obj";
    std::filesystem::create_directories(dir + "/meshes");
    save_mesh(make_cylinder(0.25, 1.0, 10, 12, FaceShape::Quads), mesh_path);
    doc = load_document(mesh_path);
    const MeshTopology& t = *doc->topology;
    EditState& s = doc->state;
    add_handle(s, t, t.rest_points, faces_where(t, 0.0, 0.09), HandleMode::Fixed);
    add_handle(s, t, t.rest_points, faces_where(t, 0.91, 1.0), HandleMode::Pose);
    s.handles[1].pose.translate = Vec3(0.2, -0.05, 0.1);
    s.handles[1].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec3(1, 0, 1).normalized()));
    add_handle(s, t, t.rest_points, faces_where(t, 0.5, 0.55), HandleMode::Position);
    s.handles[2].pose.translate = Vec3(0.05, 0, 0);
    add_handle(s, t, t.rest_points, faces_where(t, 0.7, 0.75), HandleMode::Spring);
    s.handles[3].pose.translate = Vec3(0, 0, 0.1);
    s.handles[3].stiffness = 3.5;
    s.height_factor = paint_factors(nullptr, t.n_faces, faces_where(t, 0.3, 0.45), 0.4);
    s.height_factor = paint_factors(s.height_factor, t.n_faces, faces_where(t, 0.6, 0.65), 2.0);
    s.width_factor = paint_factors(nullptr, t.n_faces, faces_where(t, 0.2, 0.3), 0.9);
    s.prisms = {0.8, HeightUnit::MeanEdgeLength, 1.0, 0.25};
  }
};

}  // namespace

TEST(EditorScenario, ExportResolvesToTheEditorsInputs) {
  EditedCylinder s;
  const std::string path = s.dir + "/setup.json";
  const Scenario exported = export_scenario(s.doc->state, s.doc->mesh_path, path, s.doc->solver);
  EXPECT_EQ(exported.mesh, "meshes/cyl.obj") << "mesh written relative to the scenario";
  EXPECT_EQ(exported.regions.size(), 3u) << "one region per painted value";
  EXPECT_EQ(exported.handles.size(), 3u);
  EXPECT_EQ(exported.forces.size(), 1u);
  test::write_text(path, scenario_to_json(exported));

  const Scenario read = load_scenario(path);
  const ResolvedScenario r = resolve_scenario(read, *s.doc->mesh);
  const DeformationInputs in = deformation_inputs(s.doc->state);
  EXPECT_EQ(r.prisms.height, in.params.height);
  EXPECT_EQ(r.prisms.normal_blend, in.params.normal_blend);
  EXPECT_EQ(r.prisms.face_height_factor, in.params.face_height_factor);
  EXPECT_EQ(r.prisms.face_width_factor, in.params.face_width_factor);
  ASSERT_EQ(r.handles.size(), in.handles.size());
  for (size_t h = 0; h < in.handles.size(); ++h) {
    EXPECT_EQ(r.handles[h].faces, in.handles[h].faces);
    EXPECT_EQ(r.handles[h].fix, in.handles[h].fix);
    EXPECT_EQ(r.handles[h].name, in.handles[h].name);
    EXPECT_LT((r.handles[h].transform.rotation - in.handles[h].transform.rotation).norm(), 1e-14);
    EXPECT_LT((r.handles[h].transform.translation - in.handles[h].transform.translation).norm(), 1e-14);
  }
  ASSERT_EQ(r.forces.size(), 1u);
  EXPECT_EQ(r.forces[0].faces, in.forces[0].faces);
  EXPECT_EQ(r.forces[0].target_offset, in.forces[0].target_offset);
  EXPECT_EQ(r.forces[0].stiffness, 3.5);

  // The same problem: the same solution.
  Deformer a(*s.doc->mesh, in.params, in.handles, in.forces);
  Deformer b(*s.doc->mesh, r.prisms, r.handles, r.forces);
  SolveOptions o;
  o.max_iterations = 60;
  a.solve(o);
  b.solve(o);
  const std::vector<Vec3> pa = a.vertex_positions(), pb = b.vertex_positions();
  for (size_t v = 0; v < pa.size(); ++v) ASSERT_LT((pa[v] - pb[v]).norm(), 1e-9);
}

TEST(EditorScenario, OpeningASavedScenarioGivesBackTheSetup) {
  EditedCylinder s;
  const std::string path = s.dir + "/again.json";
  test::write_text(path, scenario_to_json(export_scenario(s.doc->state, s.doc->mesh_path, path,
                                                          s.doc->solver)));
  const std::unique_ptr<Document> again = load_document(path);
  EXPECT_EQ(again->scenario_path, path);
  const EditState& a = s.doc->state;
  const EditState& b = again->state;
  ASSERT_EQ(a.handles.size(), b.handles.size());
  for (size_t h = 0; h < a.handles.size(); ++h) {
    EXPECT_EQ(a.handles[h].name, b.handles[h].name);
    EXPECT_EQ(a.handles[h].mode, b.handles[h].mode) << "Fixed comes back from fix all + identity";
    EXPECT_EQ(*a.handles[h].faces, *b.handles[h].faces);
    EXPECT_LT((a.handles[h].pose.translate - b.handles[h].pose.translate).norm(), 1e-14);
    EXPECT_LT(a.handles[h].pose.rotation.angularDistance(b.handles[h].pose.rotation), 1e-14);
  }
  EXPECT_EQ(*a.height_factor, *b.height_factor);
  EXPECT_EQ(*a.width_factor, *b.width_factor);
  EXPECT_TRUE(a.prisms == b.prisms);
}

TEST(EditorScenario, ShippedScenarioOpens) {
  const std::unique_ptr<Document> doc = load_document(test::source_path("assets/scenarios/spot-pose.json"));
  const EditState& s = doc->state;
  ASSERT_EQ(s.handles.size(), 3u);
  EXPECT_EQ(s.handles[0].name, "feet");
  EXPECT_EQ(s.handles[0].mode, HandleMode::Fixed);
  EXPECT_EQ(s.handles[1].mode, HandleMode::Position);
  EXPECT_EQ(s.handles[2].mode, HandleMode::Spring);
  EXPECT_EQ(s.handles[2].stiffness, 2.0);
  ASSERT_TRUE(s.height_factor);
  EXPECT_EQ(group_factors(s.height_factor).front().value, 0.4);
}

TEST(EditorScenario, BrokenFilesThrowErrors) {
  const std::string dir = test::temp_dir();
  test::write_text(dir + "/bad.json", "{\"format\": \"primo-scenario/1\"}");
  EXPECT_THROW(load_document(dir + "/bad.json"), Error);
  EXPECT_THROW(load_document(dir + "/missing.obj"), Error);
}

namespace {

using harness::settle;

Eigen::Quaterniond twist(double degrees) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * M_PI / 180.0, Vec3::UnitY()));
}

}  // namespace

TEST(EditorScenario, ASavedPoseReopensAndDeformsToThePoseShown) {
  // A tube twisted 240 degrees in two steps of 120: a solve from rest would twist it the
  // short way (-120 degrees), a very different pose; a fixed region made on the posed tube
  // (its fitted pose is not the identity); a spring.
  const std::string dir = test::temp_dir();
  Editor editor;
  const int top = harness::open_tube_with_fixed_base(editor, dir);
  Document& doc = *editor.document();
  const MeshTopology& t = *doc.topology;
  for (double degrees : {120.0, 240.0}) {
    doc.state.handles[size_t(top)].pose.rotation = twist(degrees);
    editor.commit("twist");
    ASSERT_TRUE(settle(editor));
  }
  add_handle(doc.state, t, editor.positions(), faces_where(t, 0.15, 0.25), HandleMode::Fixed);
  const int spring = add_handle(doc.state, t, editor.positions(), faces_where(t, 0.6, 0.7), HandleMode::Spring);
  doc.state.handles[size_t(spring)].pose.translate = Vec3(0.1, 0.0, 0.0);
  editor.commit("fixed region and spring");
  ASSERT_TRUE(settle(editor));
  const std::vector<Vec3> shown = editor.positions();
  std::vector<HandleMode> modes;
  for (const HandleGroup& g : doc.state.handles) modes.push_back(g.mode);
  ASSERT_EQ(modes[2], HandleMode::Fixed);
  ASSERT_FALSE(doc.state.handles[2].pose.is_identity());  // what used to come back as a Pose handle

  const std::string scenario = dir + "/pose.json";
  editor.save_scenario(scenario);
  const Scenario saved = load_scenario(scenario);
  ASSERT_TRUE(saved.solved_state.has_value());
  ASSERT_EQ(saved.solved_state->face_motions.size(), size_t(t.n_faces));
  const double diagonal = t.bbox_diagonal;

  // Reopened: the same pose and the same modes.
  Editor reopened;
  reopened.open(scenario);
  ASSERT_TRUE(settle(reopened));
  ASSERT_NE(reopened.document(), nullptr);
  std::vector<HandleMode> reopened_modes;
  for (const HandleGroup& g : reopened.document()->state.handles) reopened_modes.push_back(g.mode);
  EXPECT_EQ(reopened_modes, modes);
  const double reopened_apart = largest_point_distance(reopened.positions(), shown) / diagonal;
  EXPECT_LT(reopened_apart, 1e-6);

  // `primo deform` of the saved scenario: the pose shown.
  const test::CommandResult r = test::run_primo("deform " + scenario + " -o " + dir + "/out.obj");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Mesh out = load_mesh(dir + "/out.obj");
  std::vector<Vec3> deformed;
  for (auto v : out.vertices()) deformed.push_back(out.point(v));
  const double deform_apart = largest_point_distance(deformed, shown) / diagonal;
  EXPECT_LT(deform_apart, 1e-6);

  // Without the solved state the same scenario solves to another pose: the check means
  // something.
  Scenario bare = saved;
  bare.solved_state.reset();
  test::write_text(dir + "/bare.json", scenario_to_json(bare));
  ASSERT_EQ(test::run_primo("deform " + dir + "/bare.json -o " + dir + "/bare.obj").exit_code, 0);
  const Mesh bare_out = load_mesh(dir + "/bare.obj");
  std::vector<Vec3> from_rest;
  for (auto v : bare_out.vertices()) from_rest.push_back(bare_out.point(v));
  const double bare_apart = largest_point_distance(from_rest, shown) / diagonal;
  std::cout << "[ metric   ] saved pose, largest vertex distance to the pose shown: reopened "
            << reopened_apart << ", primo deform " << deform_apart
            << ", primo deform without the solved state " << bare_apart << " (of the diagonal)\n";
  EXPECT_GT(bare_apart, 0.05);
}
