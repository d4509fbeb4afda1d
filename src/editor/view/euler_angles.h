#pragma once
// A handle's rotation as Euler XYZ angles in degrees, as Blender shows them: X applied first,
// then Y, then Z (R = Rz Ry Rx). Like the Axis/Angle fields they keep whole turns: a turn of
// 720 degrees about z reads (0, 0, 720), and 720 typed about one axis is two turns.

#include "primo/util/types.h"

namespace primo::editor {

// The rotation R = Rz(z) Ry(y) Rx(x) of angles in degrees.
Mat3 rotation_of_euler_xyz(const Vec3& degrees);

// Angles that make `turn`'s rotation, y in [-90, 90] and x, z in (-180, 180] (x = 0 where y is
// +-90, the gimbal lock). A turn beyond half a turn adds to each angle the whole turns that
// bring it nearest the turn's own component on that axis, so 190 about z reads 190, not -170.
Vec3 euler_xyz_of_turn(const Vec3& turn);

// The turn typed angles make. One angle alone (the others 0) is that turn about its axis, whole
// turns included; otherwise the rotation continues the turn nearest `near` (primo/model/turn.h), as a
// rotation set without its turn does.
Vec3 turn_of_euler_xyz(const Vec3& degrees, const Vec3& near);

}  // namespace primo::editor
