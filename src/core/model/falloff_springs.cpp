#include "primo/model/falloff_springs.h"

namespace primo {

std::vector<FalloffSpring> falloff_springs(const FaceGeometry& rest, const std::vector<int>& faces,
                                           const std::vector<double>& weights) {
  std::vector<FalloffSpring> out;
  out.reserve(faces.size());
  double area = 0.0;
  for (size_t i = 0; i < faces.size(); ++i) {
    const size_t f = size_t(faces[i]);
    out.push_back({faces[i], weights[i], 0.0, rest.centroid[f]});
    area += rest.area[f];
  }
  for (FalloffSpring& s : out) s.share = s.weight * rest.area[size_t(s.face)] / area;
  return out;
}

RigidTransform falloff_motion(const RigidTransform& handle_motion, const Vec3& translate,
                              bool spring_handle) {
  if (!spring_handle) return handle_motion;
  return {Mat3::Identity(), translate};
}

std::vector<Force> falloff_forces(const std::string& handle_name,
                                  const std::vector<FalloffSpring>& springs,
                                  const RigidTransform& motion, double stiffness) {
  std::vector<Force> forces;
  forces.reserve(springs.size());
  for (const FalloffSpring& s : springs)
    forces.push_back({handle_name + " falloff", {s.face},
                      motion.apply(s.rest_centroid) - s.rest_centroid, stiffness * s.share});
  return forces;
}

}  // namespace primo
