#include "mirror.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace primo::editor {
namespace {

// Face centroids in a uniform grid, for nearest-centroid queries.
class CentroidGrid {
 public:
  CentroidGrid(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
    for (size_t i = 0; i < points.size(); ++i) cells_[key(cell_of(points[i]))].push_back(int(i));
  }
  // Nearest point within `radius`, or -1.
  int nearest(const Vec3& p, double radius) const {
    const std::vector<int> one = nearest(p, radius, 1);
    return one.empty() ? -1 : one.front();
  }
  // Up to `k` points within `radius`, nearest first (ties by index).
  std::vector<int> nearest(const Vec3& p, double radius, size_t k) const {
    std::vector<std::pair<double, int>> found;
    within(p, radius, found);
    std::sort(found.begin(), found.end());
    std::vector<int> out;
    for (size_t i = 0; i < found.size() && i < k; ++i) out.push_back(found[i].second);
    return out;
  }
  // Every point within `radius` with its squared distance, in no order.
  void within(const Vec3& p, double radius, std::vector<std::pair<double, int>>& found) const {
    found.clear();
    const Eigen::Vector3i c = cell_of(p);
    const int span = std::max(1, int(std::ceil(radius / cell_)));
    for (int dx = -span; dx <= span; ++dx)
      for (int dy = -span; dy <= span; ++dy)
        for (int dz = -span; dz <= span; ++dz) {
          const auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const int i : it->second) {
            const double d2 = (points_[size_t(i)] - p).squaredNorm();
            if (d2 < radius * radius) found.emplace_back(d2, i);
          }
        }
  }

