// Pivots: a handle turns about a point the user places (on the surface, at the selection's
// centre, typed, or back at its rest centroid); placing it never moves the faces, is one undo
// step, follows a mirror twin, and is kept by scenarios and recorded sessions.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <memory>

#include "recording/document_recorder.h"
#include "support/editor_harness.h"
#include "document/pivot.h"
#include "primo/mesh/geometry.h"
#include "primo/io/mesh_io.h"
#include "primo/scenario/scenario.h"
#include "primo/sessions/session.h"
#include "document/scenario_bridge.h"
#include "recording/session_bridge.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;
using primo::editor::harness::Harness;

namespace {

constexpr double kDeg = M_PI / 180.0;

// The largest distance between where two rigid motions put the group's rest vertices.
double largest_difference(const RigidTransform& a, const RigidTransform& b, const MeshTopology& t,
                          const std::vector<int>& faces) {
  double worst = 0.0;
  for (int f : faces)
    for (int k = t.face_begin[f]; k < t.face_begin[f + 1]; ++k) {
      const Vec3& x = t.rest_points[t.face_vertices[k]];
      worst = std::max(worst, (a.apply(x) - b.apply(x)).norm());
    }
  return worst;
}

Vec3 to_eigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

TEST(EditorPivot, MovingThePivotKeepsTheFacesWhereTheyAre) {
  Harness s;
  s.two_handles();
  Document& d = *s.editor.document();
  HandleGroup& top = d.state.handles[1];
  top.pose.set_turn(turn_about(Vec3(0.3, 0.2, 1.0), 130.0));
  top.pose.translate = Vec3(0.1, -0.2, 0.05);
  const RigidTransform before = top.transform();
  const Vec3 turn = top.pose.whole_turn();
  move_pivot(top, Vec3(0.0, 0.5, 0.1));
  EXPECT_EQ(top.center, Vec3(0.0, 0.5, 0.1));
  EXPECT_LT(largest_difference(before, top.transform(), *d.topology, *top.faces), 1e-12);
  EXPECT_EQ(top.pose.whole_turn(), turn) << "the turn is the pivot's business no more than before";
  // A spring has no rotation: its pull does not change.
  HandleGroup spring = top;
  spring.mode = HandleMode::Spring;
  spring.pose = Pose{};
  spring.pose.translate = Vec3(0.2, 0, 0);
  move_pivot(spring, Vec3(1, 2, 3));
  EXPECT_EQ(spring.pose.translate, Vec3(0.2, 0, 0));
}

TEST(EditorPivot, TheGizmoTurnsTheHandleAboutItsPivot) {
  Harness s;
  s.two_handles();
  Document& d = *s.editor.document();
  // The top handle's pivot at the bar's middle, its "elbow".
  const Vec3 elbow(0.0, 0.5, 0.0);
  ASSERT_TRUE(s.editor.set_pivot(1, elbow));
  s.key(GLFW_KEY_E);
  GizmoKind kind;
  glm::dvec3 center;
  ASSERT_TRUE(s.editor.gizmo_visible(kind, center));
  EXPECT_LT((to_eigen(center) - elbow).norm(), 1e-12) << "the gizmo is drawn at the pivot";
  s.quarter_turn_of_the_view_ring();
  const HandleGroup& top = d.state.handles[1];
  EXPECT_NEAR(Eigen::AngleAxisd(top.pose.rotation).angle(), 90.0 * kDeg, 1e-9);
  // The elbow stays put; the top's centre swings a quarter circle of radius 0.47 about it.
  const RigidTransform t = top.transform();
  EXPECT_LT((t.apply(elbow) - elbow).norm(), 1e-12);
  const Vec3 centroid = rest_centroid(top, *d.topology);
  EXPECT_NEAR((t.apply(centroid) - elbow).norm(), (centroid - elbow).norm(), 1e-12);
  EXPECT_GT((t.apply(centroid) - centroid).norm(), 0.6) << "about the elbow, not about itself";
  ASSERT_TRUE(s.settle());
}

TEST(EditorPivot, EachPlacementIsOneUndoStepThatLeavesTheMeshAlone) {
  Harness s;
  s.two_handles();
  Document& d = *s.editor.document();
  d.state.handles[1].pose.set_turn(turn_about(Vec3::UnitZ(), 40.0));
  s.editor.commit("Rotate");
  ASSERT_TRUE(s.settle());
  const std::vector<Vec3> shown = s.editor.positions();
  const RigidTransform before = d.state.handles[1].transform();
  const Vec3 centroid = rest_centroid(d.state.handles[1], *d.topology);
  ASSERT_EQ(d.state.handles[1].center, centroid);

  // Centre of selection: the selected faces' centre as shown now.
  s.select_where(0.45, 0.55);
  const Vec3 middle = weighted_centroid(*d.topology, s.editor.positions(),
                                        selected_faces(*d.state.selection));
  ASSERT_TRUE(s.editor.pivot_to_selection(1));
  EXPECT_EQ(d.history.undo_label(), "Pivot of 'Handle 2'");
  EXPECT_LT((to_eigen(s.editor.handle_pivot(1)) - middle).norm(), 1e-12);
  EXPECT_LT(largest_difference(before, d.state.handles[1].transform(), *d.topology,
                               *d.state.handles[1].faces), 1e-12);
  ASSERT_TRUE(s.settle());
  double moved = 0.0;
  for (size_t v = 0; v < shown.size(); ++v) moved = std::max(moved, (s.editor.positions()[v] - shown[v]).norm());
  EXPECT_LT(moved, 1e-6 * s.diagonal()) << "placing a pivot is no pose";

  // Rest centroid brings it back; undo twice goes back through both.
  ASSERT_TRUE(s.editor.pivot_to_rest_centroid(1));
  EXPECT_EQ(d.state.handles[1].center, centroid);
  EXPECT_FALSE(s.editor.pivot_to_rest_centroid(1)) << "already there: no step";
  s.editor.undo();
  EXPECT_NE(d.state.handles[1].center, centroid);
  s.editor.undo();
  EXPECT_EQ(d.state.handles[1].center, centroid);
  // Nothing selected: a message, no step.
  s.editor.clear_selection();
  const std::string label = d.history.undo_label();
  EXPECT_FALSE(s.editor.pivot_to_selection(1));
  EXPECT_EQ(d.history.undo_label(), label);
  ASSERT_NE(s.editor.current_message(), nullptr);
  EXPECT_NE(s.editor.current_message()->text.find("Select faces"), std::string::npos);
  // Not a number: refused.
  EXPECT_FALSE(s.editor.set_pivot(1, Vec3(std::nan(""), 0, 0)));
  EXPECT_EQ(d.state.handles[1].center, centroid);
}

TEST(EditorPivot, ShiftSAndCtrlShiftRightClickPutThePivotOnTheSurfaceUnderTheCursor) {
  Harness s;
  s.two_handles();
  Document& d = *s.editor.document();
  const MeshTopology& t = *d.topology;
  // A front face at mid-height (the camera looks along -z).
  int face = -1;
  for (int f = 0; f < t.n_faces; ++f)
    if (t.rest_geometry.normal[f].z() > 0.9 && std::abs(t.rest_geometry.centroid[f].y() - 0.55) < 0.03) face = f;
  ASSERT_GE(face, 0);
  const glm::dvec3 c = s.editor.camera().project(glm::dvec3(
      t.rest_geometry.centroid[face].x(), t.rest_geometry.centroid[face].y(), t.rest_geometry.centroid[face].z()));
  s.event(InputEvent::cursor(c.x, c.y));
  s.key(GLFW_KEY_S, GLFW_MOD_SHIFT);
  EXPECT_LT((d.state.handles[1].center - t.rest_geometry.centroid[face]).norm(), 1e-6);
  EXPECT_EQ(d.history.undo_label(), "Pivot of 'Handle 2'");
  s.editor.undo();
  EXPECT_NE(d.state.handles[1].center, t.rest_geometry.centroid[face]);
  // The mouse chord does the same and starts no camera gesture.
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_RIGHT, GLFW_PRESS, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT));
  EXPECT_EQ(s.editor.gesture(), Editor::Gesture::None);
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_RIGHT, GLFW_RELEASE, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT));
  EXPECT_LT((d.state.handles[1].center - t.rest_geometry.centroid[face]).norm(), 1e-6);
  // Off the mesh: a message, the pivot stays.
  const Vec3 placed = d.state.handles[1].center;
  s.event(InputEvent::cursor(5, 5));
  s.key(GLFW_KEY_S, GLFW_MOD_SHIFT);
  EXPECT_EQ(d.state.handles[1].center, placed);
  ASSERT_NE(s.editor.current_message(), nullptr);
  EXPECT_NE(s.editor.current_message()->text.find("Not on the surface"), std::string::npos);
}

