#include "primo/solve/body_partition.h"

#include <algorithm>
#include <limits>

namespace primo {
namespace {

// Splits `bodies` in two at the median of their positions along the longest axis of their
// bounding box, `levels` times over.
void bisect(const std::vector<Vec3>& position, std::vector<int> bodies, int levels,
            std::vector<std::vector<int>>& parts) {
  if (levels == 0 || bodies.size() < 2) {
    std::sort(bodies.begin(), bodies.end());
    parts.push_back(std::move(bodies));
    return;
  }
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int b : bodies) {
    lo = lo.cwiseMin(position[size_t(b)]);
    hi = hi.cwiseMax(position[size_t(b)]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const size_t middle = bodies.size() / 2;
  // Ties broken by index, so the split never depends on the sort's whims.
  std::nth_element(bodies.begin(), bodies.begin() + middle, bodies.end(), [&](int a, int b) {
    const double ca = position[size_t(a)][axis], cb = position[size_t(b)][axis];
    return ca < cb || (ca == cb && a < b);
  });
  std::vector<int> upper(bodies.begin() + middle, bodies.end());
  bodies.resize(middle);
  bisect(position, std::move(bodies), levels - 1, parts);
  bisect(position, std::move(upper), levels - 1, parts);
}

// Greedy colouring of the parts' adjacency (two parts touch when an edge joins them), in
// part order: the smallest colour no earlier neighbour has.
std::vector<std::vector<int>> colour_parts(size_t n_bodies,
                                           const std::vector<std::vector<int>>& parts,
                                           const std::vector<std::pair<int, int>>& edges) {
  std::vector<int> part_of(n_bodies, -1);
  for (size_t p = 0; p < parts.size(); ++p)
    for (int b : parts[p]) part_of[size_t(b)] = int(p);
  std::vector<std::vector<int>> touching(parts.size());
  for (const auto& [a, b] : edges) {
    if (a < 0 || b < 0) continue;  // a coupling to a body that does not move
    const int p0 = part_of[size_t(a)], p1 = part_of[size_t(b)];
    if (p0 >= 0 && p1 >= 0 && p0 != p1) {
      touching[size_t(p0)].push_back(p1);
      touching[size_t(p1)].push_back(p0);
    }
  }
  std::vector<int> colour(parts.size(), -1);
  std::vector<std::vector<int>> colours;
  for (size_t p = 0; p < parts.size(); ++p) {
    std::vector<char> used(colours.size() + 1, 0);
    for (int q : touching[p])
      if (colour[size_t(q)] >= 0) used[size_t(colour[size_t(q)])] = 1;
    int c = 0;
    while (used[size_t(c)]) ++c;
    colour[p] = c;
    if (c == int(colours.size())) colours.emplace_back();
    colours[size_t(c)].push_back(int(p));
  }
  return colours;
}

}  // namespace

BodyPartition partition_bodies(std::vector<int> bodies, const std::vector<Vec3>& position,
                               const std::vector<std::pair<int, int>>& edges,
                               size_t bodies_per_part, int max_levels) {
  BodyPartition partition;
  int levels = 0;
  while (levels < max_levels && (bodies.size() >> (levels + 1)) >= bodies_per_part) ++levels;
  bisect(position, std::move(bodies), levels, partition.parts);
  partition.colours = colour_parts(position.size(), partition.parts, edges);
  return partition;
}

}  // namespace primo
