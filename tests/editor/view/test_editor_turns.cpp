// Turns beyond half a turn in the editor: a handle turned twice round the gizmo's ring, or
// typed as 720 degrees, keeps both turns in its pose, its scenario, its session and its
// mirror twin, and the solver follows them.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <complex>
#include <filesystem>

#include "document/document.h"
#include "document/edit_state.h"
#include "document/mirror.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/scenario/scenario.h"
#include "primo/sessions/session.h"
#include "primo/model/turn.h"
#include "document/scenario_bridge.h"
#include "recording/session_bridge.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;

namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<int> faces_where(const MeshTopology& t, double y_min, double y_max) {
  std::vector<int> faces;
  for (int f = 0; f < t.n_faces; ++f) {
    const double y = t.rest_geometry.centroid[f].y();
    if (y >= y_min && y <= y_max) faces.push_back(f);
  }
  return faces;
}

// A tube with a fixed base and a top handle.
struct Tube {
  std::string dir = test::temp_dir();
  std::unique_ptr<Document> doc;
  Tube() {
    save_mesh(make_cylinder(0.15, 2.0, 16, 24, FaceShape::Quads), dir + "/tube.obj");
    doc = load_document(dir + "/tube.obj");
    const MeshTopology& t = *doc->topology;
    add_handle(doc->state, t, t.rest_points, faces_where(t, 0.0, 0.08), HandleMode::Fixed);
    add_handle(doc->state, t, t.rest_points, faces_where(t, 1.92, 2.0), HandleMode::Pose);
  }
  Pose& top() { return doc->state.handles[1].pose; }
};

}  // namespace

TEST(EditorTurns, TwoTurnsOfTheRingAddUp) {
  // The gizmo sets the rotation at every frame (start pose times the ring's angle); each
  // frame's turn continues the last, so two turns in 10-degree frames are 720 degrees.
  Pose pose;
  for (int k = 1; k <= 72; ++k)
    pose.turn_to(Eigen::Quaterniond(Eigen::AngleAxisd(10.0 * k * kDeg, Vec3::UnitY())));
  EXPECT_TRUE(pose.whole_turn().isApprox(Vec3(0, 720 * kDeg, 0))) << pose.whole_turn().transpose();
  EXPECT_TRUE(pose.rotation.toRotationMatrix().isApprox(Mat3::Identity(), 1e-12));
  EXPECT_FALSE(pose.is_identity()) << "two turns are not the rest";
  const AxisAngle shown = axis_angle_of_turn(pose.whole_turn());
  EXPECT_NEAR(shown.angle_deg, 720.0, 1e-9);
  // Typed: -40 about y stays -40 about y, not 40 about -y.
  pose.set_turn(turn_about(Vec3::UnitY(), -40.0));
  EXPECT_NEAR(axis_angle_of_turn(pose.whole_turn()).angle_deg, -40.0, 1e-12);
  EXPECT_TRUE(axis_angle_of_turn(pose.whole_turn()).axis.isApprox(Vec3::UnitY()));
}

TEST(EditorTurns, AScenarioAndASessionKeepTheTurns) {
  Tube tube;
  tube.top().set_turn(turn_about(Vec3::UnitY(), 720.0));
  tube.top().translate = Vec3(0.1, 0, 0);
  // The scenario writes angle_deg 720, and reads back as two turns.
  const std::string path = tube.dir + "/turned.json";
  test::write_text(path, scenario_to_json(export_scenario(tube.doc->state, tube.doc->mesh_path,
                                                          path, tube.doc->solver)));
  const Scenario written = load_scenario(path);
  EXPECT_NEAR(written.handles[1].transform.angle_deg, 720.0, 1e-9);
  const std::unique_ptr<Document> again = load_document(path);
  EXPECT_TRUE(again->state.handles[1].pose.whole_turn().isApprox(Vec3(0, 720 * kDeg, 0)));
  EXPECT_EQ(again->state.handles[1].mode, HandleMode::Pose) << "two turns are no fixed region";
  // The deformer gets them.
  const DeformationInputs in = deformation_inputs(tube.doc->state);
  ASSERT_TRUE(in.handles[1].turn.has_value());
  EXPECT_TRUE(in.handles[1].turn->isApprox(Vec3(0, 720 * kDeg, 0)));
  // A session writes the turn where the rotation alone would lose it, and reads it back.
  SessionState session = session_state(tube.doc->state);
  Session s;
  s.mesh = "tube.obj";
  s.initial = session;
  const std::string text = session_to_json(s, tube.dir + "/a.session.json");
  EXPECT_NE(text.find("\"turn\""), std::string::npos);
  const Session back = parse_session(text, tube.dir + "/a.session.json");
  EXPECT_TRUE(back.initial.handles[1].pose.whole_turn().isApprox(Vec3(0, 720 * kDeg, 0)));
  // A turn that does not make its rotation is an error naming it.
  std::string broken = text;
  const size_t at = broken.find("\"turn\"");
  broken.replace(broken.find('[', at), broken.find(']', at) - broken.find('[', at) + 1, "[0, 1, 0]");
  EXPECT_NE(test::error_of([&] { parse_session(broken, "s.json"); }).find("turn"), std::string::npos);
}