TEST(EditorPivot, APlacedPivotStaysWhenFacesAreTakenAwayAndFollowsAMirrorTwin) {
  Harness s(make_bar(0.2, 2.0, 2, 20));
  Document& d = *s.editor.document();
  s.select_where(1.5, 2.0);
  s.editor.make_handle(HandleMode::Pose);
  const Vec3 joint(0.0, 1.5, 0.0);
  ASSERT_TRUE(s.editor.set_pivot(0, joint));
  s.select_where(1.9, 2.0);
  s.editor.make_handle(HandleMode::Pose);
  EXPECT_EQ(d.state.handles[0].center, joint) << "a placed pivot is no centroid to recompute";

  // Mirrored across y = 1: the twin turns about the mirror image of the pivot.
  Harness m(make_bar(0.2, 2.0, 2, 20));
  Document& md = *m.editor.document();
  m.editor.set_mirror(1, true);
  m.select_where(1.8, 2.0);
  m.editor.make_handle(HandleMode::Pose);
  ASSERT_EQ(md.state.handles.size(), 2u);
  ASSERT_EQ(md.state.handles[0].mirror_twin, 1);
  ASSERT_TRUE(m.editor.set_pivot(0, Vec3(0.0, 1.7, 0.05)));
  EXPECT_LT((md.state.handles[1].center - Vec3(0.0, 0.3, 0.05)).norm(), 1e-12);
}

