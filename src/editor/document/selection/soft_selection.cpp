#include "soft_selection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace primo::editor {

double smooth_falloff(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

std::vector<FalloffFace> falloff_faces(const MeshTopology& t, const std::vector<int>& handle_faces,
                                       double radius, const FaceMask& taken) {
  if (!(radius > 0.0) || handle_faces.empty()) return {};
  const auto& centroid = t.rest_geometry.centroid;
  // Faces further than the radius from the handle's bounding box are out of reach.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int f : handle_faces) {
    lo = lo.cwiseMin(centroid[size_t(f)]);
    hi = hi.cwiseMax(centroid[size_t(f)]);
  }
  lo.array() -= radius;
  hi.array() += radius;
  std::vector<int> faces;
  std::vector<double> weights;
  for (int f = 0; f < t.n_faces; ++f) {
    if (f < int(taken.size()) && taken[size_t(f)]) continue;
    const Vec3& c = centroid[size_t(f)];
    if ((c.array() < lo.array()).any() || (c.array() > hi.array()).any()) continue;
    double d = std::numeric_limits<double>::infinity();
    for (int h : handle_faces) d = std::min(d, (c - centroid[size_t(h)]).norm());
    const double w = smooth_falloff(1.0 - d / radius);
    if (!(w > 0.0)) continue;
    faces.push_back(f);
    weights.push_back(w);
  }
  return falloff_springs(t.rest_geometry, faces, weights);
}

}  // namespace primo::editor
