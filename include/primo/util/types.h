#pragma once
// Small linear-algebra vocabulary shared by the whole core.

#include <Eigen/Core>

namespace primo {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
// A rigid body's motion (v, omega) and the blocks of a Hessian in it.
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

}  // namespace primo
