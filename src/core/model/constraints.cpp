#include "primo/model/constraints.h"

#include <Eigen/Geometry>
#include <cmath>

#include "primo/util/error.h"

namespace primo {

RigidTransform make_rigid_transform(const Vec3& translate, const Vec3& axis, double angle_deg,
                                    const Vec3& center) {
  RigidTransform t;
  if (angle_deg != 0.0) {
    const double len = axis.norm();
    if (!(len > 0.0) || !std::isfinite(len))
      throw Error("rotation axis must be non-zero when angle_deg is not 0");
    t.rotation = Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis / len).toRotationMatrix();
  }
  t.translation = center + translate - t.rotation * center;
  return t;
}

const char* fix_name(Fix fix) {
  switch (fix) {
    case Fix::All: return "all";
    case Fix::Position: return "position";
    case Fix::Orientation: return "orientation";
  }
  return "all";
}

std::optional<Fix> fix_from_name(std::string_view name) {
  for (const Fix fix : {Fix::All, Fix::Position, Fix::Orientation})
    if (name == fix_name(fix)) return fix;
  return std::nullopt;
}

}  // namespace primo