 private:
  Eigen::Vector3i cell_of(const Vec3& p) const {
    return Eigen::Vector3i(int(std::floor(p.x() / cell_)), int(std::floor(p.y() / cell_)),
                           int(std::floor(p.z() / cell_)));
  }
  static std::int64_t key(const Eigen::Vector3i& c) {
    return (std::int64_t(c.x() & 0x1fffff) << 42) | (std::int64_t(c.y() & 0x1fffff) << 21) |
           std::int64_t(c.z() & 0x1fffff);
  }
  const std::vector<Vec3>& points_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

MirrorMap empty_map(const MeshTopology& t, int axis) {
  MirrorMap map;
  map.axis = axis;
  map.plane = 0.5 * (t.bbox_min[axis] + t.bbox_max[axis]);
  map.face_twin.assign(size_t(t.n_faces), -1);
  return map;
}

double mean_face_size(const MeshTopology& t) {
  double area = 0.0;
  for (const double a : t.rest_geometry.area) area += a;
  return std::sqrt(area / std::max(1, t.n_faces));
}

// Position matches with a search radius of `reach` face sizes; `errors` gets each face's
// distance from its reflected centroid to its match's centroid (infinite when none).
std::vector<int> nearest_twins(const MeshTopology& t, const MirrorMap& map, double reach,
                               std::vector<double>* errors) {
  const std::vector<Vec3>& c = t.rest_geometry.centroid;
  const double size = std::max(mean_face_size(t), 1e-12 * std::max(t.bbox_diagonal, 1e-300));
  const CentroidGrid grid(c, reach * size);
  std::vector<int> twin(size_t(t.n_faces), -1);
  if (errors) errors->assign(size_t(t.n_faces), INFINITY);
  for (int f = 0; f < t.n_faces; ++f) {
    const Vec3 r = reflect(map, c[size_t(f)]);
    twin[size_t(f)] = grid.nearest(r, reach * size);
    if (errors && twin[size_t(f)] >= 0) (*errors)[size_t(f)] = (c[size_t(twin[size_t(f)])] - r).norm();
  }
  return twin;
}

// Each face's mean edge length at rest: the scale of a reflection's error, local because a
// remeshed scan has small faces where it is detailed and large ones where it is flat.
std::vector<double> mean_edge_lengths(const MeshTopology& t) {
  std::vector<double> length(size_t(t.n_faces), 0.0);
  for (int f = 0; f < t.n_faces; ++f) {
    const int b = t.face_begin[f], d = t.degree(f);
    for (int k = 0; k < d; ++k)
      length[size_t(f)] += (t.rest_points[size_t(t.face_vertices[size_t(b + (k + 1) % d)])] -
                            t.rest_points[size_t(t.face_vertices[size_t(b + k)])])
                               .norm();
    length[size_t(f)] /= std::max(d, 1);
  }
  return length;
}

// Twins one to one: every pair of faces whose reflected centroid lands within `reach` edge
// lengths of the other's (the larger face's edge), nearest pairs first, each face taken once.
// The distance is the same seen from either face (a reflection keeps distances), so the result
// is an involution; a face on the plane may be its own twin.
std::vector<int> one_to_one_twins(const MeshTopology& t, const MirrorMap& map, double reach) {
  const std::vector<Vec3>& c = t.rest_geometry.centroid;
  const std::vector<double> edge = mean_edge_lengths(t);
  std::vector<double> sorted = edge;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double floor = 1e-12 * std::max(t.bbox_diagonal, 1e-300);
  const CentroidGrid grid(c, reach * std::max(sorted[sorted.size() / 2], floor));
  struct Pair {
    double distance;
    int a, b;
    bool operator<(const Pair& o) const {
      return std::tie(distance, a, b) < std::tie(o.distance, o.a, o.b);
    }
  };
  std::vector<Pair> pairs;
  std::vector<std::pair<double, int>> found;
  for (int f = 0; f < t.n_faces; ++f) {
    grid.within(reflect(map, c[size_t(f)]), reach * std::max(edge[size_t(f)], floor), found);
    for (const auto& [d2, g] : found) pairs.push_back({std::sqrt(d2), std::min(f, g), std::max(f, g)});
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> twin(size_t(t.n_faces), -1);
  for (const Pair& p : pairs)
    if (twin[size_t(p.a)] < 0 && twin[size_t(p.b)] < 0) twin[size_t(p.a)] = p.b, twin[size_t(p.b)] = p.a;
  return twin;
}

// Shared-edge neighbours: for face f's edge k (from its k-th to its (k+1)-th vertex), the face
// across it and that face's edge index; -1 on a boundary or a non-manifold edge.
struct EdgeNeighbours {
  std::vector<int> face, edge;  // indexed by face_begin[f] + k
};

EdgeNeighbours edge_neighbours(const MeshTopology& t) {
  EdgeNeighbours n;
  n.face.assign(t.face_vertices.size(), -1);
  n.edge.assign(t.face_vertices.size(), -1);
  std::unordered_map<std::uint64_t, int> first;  // undirected edge -> slot seen first
  first.reserve(t.face_vertices.size());
  std::vector<int> slot_face(t.face_vertices.size());
  for (int f = 0; f < t.n_faces; ++f)
    for (int k = 0; k < t.degree(f); ++k) slot_face[size_t(t.face_begin[f] + k)] = f;
  std::vector<char> non_manifold(t.face_vertices.size(), 0);
  for (int f = 0; f < t.n_faces; ++f) {
    const int b = t.face_begin[f], d = t.degree(f);
    for (int k = 0; k < d; ++k) {
      const std::uint32_t a = std::uint32_t(t.face_vertices[size_t(b + k)]);
      const std::uint32_t c = std::uint32_t(t.face_vertices[size_t(b + (k + 1) % d)]);
      const std::uint64_t key = (std::uint64_t(std::min(a, c)) << 32) | std::max(a, c);
      const auto [it, inserted] = first.emplace(key, b + k);
      if (inserted) continue;
      const int other = it->second;
      if (n.face[size_t(other)] >= 0) {  // a third face on this edge
        non_manifold[size_t(other)] = 1;
        continue;
      }
      n.face[size_t(other)] = f, n.edge[size_t(other)] = k;
      const int of = slot_face[size_t(other)];
      n.face[size_t(b + k)] = of, n.edge[size_t(b + k)] = other - t.face_begin[of];
    }
  }
  for (size_t s = 0; s < non_manifold.size(); ++s)
    if (non_manifold[s]) n.face[s] = -1;
  return n;
}

// Spreads a seed correspondence: vertex i of face f is vertex (k - i) mod d of face g. Writes
// twins into `twin` (all -1 where not reached) and returns the number of faces matched, or -1
// when the spread contradicts itself (the seed was wrong or the mesh is not symmetric).
// `error` gets the summed distance of reflected centroids from their twins'; the spread stops
// (returning -1) once it passes `max_error`.
int spread(const MeshTopology& t, const EdgeNeighbours& n, const MirrorMap& map, int seed_f,
           int seed_g, int seed_k, double max_error, double& error, std::vector<int>& twin,
           std::vector<int>& vertex_twin) {
  error = 0.0;
  std::fill(twin.begin(), twin.end(), -1);
  std::fill(vertex_twin.begin(), vertex_twin.end(), -1);
  std::vector<int> offset(size_t(t.n_faces), 0);
  auto vertex = [&](int f, int i) {
    const int d = t.degree(f);
    return t.face_vertices[size_t(t.face_begin[f] + ((i % d) + d) % d)];
  };
  auto pair_vertices = [&](int v, int w) {
    if (vertex_twin[size_t(v)] < 0 && vertex_twin[size_t(w)] < 0) {
      vertex_twin[size_t(v)] = w, vertex_twin[size_t(w)] = v;
      return true;
    }
    return vertex_twin[size_t(v)] == w && vertex_twin[size_t(w)] == v;
  };
  std::deque<int> queue;
  int matched = 0;
  auto pair_faces = [&](int f, int g, int k) {
    const int d = t.degree(f);
    if (t.degree(g) != d) return false;
    k = ((k % d) + d) % d;
    if (twin[size_t(f)] >= 0 || twin[size_t(g)] >= 0) {
      if (twin[size_t(f)] != g || twin[size_t(g)] != f) return false;
      return vertex_twin[size_t(vertex(f, 0))] == vertex(g, k);
    }
    for (int i = 0; i < d; ++i)
      if (!pair_vertices(vertex(f, i), vertex(g, k - i))) return false;
    twin[size_t(f)] = g, twin[size_t(g)] = f;
    offset[size_t(f)] = k, offset[size_t(g)] = k;
    matched += f == g ? 1 : 2;
    error += (f == g ? 1.0 : 2.0) * (reflect(map, t.rest_geometry.centroid[size_t(f)]) -
                                     t.rest_geometry.centroid[size_t(g)])
                                        .norm();
    if (error > max_error) return false;
    queue.push_back(f);
    return true;
  };
  if (!pair_faces(seed_f, seed_g, seed_k)) return -1;
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    const int g = twin[size_t(f)], k = offset[size_t(f)], d = t.degree(f);
    for (int i = 0; i < d; ++i) {
      // f's edge i runs from vertex i to i + 1; its image runs from g's k - i to k - i - 1,
      // which is g's edge j = k - i - 1 (from j to j + 1) traversed backwards.
      const int j = (((k - i - 1) % d) + d) % d;
      const int fn = n.face[size_t(t.face_begin[f] + i)];
      const int gn = n.face[size_t(t.face_begin[g] + j)];
      if ((fn < 0) != (gn < 0)) return -1;
      if (fn < 0) continue;
      // Vertex i of f sits at fn's slot a; its twin (g's k - i) at gn's slot b.
      const int a = (n.edge[size_t(t.face_begin[f] + i)] + 1) % t.degree(fn);
      const int b = n.edge[size_t(t.face_begin[g] + j)];
      if (t.degree(fn) != t.degree(gn)) return -1;
      if (!pair_faces(fn, gn, a + b)) return -1;
    }
  }
  return matched;
}

}  // namespace

