#pragma once
// The pose `bench engine` gives a real mesh and `bench drag --bbox-handles` any mesh: the
// bottom tenth (in y) fixed; the top tenth turned 30 degrees about x through its centroid and
// pushed along +z by a tenth of the bounding-box diagonal, reaching forward.

#include <string>
#include <vector>

#include "primo/model/constraints.h"
#include "primo/mesh/mesh.h"

namespace primo::bench {

struct ReachPose {
  std::vector<int> bottom;
  std::vector<int> top;
  Vec3 top_centroid = Vec3::Zero();
  Vec3 translate = Vec3::Zero();
  Vec3 axis = Vec3::UnitX();
  double angle_deg = 30.0;

  RigidTransform top_motion() const {
    return make_rigid_transform(translate, axis, angle_deg, top_centroid);
  }
  std::vector<Handle> handles() const {
    return {{"bottom", bottom, Fix::All, RigidTransform::identity()},
            {"top", top, Fix::All, top_motion()}};
  }
};

// Throws primo::Error naming `source` when the bottom or top tenth has no face.
ReachPose make_reach_pose(const Mesh& mesh, const std::string& source);

}  // namespace primo::bench
