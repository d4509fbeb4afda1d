#include "reach_pose.h"

#include <algorithm>
#include <cmath>

#include "primo/util/error.h"
#include "primo/mesh/geometry.h"

namespace primo::bench {

ReachPose make_reach_pose(const Mesh& mesh, const std::string& source) {
  const FaceGeometry faces = compute_face_geometry(mesh);
  double y_min = INFINITY, y_max = -INFINITY;
  for (auto v : mesh.vertices()) {
    y_min = std::min(y_min, mesh.point(v).y());
    y_max = std::max(y_max, mesh.point(v).y());
  }
  const double y_extent = y_max - y_min;
  ReachPose pose;
  for (int f = 0; f < int(mesh.n_faces()); ++f) {
    const double y = faces.centroid[f].y();
    if (y < y_min + 0.1 * y_extent)
      pose.bottom.push_back(f);
    else if (y > y_max - 0.1 * y_extent)
      pose.top.push_back(f);
  }
  if (pose.bottom.empty() || pose.top.empty())
    throw Error(source + ": no faces in the bottom or top tenth of the bounding box");
  pose.top_centroid = area_weighted_centroid(faces, pose.top);
  pose.translate = Vec3(0.0, 0.0, 0.1 * bounding_box_diagonal(mesh));
  return pose;
}

}  // namespace primo::bench
