// Editor camera and gizmo math: projections, framing, navigation, gizmo hits and drags.

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include "view/camera.h"
#include "view/gizmo.h"

using namespace primo;
using namespace primo::editor;

namespace {

Camera front_camera() {
  Camera c;
  c.set_viewport(800, 600);
  c.set_pose({glm::dvec3(0.0), 4.0, 0.0, 0.0});  // at +z looking down -z
  return c;
}

}  // namespace

TEST(EditorCamera, ProjectUnprojectRoundTrip) {
  Camera c = front_camera();
  c.set_pose({glm::dvec3(0.1, 0.2, 0.3), 3.0, 0.7, 0.4});
  for (glm::dvec3 p : {glm::dvec3(0.0), glm::dvec3(0.5, -0.2, 0.1), glm::dvec3(-0.3, 0.4, 0.6)}) {
    const glm::dvec3 w = c.project(p);
    EXPECT_LT(glm::length(c.unproject({w.x, w.y}, w.z) - p), 1e-9);
  }
  const glm::dvec3 center = c.project(c.pose().target);
  EXPECT_NEAR(center.x, 400.0, 1e-9);
  EXPECT_NEAR(center.y, 300.0, 1e-9);
  // One pixel to the right at the target is world_per_pixel along right().
  const double s = c.world_per_pixel(c.pose().target);
  EXPECT_NEAR(c.project(c.pose().target + s * c.right()).x, 401.0, 1e-6);
  c.set_orthographic(true);
  const glm::dvec3 w = c.project(glm::dvec3(0.2, 0.1, -0.4));
  EXPECT_LT(glm::length(c.unproject({w.x, w.y}, w.z) - glm::dvec3(0.2, 0.1, -0.4)), 1e-9);
}

TEST(EditorCamera, FrameFitsTheSphere) {
  Camera c = front_camera();
  c.frame(glm::dvec3(1, 2, 3), 0.5, true);
  const glm::dvec3 center = c.project(glm::dvec3(1, 2, 3));
  EXPECT_NEAR(center.x, 400, 1e-6);
  EXPECT_NEAR(center.y, 300, 1e-6);
  // The sphere's top and side stay inside the viewport.
  EXPECT_GT(c.project(glm::dvec3(1, 2.5, 3)).y, 0.0);
  EXPECT_LT(c.project(glm::dvec3(1.5, 2, 3)).x, 800.0);
  // Animated framing gets there.
  c.frame(glm::dvec3(0, 0, 0), 2.0);
  while (c.update(0.05)) {
  }
  EXPECT_LT(glm::length(c.pose().target), 1e-12);
}

TEST(EditorCamera, DollyKeepsThePointUnderTheCursor) {
  Camera c = front_camera();
  const glm::dvec2 cursor(600, 200);
  const glm::dvec3 before = c.unproject(cursor, c.project(c.pose().target).z);
  c.dolly(2.0, cursor);
  EXPECT_LT(c.pose().distance, 4.0);
  const glm::dvec3 seen = c.project(before);
  EXPECT_NEAR(seen.x, 600, 1e-6);
  EXPECT_NEAR(seen.y, 200, 1e-6);
}

TEST(EditorCamera, OrbitStopsAtThePoles) {
  Camera c = front_camera();
  c.orbit(0, 10000);
  EXPECT_LT(c.pose().pitch, glm::half_pi<double>());
  EXPECT_GT(glm::dot(c.up(), glm::dvec3(0, 1, 0)), 0.0);
}

