#include "proxy_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace primo::editor {
namespace {

struct TriangleHash {
  size_t operator()(const std::array<unsigned, 3>& t) const {
    return (size_t(t[0]) * 73856093u) ^ (size_t(t[1]) * 19349663u) ^ (size_t(t[2]) * 83492791u);
  }
};

ProxyTriangles cluster(const MeshTopology& t, int resolution) {
  const Vec3 lo = t.bbox_min;
  const Vec3 extent = (t.bbox_max - t.bbox_min).cwiseMax(Vec3::Constant(1e-12));
  const double cell = extent.maxCoeff() / resolution;
  auto cell_of = [&](const Vec3& p) {
    const Vec3 q = (p - lo) / cell;
    const long long x = std::min<long long>(resolution, (long long)q.x());
    const long long y = std::min<long long>(resolution, (long long)q.y());
    const long long z = std::min<long long>(resolution, (long long)q.z());
    return (x * (resolution + 1) + y) * (resolution + 1) + z;
  };
  std::unordered_map<long long, unsigned> kept;
  kept.reserve(size_t(t.n_vertices) / 4 + 16);
  std::vector<unsigned> rep(t.n_vertices);
  for (int v = 0; v < t.n_vertices; ++v)
    rep[v] = kept.emplace(cell_of(t.rest_points[v]), unsigned(v)).first->second;

  ProxyTriangles proxy;
  std::unordered_set<std::array<unsigned, 3>, TriangleHash> seen;
  for (size_t i = 0; i < t.triangle_face.size(); ++i) {
    const unsigned a = rep[t.triangles[3 * i]], b = rep[t.triangles[3 * i + 1]],
                   c = rep[t.triangles[3 * i + 2]];
    if (a == b || b == c || a == c) continue;
    std::array<unsigned, 3> key{a, b, c};
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) continue;
    proxy.triangles.insert(proxy.triangles.end(), {a, b, c});
    proxy.triangle_face.push_back(t.triangle_face[i]);
  }
  return proxy;
}

}  // namespace

ProxyTriangles cluster_triangles(const MeshTopology& topology, int max_triangles) {
  if (int(topology.triangle_face.size()) <= max_triangles) return {};
  // About two triangles per kept vertex on a surface, and kept vertices grow with the square
  // of the resolution: start from that estimate and coarsen until the proxy fits.
  const double ratio = double(max_triangles) / double(topology.triangle_face.size());
  const double full = std::sqrt(double(topology.n_vertices));
  int resolution = std::max(4, int(full * std::sqrt(ratio)));
  for (;;) {
    ProxyTriangles p = cluster(topology, resolution);
    if (int(p.triangle_face.size()) <= max_triangles || resolution <= 4) return p;
    resolution = std::max(4, int(resolution * 0.85));
  }
}

}  // namespace primo::editor
