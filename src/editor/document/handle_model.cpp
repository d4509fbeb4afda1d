#include "handle_model.h"

#include <algorithm>

#include "primo/solve/horn.h"
#include "primo/model/turn.h"

namespace primo::editor {

const char* mode_label(HandleMode mode) {
  switch (mode) {
    case HandleMode::Pose: return "Position + orientation";
    case HandleMode::Position: return "Position only";
    case HandleMode::Orientation: return "Orientation only";
    case HandleMode::Spring: return "Spring";
    case HandleMode::Fixed: return "Fixed region";
  }
  return "?";
}

bool is_draggable(HandleMode mode) { return mode != HandleMode::Fixed; }

bool uses_rotation(HandleMode mode) {
  return mode == HandleMode::Pose || mode == HandleMode::Orientation;
}

bool uses_translation(HandleMode mode) {
  return mode == HandleMode::Pose || mode == HandleMode::Position || mode == HandleMode::Spring;
}

void Pose::turn_to(const Eigen::Quaterniond& q) {
  rotation = q;
  turn = nearest_turn(q.toRotationMatrix(), whole_turn());
}

void Pose::set_turn(const Vec3& t) {
  turn = t;
  rotation = Eigen::Quaterniond(rotation_of_turn(t)).normalized();
}

RigidTransform HandleGroup::transform() const {
  RigidTransform t;
  t.rotation = pose.rotation.toRotationMatrix();
  t.translation = center + pose.translate - t.rotation * center;
  return t;
}

HandleGroup make_handle_group(std::string name, std::vector<int> faces, HandleMode mode,
                              const MeshTopology& topology, const std::vector<Vec3>& current) {
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  HandleGroup g;
  g.name = std::move(name);
  g.mode = mode;
  g.center = area_weighted_centroid(topology.rest_geometry, faces);

  // The group's vertices, each once.
  std::vector<int> vertices;
  for (int f : faces)
    for (int k = topology.face_begin[f]; k < topology.face_begin[f + 1]; ++k)
      vertices.push_back(topology.face_vertices[k]);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  const bool moved = std::any_of(vertices.begin(), vertices.end(), [&](int v) {
    return current[v] != topology.rest_points[v];
  });

  if (moved && mode == HandleMode::Spring) {
    // The spring pulls each face towards its rest centroid plus the offset.
    g.pose.translate = weighted_centroid(topology, current, faces) - g.center;
  } else if (moved) {
    // Best rigid fit (Horn) of the rest vertices onto the current ones.
    Vec3 rest_mean = Vec3::Zero(), cur_mean = Vec3::Zero();
    for (int v : vertices) {
      rest_mean += topology.rest_points[v];
      cur_mean += current[v];
    }
    rest_mean /= double(vertices.size());
    cur_mean /= double(vertices.size());
    Mat3 S = Mat3::Zero();
    for (int v : vertices)
      S += (topology.rest_points[v] - rest_mean) * (current[v] - cur_mean).transpose();
    const Mat3 R = horn_rotation(S);
    g.pose.turn_to(Eigen::Quaterniond(R).normalized());
    // R (x - center) + center + translate = R (x - rest_mean) + cur_mean
    g.pose.translate = cur_mean - R * rest_mean + R * g.center - g.center;
  }
  g.faces = std::make_shared<const std::vector<int>>(std::move(faces));
  return g;
}

}  // namespace primo::editor