TEST(EditorGizmo, HitsArrowsAndDragsAlongThem) {
  Camera c = front_camera();
  const glm::dvec3 center(0.0);
  const glm::dvec3 tip = c.project(center + 0.9 * gizmo_world_size(c, center) * glm::dvec3(1, 0, 0));
  EXPECT_EQ(gizmo_hit(GizmoKind::Translate, c, center, {tip.x, tip.y + 3}), GizmoPart::X);
  EXPECT_EQ(gizmo_hit(GizmoKind::Translate, c, center, {400, 300}), GizmoPart::View);
  EXPECT_EQ(gizmo_hit(GizmoKind::Translate, c, center, {700, 100}), GizmoPart::None);

  GizmoDrag drag(GizmoKind::Translate, GizmoPart::X, c, center, {tip.x, tip.y});
  const Vec3 t = drag.translation(c, {tip.x + 50, tip.y}, false, 0.0);
  EXPECT_NEAR(t.x(), 50 * c.world_per_pixel(center), 1e-9);
  // Off the axis on screen: still along the axis only.
  const Vec3 off = drag.translation(c, {tip.x + 50, tip.y + 20}, false, 0.0);
  EXPECT_GT(off.x(), 0.0);
  EXPECT_EQ(off.y(), 0.0);
  EXPECT_EQ(off.z(), 0.0);
  const Vec3 snapped = drag.translation(c, {tip.x + 50, tip.y}, true, 0.1);
  EXPECT_NEAR(snapped.x(), 0.1 * std::round(t.x() / 0.1), 1e-12);
}

TEST(EditorGizmo, RingsRotateRightHanded) {
  Camera c = front_camera();
  const glm::dvec3 center(0.0);
  // The Z ring faces the viewer (a circle about the centre); X and Y rings are seen edge-on
  // as lines through the centre, so grab Z at 45 degrees.
  const std::vector<glm::dvec2> ring = gizmo_ring(c, center, GizmoPart::Z);
  double radius = 0;
  for (const auto& p : ring) radius = std::max(radius, p.x - 400.0);
  const double d = radius / std::sqrt(2.0);
  const glm::dvec2 upper_right(400 + d, 300 - d), upper_left(400 - d, 300 - d);
  EXPECT_EQ(gizmo_hit(GizmoKind::Rotate, c, center, upper_right), GizmoPart::Z);
  GizmoDrag drag(GizmoKind::Rotate, GizmoPart::Z, c, center, upper_right);
  // A quarter turn counter-clockwise on screen is +90 degrees about +z (towards the viewer).
  const glm::dvec2 top = upper_left;
  EXPECT_NEAR(drag.angle_degrees(c, top, false), 90.0, 1e-6);
  const Eigen::Quaterniond q = drag.rotation(c, top + glm::dvec2(3, 0), true);
  EXPECT_TRUE((q * Vec3::UnitX()).isApprox(Vec3::UnitY(), 1e-12));
}

TEST(EditorGizmo, DragRotationFollowsTheCursor) {
  Camera c = front_camera();
  // Dragging right turns the front of the surface (+z) towards +x.
  const Eigen::Quaterniond q = drag_rotation(c, {400, 300}, {420, 300});
  EXPECT_GT((q * Vec3::UnitZ()).x(), 0.1);
  EXPECT_NEAR(2 * std::acos(std::abs(q.w())), glm::radians(10.0), 1e-9);
  EXPECT_DOUBLE_EQ(snap_step_for(2.0), 0.1);
  EXPECT_DOUBLE_EQ(snap_step_for(500.0), 10.0);
}

TEST(EditorCamera, AxesOnScreenFollowTheView) {
  Camera c = front_camera();  // at +z looking down -z
  const auto a = c.axes_on_screen();
  EXPECT_NEAR(a[0].x, 1.0, 1e-12);   // x to the right
  EXPECT_NEAR(a[1].y, -1.0, 1e-12);  // y up (screen y grows down)
  EXPECT_NEAR(a[2].z, -1.0, 1e-12);  // z towards the viewer
  c.view_preset(ViewPreset::Top);
  c.update(10.0);  // finish the animation
  const auto top = c.axes_on_screen();
  EXPECT_NEAR(std::abs(top[1].z), 1.0, 1e-3);  // looking along y (short of the pole)
}