TEST(EditorTurns, AMirrorTwinTurnsAsFarTheOtherWay) {
  // A bar along y (0 to 2) with a handle at each end, mirrored across y = 1.
  const std::string dir = test::temp_dir();
  Mesh bar = make_bar(0.2, 2.0, 2, 20);
  save_mesh(bar, dir + "/bar.obj");
  const std::unique_ptr<Document> doc = load_document(dir + "/bar.obj");
  const MeshTopology& t = *doc->topology;
  MirrorMap map = match_mirror(t, 1);
  ASSERT_GT(map.matched, 0);
  add_handle(doc->state, t, t.rest_points, faces_where(t, 1.9, 2.0), HandleMode::Pose);
  add_handle(doc->state, t, t.rest_points, faces_where(t, 0.0, 0.1), HandleMode::Pose);
  HandleGroup& source = doc->state.handles[0];
  source.pose.set_turn(turn_about(Vec3(1, 1, 0), 400.0));
  const Pose twin = mirrored_pose(source, doc->state.handles[1], map);
  EXPECT_NEAR(twin.whole_turn().norm(), 400.0 * kDeg, 1e-9);
  EXPECT_TRUE(turn_makes(twin.whole_turn(), twin.rotation.toRotationMatrix()));
}

#include "support/editor_harness.h"

namespace {

// How far the ring of vertices at height y turned about the y axis, in degrees in (-180, 180].
double turn_at_deg(const MeshTopology& t, const std::vector<Vec3>& points, double y) {
  std::complex<double> sum = 0.0;
  for (size_t v = 0; v < t.rest_points.size(); ++v) {
    const Vec3& rest = t.rest_points[v];
    if (std::abs(rest.y() - y) > 1e-9) continue;
    sum += std::polar(1.0, std::atan2(rest.z(), rest.x()) - std::atan2(points[v].z(), points[v].x()));
  }
  return std::arg(sum) / kDeg;
}

}  // namespace

TEST(EditorTurns, TheSolverFollowsATypedWholeTurnAndItsUndo) {
  harness::Harness h(make_cylinder(0.15, 2.0, 16, 24, FaceShape::Quads));
  h.select_where(-1, 0.08);
  h.editor.make_handle(HandleMode::Fixed);
  h.select_where(1.92, 3);
  h.editor.make_handle(HandleMode::Pose);
  ASSERT_TRUE(h.settle());
  const MeshTopology& t = *h.editor.document()->topology;
  // Typed into the Angle field: a whole turn, which as a rotation alone is the rest.
  h.editor.document()->state.handles[1].pose.set_turn(turn_about(Vec3::UnitY(), 360.0));
  h.editor.commit("Rotate 'Handle 2'");
  ASSERT_TRUE(h.settle());
  const double turned = turn_at_deg(t, h.editor.positions(), 0.5);
  EXPECT_NEAR(turned, 90.0, 15.0) << "a quarter up the tube turns a quarter of the turn";
  // Undone, the turn unwinds to the rest; redone, it is back.
  h.editor.undo();
  ASSERT_TRUE(h.settle());
  double farthest = 0.0;
  for (size_t v = 0; v < t.rest_points.size(); ++v)
    farthest = std::max(farthest, (h.editor.positions()[v] - t.rest_points[v]).norm());
  EXPECT_LT(farthest, 1e-6 * h.diagonal());
  h.editor.redo();
  ASSERT_TRUE(h.settle());
  EXPECT_NEAR(turn_at_deg(t, h.editor.positions(), 0.5), turned, 1.0);
}