const char* axis_name(int axis) { return axis == 0 ? "X" : axis == 1 ? "Y" : "Z"; }

Vec3 reflect(const MirrorMap& map, const Vec3& p) {
  Vec3 r = p;
  r[map.axis] = 2.0 * map.plane - p[map.axis];
  return r;
}

MirrorMap match_mirror_by_position(const MeshTopology& t, int axis, double reach) {
  MirrorMap map = empty_map(t, axis);
  if (t.n_faces == 0) return map;
  // A scanned or sculpted mesh is rarely centred on its own bounding box along the mirror
  // axis: the plane moves to the median midpoint of matched pairs, a few times.
  for (int round = 0; round < 3; ++round) {
    const std::vector<int> near = nearest_twins(t, map, 2.0, nullptr);
    std::vector<double> middle;
    for (int f = 0; f < t.n_faces; ++f)
      if (near[size_t(f)] >= 0)
        middle.push_back(0.5 * (t.rest_geometry.centroid[size_t(f)][axis] +
                                t.rest_geometry.centroid[size_t(near[size_t(f)])][axis]));
    if (middle.size() < size_t(t.n_faces) / 10) break;
    std::nth_element(middle.begin(), middle.begin() + middle.size() / 2, middle.end());
    map.plane = middle[middle.size() / 2];
  }
  map.face_twin = one_to_one_twins(t, map, reach);
  for (const int g : map.face_twin) map.matched += g >= 0;
  return map;
}

