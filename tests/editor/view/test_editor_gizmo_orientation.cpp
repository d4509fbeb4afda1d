// The gizmo's orientations (global, local, normal, view) and the rotation's Euler XYZ fields:
// the axes each frame gives, drags along them, the key that cycles them, and Euler angles that
// keep whole turns.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "support/editor_harness.h"
#include "view/euler_angles.h"
#include "view/gizmo_orientation.h"
#include "primo/model/turn.h"

using namespace primo;
using namespace primo::editor;
using primo::editor::harness::Harness;

namespace {

constexpr double kDeg = M_PI / 180.0;

Vec3 to_eigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// Unit, orthogonal, right-handed columns.
void expect_rotation(const glm::dmat3& m) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(glm::length(m[i]), 1.0, 1e-12) << "axis " << i;
    EXPECT_NEAR(glm::dot(m[i], m[(i + 1) % 3]), 0.0, 1e-12) << "axes " << i;
  }
  EXPECT_NEAR(glm::dot(glm::cross(m[0], m[1]), m[2]), 1.0, 1e-12) << "right-handed";
}

}  // namespace

TEST(EditorGizmoOrientation, EachOrientationGivesItsFrame) {
  Harness s;
  s.two_handles();
  Document& d = *s.editor.document();
  HandleGroup& top = d.state.handles[1];
  top.pose.set_turn(turn_about(Vec3(1, 0, 1), 70.0));
  const Mat3 R = top.pose.rotation.toRotationMatrix();
  const Camera& cam = s.editor.camera();
  const MeshTopology& t = *d.topology;

  EXPECT_EQ(gizmo_axes(GizmoOrientation::Global, top, t, cam), glm::dmat3(1.0));
  const glm::dmat3 local = gizmo_axes(GizmoOrientation::Local, top, t, cam);
  expect_rotation(local);
  for (int i = 0; i < 3; ++i) EXPECT_LT((to_eigen(local[i]) - R.col(i)).norm(), 1e-12);
  // The top cap faces +y at rest: the normal frame's Z is +y turned by the handle.
  EXPECT_LT((rest_mean_normal(t, *top.faces) - Vec3::UnitY()).norm(), 1e-9);
  const glm::dmat3 normal = gizmo_axes(GizmoOrientation::Normal, top, t, cam);
  expect_rotation(normal);
  EXPECT_LT((to_eigen(normal[2]) - R * Vec3::UnitY()).norm(), 1e-9);
  const glm::dmat3 view = gizmo_axes(GizmoOrientation::View, top, t, cam);
  expect_rotation(view);
  EXPECT_LT(glm::length(view[2] + cam.forward()), 1e-12) << "Z towards the viewer";
  EXPECT_LT(glm::length(view[0] - cam.right()), 1e-12);
  // A closed group has no mean normal: the rest Z axis, not a NaN.
  std::vector<int> all(size_t(t.n_faces));
  for (int f = 0; f < t.n_faces; ++f) all[size_t(f)] = f;
  EXPECT_EQ(rest_mean_normal(t, all), Vec3::UnitZ());
}

