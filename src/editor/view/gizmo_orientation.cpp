#include "gizmo_orientation.h"

#include <cmath>

namespace primo::editor {
namespace {

glm::dvec3 to_glm(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

glm::dmat3 columns(const Mat3& m) {
  return glm::dmat3(to_glm(m.col(0)), to_glm(m.col(1)), to_glm(m.col(2)));
}

}  // namespace

const char* orientation_label(GizmoOrientation orientation) {
  switch (orientation) {
    case GizmoOrientation::Global: return "Global";
    case GizmoOrientation::Local: return "Local";
    case GizmoOrientation::Normal: return "Normal";
    case GizmoOrientation::View: return "View";
  }
  return "?";
}

GizmoOrientation next_orientation(GizmoOrientation orientation) {
  return GizmoOrientation((int(orientation) + 1) % kGizmoOrientations);
}

Vec3 rest_mean_normal(const MeshTopology& topology, const std::vector<int>& faces) {
  Vec3 sum = Vec3::Zero();
  double area = 0.0;
  for (int f : faces) {
    sum += topology.rest_geometry.vector_area[size_t(f)];
    area += topology.rest_geometry.area[size_t(f)];
  }
  // Cancelling to a millionth of the faces' area: no direction to speak of.
  if (!(sum.norm() > 1e-6 * area)) return Vec3::UnitZ();
  return sum.normalized();
}

glm::dmat3 gizmo_axes(GizmoOrientation orientation, const HandleGroup& group,
                      const MeshTopology& topology, const Camera& camera) {
  const Mat3 R = group.pose.rotation.toRotationMatrix();
  switch (orientation) {
    case GizmoOrientation::Global: return glm::dmat3(1.0);
    case GizmoOrientation::Local: return columns(R);
    case GizmoOrientation::Normal: {
      // Z along the normal; X the rest X axis (Y where the normal is near X) made
      // perpendicular to it, so that the frame turns with the handle and nothing else.
      const Vec3 n = rest_mean_normal(topology, *group.faces);
      const Vec3 seed = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
      const Vec3 x = (seed - seed.dot(n) * n).normalized();
      Mat3 frame;
      frame.col(0) = x;
      frame.col(1) = n.cross(x);
      frame.col(2) = n;
      return columns(R * frame);
    }
    case GizmoOrientation::View:
      return glm::dmat3(camera.right(), camera.up(), -camera.forward());
  }
  return glm::dmat3(1.0);
}

}  // namespace primo::editor