TEST(EditorPivot, AScenarioSavesThePivotAsItsCenterAndReadsItBack) {
  const std::string dir = test::temp_dir();
  save_mesh(make_bar(0.2, 1.0, 2, 10), dir + "/bar.obj");
  std::unique_ptr<Document> doc = load_document(dir + "/bar.obj");
  const MeshTopology& t = *doc->topology;
  std::vector<int> top;
  for (int f = 0; f < t.n_faces; ++f)
    if (t.rest_geometry.centroid[f].y() > 0.9) top.push_back(f);
  add_handle(doc->state, t, t.rest_points, top, HandleMode::Pose);
  HandleGroup& g = doc->state.handles[0];
  g.pose.set_turn(turn_about(Vec3::UnitX(), 30.0));
  g.pose.translate = Vec3(0.0, 0.1, 0.0);
  move_pivot(g, Vec3(0.0, 0.6, 0.0));
  const std::string path = dir + "/pivot.json";
  test::write_text(path, scenario_to_json(export_scenario(doc->state, doc->mesh_path, path, doc->solver)));
  const Scenario written = load_scenario(path);
  ASSERT_TRUE(written.handles[0].transform.center.has_value());
  EXPECT_EQ(*written.handles[0].transform.center, Vec3(0.0, 0.6, 0.0));
  const std::unique_ptr<Document> again = load_document(path);
  const HandleGroup& back = again->state.handles[0];
  EXPECT_LT((back.center - Vec3(0.0, 0.6, 0.0)).norm(), 1e-12) << "the file's center is the pivot";
  EXPECT_LT((back.pose.translate - g.pose.translate).norm(), 1e-12);
  EXPECT_LT(largest_difference(back.transform(), g.transform(), t, top), 1e-12);
  // Without a center the pivot is the rest centroid, as the format says.
  test::write_text(dir + "/plain.json",
                   R"({"format": "primo-scenario/1", "mesh": "bar.obj", "handles": [{"select": {"faces": [)" + std::to_string(top[0]) +
                       R"(]}, "fix": "all", "transform": {"translate": [0, 0.1, 0]}}]})");
  const std::unique_ptr<Document> plain = load_document(dir + "/plain.json");
  EXPECT_LT((plain->state.handles[0].center - area_weighted_centroid(t.rest_geometry, {top[0]})).norm(), 1e-12);
}

TEST(EditorPivot, ASessionRecordsThePivotAndReplaysIt) {
  std::unique_ptr<Document> doc = make_document(make_bar(0.2, 1.0, 2, 10), "bar.obj");
  const MeshTopology& t = *doc->topology;
  std::vector<int> top;
  for (int f = 0; f < t.n_faces; ++f)
    if (t.rest_geometry.centroid[f].y() > 0.9) top.push_back(f);
  add_handle(doc->state, t, t.rest_points, top, HandleMode::Pose);
  doc->state.handles[0].pose.set_turn(turn_about(Vec3::UnitZ(), 20.0));
  doc->commit("pose");
  DocumentRecorder rec;
  double now = 0.0;
  rec.start(*doc, now);
  move_pivot(doc->state.handles[0], Vec3(0.0, 0.5, 0.0));
  doc->commit("pivot");
  now += 1.0 / 60;
  rec.observe(*doc, now);
  // A turn about the new pivot.
  doc->state.handles[0].pose.set_turn(turn_about(Vec3::UnitZ(), 60.0));
  now += 1.0 / 60;
  rec.observe(*doc, now);
  const Session session = rec.stop(*doc, now);
  ASSERT_EQ(session.events.size(), 2u);
  EXPECT_EQ(session.events[0].type, SessionEvent::Type::Handles) << "the pivot is in the handle list";
  EXPECT_EQ(session.events[0].handles[0].center, Vec3(0.0, 0.5, 0.0));
  // Written and read back, the replayed state is the editor's, the turn about the new pivot.
  const Session back = parse_session(session_to_json(session, "a.session.json"), "a.session.json");
  const SessionState final_state = validate_session(back, doc->n_faces());
  EXPECT_TRUE(final_state == session_state(doc->state));
  EXPECT_LT(largest_difference(final_state.handles[0].transform(), doc->state.handles[0].transform(), t, top),
            1e-12);
}
