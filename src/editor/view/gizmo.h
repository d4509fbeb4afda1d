#pragma once
// The transform gizmo on the active handle: three axis arrows and a view-plane square for
// moving, three axis rings and a view ring for rotating, all sized to a constant number of
// pixels. This is the math (hit tests and drags); drawing is in gizmo_draw.
//
// Axes are the columns of `axes` (the world's by default; gizmo_orientation.h gives the
// others); dragging an arrow moves along its axis (the point of the axis closest
// to the mouse ray), the square moves in the view plane, a ring rotates about its axis by
// the angle the cursor sweeps around the gizmo centre. Snapping: translation to `snap_step`,
// rotation to 15 degrees.

#include <Eigen/Geometry>
#include <glm/glm.hpp>

#include "camera.h"
#include "primo/util/types.h"

namespace primo::editor {

enum class GizmoKind { Translate, Rotate };
enum class GizmoPart { None, X, Y, Z, View };

constexpr double kGizmoPixels = 90.0;     // arrow length / ring radius on screen
constexpr double kGizmoHitPixels = 9.0;   // how close the cursor must be to grab a part
constexpr double kRotateSnapDegrees = 15.0;

// Unit; View: towards the viewer.
glm::dvec3 gizmo_axis(GizmoPart part, const Camera& camera, const glm::dmat3& axes = glm::dmat3(1.0));
// World length of the gizmo's arrows at `center`.
double gizmo_world_size(const Camera& camera, const glm::dvec3& center);
// Viewport pixels of a ring (axis X/Y/Z or View) sampled at `n` points.
std::vector<glm::dvec2> gizmo_ring(const Camera& camera, const glm::dvec3& center, GizmoPart part,
                                   const glm::dmat3& axes = glm::dmat3(1.0), int n = 72);
GizmoPart gizmo_hit(GizmoKind kind, const Camera& camera, const glm::dvec3& center,
                    const glm::dvec2& cursor, const glm::dmat3& axes = glm::dmat3(1.0));

// One drag of a gizmo part, started at `cursor`.
class GizmoDrag {
 public:
  GizmoDrag(GizmoKind kind, GizmoPart part, const Camera& camera, const glm::dvec3& center,
            const glm::dvec2& cursor, const glm::dmat3& axes = glm::dmat3(1.0));
  // The motion since the start: a translation (Translate) or a rotation about the centre
  // (Rotate). With `snap`, translations are rounded to multiples of `snap_step` along the
  // axis (or per component in the view plane) and angles to 15 degrees.
  Vec3 translation(const Camera& camera, const glm::dvec2& cursor, bool snap, double snap_step) const;
  Eigen::Quaterniond rotation(const Camera& camera, const glm::dvec2& cursor, bool snap) const;
  double angle_degrees(const Camera& camera, const glm::dvec2& cursor, bool snap) const;
  GizmoKind kind() const { return kind_; }
  GizmoPart part() const { return part_; }

 private:
  double axis_parameter(const Camera& camera, const glm::dvec2& cursor) const;
  GizmoKind kind_;
  GizmoPart part_;
  glm::dvec3 center_;
  glm::dvec3 axis_;
  glm::dvec3 plane_normal_;
  glm::dvec2 start_cursor_;
  double start_parameter_ = 0.0;
  glm::dvec3 start_point_{0.0};
};

// Free rotation for dragging an orientation-only handle: the surface turns about the view-
// plane axis perpendicular to the drag, by 0.5 degree per pixel.
Eigen::Quaterniond drag_rotation(const Camera& camera, const glm::dvec2& from, const glm::dvec2& to);

// Where the mouse ray meets the plane through `point` facing the camera.
glm::dvec3 view_plane_point(const Camera& camera, const glm::dvec3& point, const glm::dvec2& cursor);

// A round step for snapping translations: the power of ten nearest to diagonal / 50.
double snap_step_for(double diagonal);

}  // namespace primo::editor
