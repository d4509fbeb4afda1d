#pragma once
// A handle's rotation with its whole turns kept. A rotation matrix forgets how far it was
// turned: 360 degrees is the identity, 270 is 90 the other way. A turn is a rotation vector
// (unit axis times angle in radians) of any length, so a handle turned twice about its axis
// stays turned twice, and a solve from rest follows it through its whole angle (the scenario
// format's "Turns beyond half a turn").

#include "primo/util/types.h"

namespace primo {

// The turn of `angle_deg` degrees about `axis` (any non-zero length; zero angle: no turn).
// Throws Error when the angle is not 0 and the axis is zero or not finite.
Vec3 turn_about(const Vec3& axis, double angle_deg);

// The rotation a turn makes (Rodrigues).
Mat3 rotation_of_turn(const Vec3& turn);

// Of the turns that make `rotation` (its principal rotation vector plus any whole turns about
// the same axis), the one nearest `near`: a rotation set without its turns continues the
// turns it follows (a handle posed from 170 to 190 degrees in a step has turned 190, not -170).
Vec3 nearest_turn(const Mat3& rotation, const Vec3& near = Vec3::Zero());

// A turn as an axis and a signed angle for people to read and type: the axis's largest
// component positive, so that -40 degrees about y reads as -40 about (0, 1, 0), not 40 about
// (0, -1, 0). No turn: 0 degrees about y.
struct AxisAngle {
  Vec3 axis = Vec3::UnitY();
  double angle_deg = 0.0;
};
AxisAngle axis_angle_of_turn(const Vec3& turn);

// Whether `turn` makes `rotation` (within 1e-6 in each entry).
bool turn_makes(const Vec3& turn, const Mat3& rotation);

// `turn` where it makes `rotation`, else the turn of `rotation` nearest it: for a pose whose
// rotation was set without its turn.
Vec3 turn_of(const Mat3& rotation, const Vec3& turn);

}  // namespace primo