TEST(EditorGizmoOrientation, CommaCyclesAndTheArrowsMoveAlongTheChosenAxes) {
  Harness s;
  s.two_handles();
  Document& d = *s.editor.document();
  // The top handle half a turn about z: its own X axis is the world's -X.
  d.state.handles[1].pose.set_turn(turn_about(Vec3::UnitZ(), 180.0));
  s.editor.commit("Rotate");
  s.key(GLFW_KEY_W);
  EXPECT_EQ(s.editor.tools.gizmo_orientation, GizmoOrientation::Global);
  s.key(GLFW_KEY_COMMA);
  EXPECT_EQ(s.editor.tools.gizmo_orientation, GizmoOrientation::Local);
  ASSERT_NE(s.editor.current_message(), nullptr);
  EXPECT_EQ(s.editor.current_message()->text, "Gizmo axes: Local");
  const glm::dmat3 axes = s.editor.gizmo_axes();
  EXPECT_LT(glm::length(axes[0] - glm::dvec3(-1, 0, 0)), 1e-12);

  // The camera looks along -z: the local X arrow points left on the screen. Pull it.
  GizmoKind kind;
  glm::dvec3 center;
  ASSERT_TRUE(s.editor.gizmo_visible(kind, center));
  const Camera& cam = s.editor.camera();
  const double size = gizmo_world_size(cam, center);
  const glm::dvec3 grab = cam.project(center + 0.8 * size * axes[0]);
  const glm::dvec3 pull = cam.project(center + 1.5 * size * axes[0]);
  ASSERT_EQ(gizmo_hit(GizmoKind::Translate, cam, center, {grab.x, grab.y}, axes), GizmoPart::X);
  EXPECT_NE(gizmo_hit(GizmoKind::Translate, cam, center, {grab.x, grab.y}), GizmoPart::X)
      << "the world's X arrow is elsewhere";
  s.event(InputEvent::cursor(grab.x, grab.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  EXPECT_EQ(s.editor.gesture(), Editor::Gesture::Gizmo);
  s.event(InputEvent::cursor(pull.x, pull.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const Vec3 moved = d.state.handles[1].pose.translate;
  EXPECT_NEAR(moved.x(), -0.7 * size, 1e-6 * size) << "along the handle's own X: the world's -X";
  EXPECT_NEAR(moved.y(), 0.0, 1e-9);
  EXPECT_NEAR(moved.z(), 0.0, 1e-9);

  // The rotate gizmo's local X ring turns about the handle's X (the world's -X).
  s.key(GLFW_KEY_E);
  ASSERT_TRUE(s.editor.gizmo_visible(kind, center));
  const std::vector<glm::dvec2> ring = gizmo_ring(cam, center, GizmoPart::X, s.editor.gizmo_axes());
  // The X ring lies in the world's y-z plane, seen edge on from the front: press on it and
  // drag across.
  glm::dvec2 start = ring[0];
  for (const glm::dvec2& p : ring)
    if (gizmo_hit(GizmoKind::Rotate, cam, center, p, s.editor.gizmo_axes()) == GizmoPart::X) {
      start = p;
      break;
    }
  ASSERT_EQ(gizmo_hit(GizmoKind::Rotate, cam, center, start, s.editor.gizmo_axes()), GizmoPart::X);
  const GizmoDrag drag(GizmoKind::Rotate, GizmoPart::X, cam, center, start, s.editor.gizmo_axes());
  const Eigen::AngleAxisd turned(drag.rotation(cam, start + glm::dvec2(30, 30), false));
  EXPECT_GT(turned.angle(), 0.0);
  EXPECT_NEAR(std::abs(turned.axis().x()), 1.0, 1e-12) << "about the handle's X";

  // Four presses come back to Global.
  for (int i = 0; i < 3; ++i) s.key(GLFW_KEY_COMMA);
  EXPECT_EQ(s.editor.tools.gizmo_orientation, GizmoOrientation::Global);
}

TEST(EditorEulerAngles, AnglesMakeTheRotationAndKeepWholeTurns) {
  // XYZ: X first. (30, 40, 50) read back as typed.
  const Vec3 typed(30, 40, 50);
  const Vec3 turn = turn_of_euler_xyz(typed, Vec3::Zero());
  EXPECT_TRUE(rotation_of_turn(turn).isApprox(rotation_of_euler_xyz(typed), 1e-12));
  EXPECT_TRUE(euler_xyz_of_turn(turn).isApprox(typed, 1e-9)) << euler_xyz_of_turn(turn).transpose();
  const Mat3 by_hand = (Eigen::AngleAxisd(50 * kDeg, Vec3::UnitZ()) * Eigen::AngleAxisd(40 * kDeg, Vec3::UnitY()) *
                        Eigen::AngleAxisd(30 * kDeg, Vec3::UnitX())).toRotationMatrix();
  EXPECT_TRUE(rotation_of_euler_xyz(typed).isApprox(by_hand, 1e-12));
  // Whole turns about one axis: typed and shown.
  EXPECT_TRUE(turn_of_euler_xyz(Vec3(0, 0, 720), Vec3::Zero()).isApprox(Vec3(0, 0, 4 * M_PI)));
  EXPECT_TRUE(euler_xyz_of_turn(Vec3(0, 0, 4 * M_PI)).isApprox(Vec3(0, 0, 720), 1e-9));
  EXPECT_TRUE(euler_xyz_of_turn(turn_about(Vec3::UnitZ(), 190)).isApprox(Vec3(0, 0, 190), 1e-9))
      << "190, not -170";
  EXPECT_TRUE(euler_xyz_of_turn(turn_about(Vec3::UnitY(), -40)).isApprox(Vec3(0, -40, 0), 1e-9));
  EXPECT_EQ(turn_of_euler_xyz(Vec3::Zero(), Vec3(1, 0, 0)), Vec3::Zero());
  // Several angles: the rotation continues the turn it follows (a drag past 180 keeps going).
  const Vec3 before = turn_about(Vec3(1, 1, 0), 350.0);
  const Vec3 after = turn_of_euler_xyz(euler_xyz_of_turn(before), before);
  EXPECT_TRUE(after.isApprox(before, 1e-9)) << after.transpose() << " / " << before.transpose();
  // Gimbal lock (y = +-90): angles that make the same rotation.
  for (const Vec3& locked : {Vec3(0, 90, 30), Vec3(20, -90, 10)}) {
    const Vec3 shown = euler_xyz_of_turn(nearest_turn(rotation_of_euler_xyz(locked)));
    EXPECT_TRUE(rotation_of_euler_xyz(shown).isApprox(rotation_of_euler_xyz(locked), 1e-9))
        << shown.transpose();
  }
}
