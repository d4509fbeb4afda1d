#include "soft_selection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

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
  // The handle's centroids in cubes of the radius' size: every centroid within the radius of a
  // point lies in the 27 cubes around the point's, so the nearest one within reach is found
  // there, not among all of the handle's faces (a big handle on a big mesh made each Alt +
  // wheel step take seconds). Farther centroids give a weight of 0 either way, so the faces
  // and weights are those of comparing with every handle face.
  // (One cube for all when the radius is too small for cube numbers to fit.)
  const Vec3 origin = lo;
  const bool in_cubes = (hi - lo).maxCoeff() / radius < 1e12;
  const auto cube = [&](const Vec3& p, int axis) {
    return in_cubes ? std::int64_t(std::floor((p[axis] - origin[axis]) / radius)) : 0;
  };
  const auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (std::uint64_t(x) * 73856093u) ^ (std::uint64_t(y) * 19349663u) ^
           (std::uint64_t(z) * 83492791u);
  };
  std::unordered_map<std::uint64_t, std::vector<int>> cubes;
  for (int h : handle_faces) {
    const Vec3& c = centroid[size_t(h)];
    cubes[key(cube(c, 0), cube(c, 1), cube(c, 2))].push_back(h);
  }
  std::vector<int> faces;
  std::vector<double> weights;
  for (int f = 0; f < t.n_faces; ++f) {
    if (f < int(taken.size()) && taken[size_t(f)]) continue;
    const Vec3& c = centroid[size_t(f)];
    if ((c.array() < lo.array()).any() || (c.array() > hi.array()).any()) continue;
    double d = std::numeric_limits<double>::infinity();
    const std::int64_t x = cube(c, 0), y = cube(c, 1), z = cube(c, 2);
    for (std::int64_t i = x - 1; i <= x + 1; ++i)
      for (std::int64_t j = y - 1; j <= y + 1; ++j)
        for (std::int64_t k = z - 1; k <= z + 1; ++k) {
          const auto near = cubes.find(key(i, j, k));
          if (near == cubes.end()) continue;
          // A colliding key only adds candidates: the distance itself decides.
          for (int h : near->second) d = std::min(d, (c - centroid[size_t(h)]).norm());
        }
    const double w = smooth_falloff(1.0 - d / radius);
    if (!(w > 0.0)) continue;
    faces.push_back(f);
    weights.push_back(w);
  }
  return falloff_springs(t.rest_geometry, faces, weights);
}

}  // namespace primo::editor