MirrorMap match_mirror_by_topology(const MeshTopology& t, int axis) {
  MirrorMap map = empty_map(t, axis);
  map.by_topology = true;
  if (t.n_faces == 0) return map;
  const EdgeNeighbours n = edge_neighbours(t);
  // Seeds: faces whose reflected centroid lands near some face (a wide search, since a posed or
  // shifted mesh lands off its twins), nearest the plane first: away from it, a posed or
  // bulging side has moved most. Each seed is tried with its few nearest candidate twins
  // (a face straddling the plane lands on itself and on its neighbours) in every alignment.
  std::vector<double> error;
  const std::vector<int> near = nearest_twins(t, map, 4.0, &error);
  std::vector<double> from_plane(size_t(t.n_faces));
  for (int f = 0; f < t.n_faces; ++f)
    from_plane[size_t(f)] = std::abs(t.rest_geometry.centroid[size_t(f)][axis] - map.plane) +
                            error[size_t(f)];
  std::vector<int> order(size_t(t.n_faces));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return from_plane[size_t(a)] < from_plane[size_t(b)]; });
  const double reach = 4.0 * std::max(mean_face_size(t), 1e-12 * t.bbox_diagonal);
  const CentroidGrid grid(t.rest_geometry.centroid, reach);
  std::vector<int> twin(size_t(t.n_faces)), vertex_twin(size_t(t.n_vertices));
  constexpr int kSeedsPerPiece = 8;
  // Twelve: on a posed mesh the reflected centroid lands more than a face away from its twin
  // (an icosphere turned 3 degrees, one side bulged 15%, jittered: with four candidates the
  // true twin was among them for 3 of 60 jitters, with twelve for all 60; the real meshes'
  // matching took the same time, their wrong seeds contradict within a few faces).
  constexpr size_t kCandidates = 12;
  // A consistent spread can still be another symmetry of the connectivity (a seven-sided tube
  // has seven mirror planes): kept only when it is near the geometric mirror.
  constexpr double kMaxMeanError = 0.05;  // of the diagonal, per face
  size_t next_seed = 0;
  // One connected piece per round: its consistent spread nearest the geometric mirror is kept.
  while (next_seed < order.size()) {
    std::vector<int> best;
    double best_error = kMaxMeanError * t.bbox_diagonal * t.n_faces;
    int tried = 0;
    for (; next_seed < order.size() && tried < kSeedsPerPiece; ++next_seed) {
      const int f = order[next_seed];
      if (near[size_t(f)] < 0) break;
      if (map.face_twin[size_t(f)] >= 0) continue;
      ++tried;
      for (const int g : grid.nearest(reflect(map, t.rest_geometry.centroid[size_t(f)]), reach,
                                      kCandidates)) {
        if (map.face_twin[size_t(g)] >= 0) continue;
        for (int k = 0; k < t.degree(f); ++k) {
          double e = 0.0;
          const int matched = spread(t, n, map, f, g, k, best_error, e, twin, vertex_twin);
          if (matched <= 0 || e > kMaxMeanError * t.bbox_diagonal * matched) continue;
          bool overlaps = false;
          for (int h = 0; h < t.n_faces && !overlaps; ++h)
            overlaps = twin[size_t(h)] >= 0 && map.face_twin[size_t(h)] >= 0;
          if (overlaps || e >= best_error) continue;
          best_error = e, best = twin;
        }
      }
    }
    if (best.empty()) break;
    for (int h = 0; h < t.n_faces; ++h)
      if (best[size_t(h)] >= 0) map.face_twin[size_t(h)] = best[size_t(h)], ++map.matched;
    if (map.matched == t.n_faces) break;
  }
  return map;
}

