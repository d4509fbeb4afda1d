#pragma once
// Small linear-algebra vocabulary shared by the whole core.

#include <Eigen/Core>

namespace primo {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace primo
