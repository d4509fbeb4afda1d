#include "gizmo.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <limits>

namespace primo::editor {
namespace {

double segment_distance(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

glm::dvec2 xy(const glm::dvec3& v) { return {v.x, v.y}; }

Vec3 to_eigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

double snap(double v, double step) { return step > 0 ? std::round(v / step) * step : v; }

}  // namespace

glm::dvec3 gizmo_axis(GizmoPart part, const Camera& camera, const glm::dmat3& axes) {
  switch (part) {
    case GizmoPart::X: return axes[0];
    case GizmoPart::Y: return axes[1];
    case GizmoPart::Z: return axes[2];
    default: return -camera.forward();
  }
}

double gizmo_world_size(const Camera& camera, const glm::dvec3& center) {
  return kGizmoPixels * camera.world_per_pixel(center);
}

std::vector<glm::dvec2> gizmo_ring(const Camera& camera, const glm::dvec3& center, GizmoPart part,
                                   const glm::dmat3& axes, int n) {
  std::vector<glm::dvec2> points;
  const glm::dvec3 c = camera.project(center);
  if (part == GizmoPart::View) {
    const double r = 1.15 * kGizmoPixels;
    for (int i = 0; i < n; ++i) {
      const double a = glm::two_pi<double>() * i / n;
      points.emplace_back(c.x + r * std::cos(a), c.y + r * std::sin(a));
    }
    return points;
  }
  const glm::dvec3 axis = gizmo_axis(part, camera, axes);
  const glm::dvec3 u = glm::normalize(glm::cross(axis, std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0)
                                                                               : glm::dvec3(0, 1, 0)));
  const glm::dvec3 v = glm::cross(axis, u);
  const double r = gizmo_world_size(camera, center);
  for (int i = 0; i < n; ++i) {
    const double a = glm::two_pi<double>() * i / n;
    points.push_back(xy(camera.project(center + r * (std::cos(a) * u + std::sin(a) * v))));
  }
  return points;
}

GizmoPart gizmo_hit(GizmoKind kind, const Camera& camera, const glm::dvec3& center,
                    const glm::dvec2& cursor, const glm::dmat3& axes) {
  const glm::dvec2 c = xy(camera.project(center));
  GizmoPart best = GizmoPart::None;
  double best_d = kGizmoHitPixels;
  const GizmoPart arrows[] = {GizmoPart::X, GizmoPart::Y, GizmoPart::Z};
  if (kind == GizmoKind::Translate) {
    if (std::max(std::abs(cursor.x - c.x), std::abs(cursor.y - c.y)) <= kGizmoHitPixels)
      return GizmoPart::View;
    const double size = gizmo_world_size(camera, center);
    for (GizmoPart p : arrows) {
      const glm::dvec2 tip = xy(camera.project(center + size * gizmo_axis(p, camera, axes)));
      const double d = segment_distance(cursor, c, tip);
      if (d < best_d) best_d = d, best = p;
    }
    return best;
  }
  for (GizmoPart p : {GizmoPart::X, GizmoPart::Y, GizmoPart::Z, GizmoPart::View}) {
    const std::vector<glm::dvec2> ring = gizmo_ring(camera, center, p, axes);
    for (size_t i = 0; i < ring.size(); ++i) {
      const double d = segment_distance(cursor, ring[i], ring[(i + 1) % ring.size()]);
      if (d < best_d) best_d = d, best = p;
    }
  }
  return best;
}

GizmoDrag::GizmoDrag(GizmoKind kind, GizmoPart part, const Camera& camera,
                     const glm::dvec3& center, const glm::dvec2& cursor, const glm::dmat3& axes)
    : kind_(kind), part_(part), center_(center), axis_(gizmo_axis(part, camera, axes)),
      plane_normal_(camera.forward()), start_cursor_(cursor) {
  if (kind_ == GizmoKind::Translate) {
    if (part_ == GizmoPart::View)
      start_point_ = view_plane_point(camera, center_, cursor);
    else
      start_parameter_ = axis_parameter(camera, cursor);
  }
}

double GizmoDrag::axis_parameter(const Camera& camera, const glm::dvec2& cursor) const {
  // Closest point of the axis line C + s a to the mouse ray o + t d.
  const Ray ray = camera.ray(cursor);
  const glm::dvec3 w = center_ - ray.origin;
  const double b = glm::dot(axis_, ray.direction);
  const double denom = 1.0 - b * b;
  if (denom < 1e-9) return start_parameter_;  // looking along the axis: no motion
  return (b * glm::dot(ray.direction, w) - glm::dot(axis_, w)) / denom;
}

Vec3 GizmoDrag::translation(const Camera& camera, const glm::dvec2& cursor, bool snapping,
                            double snap_step) const {
  if (kind_ != GizmoKind::Translate) return Vec3::Zero();
  if (part_ == GizmoPart::View) {
    glm::dvec3 d = view_plane_point(camera, center_, cursor) - start_point_;
    if (snapping) d = {snap(d.x, snap_step), snap(d.y, snap_step), snap(d.z, snap_step)};
    return to_eigen(d);
  }
  double s = axis_parameter(camera, cursor) - start_parameter_;
  if (snapping) s = snap(s, snap_step);
  return to_eigen(s * axis_);
}

double GizmoDrag::angle_degrees(const Camera& camera, const glm::dvec2& cursor, bool snapping) const {
  const glm::dvec2 c = xy(camera.project(center_));
  const glm::dvec2 a = start_cursor_ - c, b = cursor - c;
  if (glm::length(a) < 1e-6 || glm::length(b) < 1e-6) return 0.0;
  // Clockwise on screen (y down) is positive here.
  const double clockwise = std::atan2(a.x * b.y - a.y * b.x, glm::dot(a, b));
  // A right-handed turn about an axis pointing at the viewer looks counter-clockwise.
  const double sign = glm::dot(axis_, camera.forward()) > 0 ? 1.0 : -1.0;
  double deg = glm::degrees(sign * clockwise);
  if (snapping) deg = snap(deg, kRotateSnapDegrees);
  return deg;
}

Eigen::Quaterniond GizmoDrag::rotation(const Camera& camera, const glm::dvec2& cursor,
                                       bool snapping) const {
  if (kind_ != GizmoKind::Rotate) return Eigen::Quaterniond::Identity();
  const double rad = glm::radians(angle_degrees(camera, cursor, snapping));
  return Eigen::Quaterniond(Eigen::AngleAxisd(rad, to_eigen(axis_).normalized()));
}

Eigen::Quaterniond drag_rotation(const Camera& camera, const glm::dvec2& from, const glm::dvec2& to) {
  const glm::dvec2 d = to - from;
  const double len = glm::length(d);
  if (len < 1e-9) return Eigen::Quaterniond::Identity();
  // Screen drag (x right, y down) as a world direction in the view plane.
  const glm::dvec3 dir = glm::normalize(d.x * camera.right() - d.y * camera.up());
  const glm::dvec3 axis = glm::normalize(glm::cross(-camera.forward(), dir));
  return Eigen::Quaterniond(Eigen::AngleAxisd(glm::radians(0.5 * len), to_eigen(axis)));
}

glm::dvec3 view_plane_point(const Camera& camera, const glm::dvec3& point, const glm::dvec2& cursor) {
  const Ray ray = camera.ray(cursor);
  const glm::dvec3 n = camera.forward();
  const double denom = glm::dot(ray.direction, n);
  if (std::abs(denom) < 1e-12) return point;
  const double t = glm::dot(point - ray.origin, n) / denom;
  return ray.origin + t * ray.direction;
}

double snap_step_for(double diagonal) {
  if (!(diagonal > 0)) return 0.1;
  return std::pow(10.0, std::round(std::log10(diagonal / 50.0)));
}

}  // namespace primo::editor
