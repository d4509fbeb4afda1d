#include "pivot.h"

#include "primo/mesh/geometry.h"

namespace primo::editor {

Vec3 rest_centroid(const HandleGroup& group, const MeshTopology& topology) {
  return area_weighted_centroid(topology.rest_geometry, *group.faces);
}

RigidTransform handle_motion(const HandleGroup& group, const MeshTopology& topology,
                             const std::vector<Vec3>& current) {
  if (group.mode != HandleMode::Orientation) return group.transform();
  RigidTransform t;
  t.rotation = group.pose.rotation.toRotationMatrix();
  t.translation = weighted_centroid(topology, current, *group.faces) -
                  t.rotation * rest_centroid(group, topology);
  return t;
}

Vec3 rest_point_of(const RigidTransform& motion, const Vec3& world) {
  return motion.rotation.transpose() * (world - motion.translation);
}

void move_pivot(HandleGroup& group, const Vec3& rest_point) {
  const Mat3 R = group.pose.rotation.toRotationMatrix();
  group.pose.translate += (R - Mat3::Identity()) * (rest_point - group.center);
  group.center = rest_point;
}

}  // namespace primo::editor
