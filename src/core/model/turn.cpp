#include "primo/model/turn.h"

#include <Eigen/Geometry>
#include <cmath>

#include "primo/util/error.h"

namespace primo {

Vec3 turn_about(const Vec3& axis, double angle_deg) {
  if (angle_deg == 0.0) return Vec3::Zero();
  const double length = axis.norm();
  if (!(length > 0.0) || !std::isfinite(length))
    throw Error("rotation axis must be non-zero when angle_deg is not 0");
  return axis / length * (angle_deg * M_PI / 180.0);
}

Mat3 rotation_of_turn(const Vec3& turn) {
  const double angle = turn.norm();
  if (angle == 0.0) return Mat3::Identity();
  return Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix();
}

Vec3 nearest_turn(const Mat3& rotation, const Vec3& near) {
  const Eigen::AngleAxisd principal(rotation);
  const double angle = principal.angle();  // in [0, pi]
  // The identity is every whole turn about any axis: whole turns about the axis of `near`.
  const double two_pi = 2.0 * M_PI;
  if (!(angle > 1e-12)) {
    const double n = near.norm();
    if (!(n > 0.0)) return Vec3::Zero();
    return near / n * (two_pi * std::round(n / two_pi));
  }
  const Vec3 axis = principal.axis();
  // The turns are axis * (angle + 2 pi k); the nearest is the one whose length along the axis
  // is nearest near's, and of two as near (half a turn from `near`) the one with the larger k:
  // from no turn, the principal one (k = 0, not -1, for a half turn).
  const double k = std::floor((near.dot(axis) - angle) / two_pi + 0.5);
  return axis * (angle + two_pi * k);
}

Vec3 turn_of(const Mat3& rotation, const Vec3& turn) {
  return turn_makes(turn, rotation) ? turn : nearest_turn(rotation, turn);
}

AxisAngle axis_angle_of_turn(const Vec3& turn) {
  AxisAngle a;
  const double angle = turn.norm();
  if (!(angle > 0.0)) return a;
  a.axis = turn / angle;
  a.angle_deg = angle * 180.0 / M_PI;
  Eigen::Index largest = 0;
  a.axis.cwiseAbs().maxCoeff(&largest);
  if (a.axis[largest] < 0) {
    a.axis = -a.axis;
    a.angle_deg = -a.angle_deg;
  }
  return a;
}

bool turn_makes(const Vec3& turn, const Mat3& rotation) {
  return turn.allFinite() &&
         (rotation_of_turn(turn) - rotation).cwiseAbs().maxCoeff() <= 1e-6;
}

}  // namespace primo
