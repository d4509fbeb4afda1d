#include "euler_angles.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "primo/model/turn.h"

namespace primo::editor {
namespace {

constexpr double kDegree = M_PI / 180.0;

}  // namespace

Mat3 rotation_of_euler_xyz(const Vec3& degrees) {
  const Vec3 r = degrees * kDegree;
  return (Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(r.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

Vec3 euler_xyz_of_turn(const Vec3& turn) {
  const Mat3 R = rotation_of_turn(turn);
  // R = Rz Ry Rx: R(2,0) = -sin y, R(2,1) = sin x cos y, R(2,2) = cos x cos y,
  // R(1,0) = cos y sin z, R(0,0) = cos y cos z.
  const double sy = std::clamp(-R(2, 0), -1.0, 1.0);
  Vec3 e;
  if (std::abs(sy) < 1.0 - 1e-12) {
    e = Vec3(std::atan2(R(2, 1), R(2, 2)), std::asin(sy), std::atan2(R(1, 0), R(0, 0)));
  } else {
    // Gimbal lock: only x - z (y = 90) or x + z (y = -90) is known; z takes it all.
    const double z = sy > 0 ? -std::atan2(R(0, 1), R(1, 1)) : std::atan2(-R(0, 1), R(1, 1));
    e = Vec3(0.0, std::copysign(M_PI / 2, sy), z);
  }
  e /= kDegree;
  for (int k = 0; k < 3; ++k)
    if (e[k] <= -180.0 + 1e-9) e[k] += 360.0;
  if (turn.norm() > M_PI) {
    const Vec3 t = turn / kDegree;
    for (int k = 0; k < 3; ++k) e[k] += 360.0 * std::round((t[k] - e[k]) / 360.0);
  }
  return e;
}

Vec3 turn_of_euler_xyz(const Vec3& degrees, const Vec3& near) {
  int nonzero = 0, axis = 0;
  for (int k = 0; k < 3; ++k)
    if (degrees[k] != 0.0) ++nonzero, axis = k;
  if (nonzero == 0) return Vec3::Zero();
  if (nonzero == 1) return turn_about(Vec3::Unit(axis), degrees[axis]);
  return nearest_turn(rotation_of_euler_xyz(degrees), near);
}

}  // namespace primo::editor