MirrorMap match_mirror(const MeshTopology& t, int axis) {
  MirrorMap by_topology = match_mirror_by_topology(t, axis);
  if (by_topology.matched == t.n_faces) return by_topology;
  MirrorMap by_position = match_mirror_by_position(t, axis);
  return by_topology.matched >= by_position.matched ? by_topology : by_position;
}

void mirror_changes(const FaceMask& before, FaceMask& after, const MirrorMap& map) {
  const FaceMask changed_from = after;
  for (size_t f = 0; f < after.size(); ++f) {
    if (before[f] == changed_from[f]) continue;
    const int g = map.face_twin[f];
    if (g >= 0) after[size_t(g)] = changed_from[f];
  }
}

FactorArray mirror_changes(const FactorArray& before, const FactorArray& after, int n_faces,
                           const MirrorMap& map) {
  if (before == after) return after;
  std::vector<double> result =
      after ? *after : std::vector<double>(size_t(n_faces), 1.0);
  bool any = false;
  for (int f = 0; f < n_faces; ++f) {
    const double b = factor_at(before, f), a = factor_at(after, f);
    const int g = map.face_twin[size_t(f)];
    if (b == a || g < 0 || result[size_t(g)] == a) continue;
    result[size_t(g)] = a;
    any = true;
  }
  if (!any) return after;
  if (std::all_of(result.begin(), result.end(), [](double v) { return v == 1.0; })) return nullptr;
  return std::make_shared<const std::vector<double>>(std::move(result));
}

std::vector<char> faces_without_twin(const MirrorMap& map) {
  std::vector<char> without(map.face_twin.size(), 0);
  for (size_t f = 0; f < without.size(); ++f) without[f] = map.face_twin[f] < 0;
  return without;
}

std::vector<int> mirror_faces(const std::vector<int>& faces, const MirrorMap& map) {
  std::vector<char> in(map.face_twin.size(), 0);
  for (const int f : faces) in[size_t(f)] = 1;
  std::vector<int> out;
  for (const int f : faces) {
    const int g = map.face_twin[size_t(f)];
    if (g >= 0 && !in[size_t(g)]) in[size_t(g)] = 1, out.push_back(g);
  }
  std::sort(out.begin(), out.end());
  return out;
}

Pose mirrored_pose(const HandleGroup& source, const HandleGroup& twin, const MirrorMap& map) {
  // Reflection M(x) = S x + d; the twin moves by M T M (x) = S R S x + S R d + S b + d.
  Mat3 S = Mat3::Identity();
  S(map.axis, map.axis) = -1.0;
  Vec3 d = Vec3::Zero();
  d[map.axis] = 2.0 * map.plane;
  const RigidTransform t = source.transform();
  const Mat3 R = S * t.rotation * S;
  const Vec3 b = S * t.rotation * d + S * t.translation + d;
  Pose pose;
  // A reflection turns a rotation vector into -S times it: the twin turns as far, the other way.
  pose.rotation = Eigen::Quaterniond(R).normalized();
  pose.turn = -(S * source.pose.whole_turn());
  pose.translate = b - twin.center + R * twin.center;
  return pose;
}

}  // namespace primo::editor
