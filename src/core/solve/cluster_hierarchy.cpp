#include "primo/solve/cluster_hierarchy.h"

#include <algorithm>
#include <limits>

namespace primo {

std::vector<int> aggregate_nodes(const Groups& adjacency, const std::vector<Vec3>& position,
                                 const std::vector<bool>& locked, int target_size) {
  const int n = int(adjacency.begin.size()) - 1;
  auto neighbours = [&](int v) {
    return std::make_pair(adjacency.items.begin() + adjacency.begin[size_t(v)],
                          adjacency.items.begin() + adjacency.begin[size_t(v) + 1]);
  };
  std::vector<int> aggregate(n, -1);
  std::vector<int> size;
  std::vector<int> members, frontier;
  for (int seed = 0; seed < n; ++seed) {
    if (aggregate[seed] >= 0) continue;
    const int id = int(size.size());
    aggregate[seed] = id;
    size.push_back(1);
    if (locked[seed]) continue;
    members.assign(1, seed);
    while (size[id] < target_size) {
      // The unassigned free neighbour of the aggregate closest to its seed.
      int best = -1;
      double best_distance = std::numeric_limits<double>::infinity();
      for (int m : members)
        for (auto [nb_it, nb_end] = neighbours(m); nb_it != nb_end; ++nb_it) {
          const int nb = *nb_it;
          if (aggregate[nb] >= 0 || locked[nb]) continue;
          const double d = (position[nb] - position[seed]).squaredNorm();
          if (d < best_distance) best_distance = d, best = nb;
        }
      if (best < 0) break;
      aggregate[best] = id;
      members.push_back(best);
      ++size[id];
    }
  }

  // Merge small free aggregates into their smallest free neighbouring aggregate.
  std::vector<int> merged_into(size.size());
  for (size_t a = 0; a < size.size(); ++a) merged_into[a] = int(a);
  const Groups nodes_of = group_by(aggregate, int(size.size()));  // each in ascending order
  auto first_node = [&](size_t a) { return nodes_of.items[size_t(nodes_of.begin[a])]; };
  for (size_t a = 0; a < size.size(); ++a) {
    if (2 * size[a] >= target_size || locked[size_t(first_node(a))]) continue;
    int best = -1;
    for (int k = nodes_of.begin[a]; k < nodes_of.begin[a + 1]; ++k)
      for (auto [nb_it, nb_end] = neighbours(nodes_of.items[size_t(k)]); nb_it != nb_end; ++nb_it) {
        int other = aggregate[*nb_it];
        while (merged_into[other] != other) other = merged_into[other];
        if (other == int(a) || locked[size_t(first_node(size_t(other)))]) continue;
        if (best < 0 || size[other] < size[best]) best = other;
      }
    if (best < 0) continue;
    merged_into[a] = best;
    size[best] += size[a];
  }
  // Renumber the surviving aggregates densely.
  std::vector<int> final_id(size.size(), -1);
  int count = 0;
  for (size_t a = 0; a < size.size(); ++a)
    if (merged_into[a] == int(a)) final_id[a] = count++;
  for (int v = 0; v < n; ++v) {
    int a = aggregate[v];
    while (merged_into[a] != a) a = merged_into[a];
    aggregate[v] = final_id[a];
  }
  return aggregate;
}

ClusterHierarchy build_cluster_hierarchy(const RigidSystem& fine, const HierarchyOptions& options) {
  ClusterHierarchy h;
  const int n_fine = fine.n_bodies();

  // Level graph: nodes with positions, adjacency, locks, and each fine body's node.
  std::vector<int> node_of(n_fine);
  for (int b = 0; b < n_fine; ++b) node_of[b] = b;
  int n_nodes = n_fine;
  std::vector<bool> locked(n_fine);
  // The fine bodies' weights and centres, read once: each level's positions sum them in body
  // order (a Body keeps its faces in a vector of its own, one more pointer per read).
  std::vector<double> body_weight(size_t(n_fine), 0.0);
  std::vector<Vec3> body_center(static_cast<size_t>(n_fine));
  for (int b = 0; b < n_fine; ++b) {
    locked[b] = fine.bodies[b].kind != BodyKind::Free;
    body_weight[size_t(b)] = double(fine.bodies[b].faces.size());
    body_center[size_t(b)] = fine.bodies[b].rest_center;
  }
  // The graph's edges as pairs of ends (2k, 2k + 1) joining distinct nodes: the fine
  // couplings on the first level, then each level's edges between the clusters of the one
  // before it. A coarse level then reads its finer level's adjacency instead of every fine
  // coupling (at 240k faces five levels of the multigrid's hierarchy read 358,000 couplings
  // of 280 bytes each); two clusters are joined exactly when two of their nodes are, so the
  // sorted neighbour lists are the same.
  std::vector<int> end_node;
  end_node.reserve(2 * fine.couplings.size());
  for (const RigidSystem::Coupling& c : fine.couplings)
    if (c.body[0] != c.body[1]) {
      end_node.push_back(c.body[0]);
      end_node.push_back(c.body[1]);
    }

  // At least one coarse level, even when the fine level is small already: without one the
  // solver would be plain local sweeps.
  while (h.coarse_levels() < options.max_levels &&
         (h.coarse_levels() == 0 || n_nodes > options.coarsest_max_bodies)) {
    std::vector<Vec3> position(n_nodes, Vec3::Zero());
    std::vector<double> weight(n_nodes, 0.0);
    for (int b = 0; b < n_fine; ++b) {
      const double w = body_weight[size_t(b)];
      position[node_of[b]] += w * body_center[size_t(b)];
      weight[node_of[b]] += w;
    }
    for (int v = 0; v < n_nodes; ++v) position[v] /= weight[v];
    // The nodes' neighbours, each list sorted and without repeats (as compressed rows: one
    // small vector per node cost more than the aggregation at 180,000 bodies).
    Groups adjacency = group_by(end_node, n_nodes);  // node -> its edge ends
    for (int& end : adjacency.items) end = end_node[size_t(end ^ 1)];  // -> the other end's node
    int kept = 0;  // each list sorted and its repeats dropped, compacted in place
    for (int v = 0; v < n_nodes; ++v) {
      const auto first = adjacency.items.begin() + adjacency.begin[size_t(v)],
                 last = adjacency.items.begin() + adjacency.begin[size_t(v) + 1];
      std::sort(first, last);
      const int unique = int(std::unique(first, last) - first);
      adjacency.begin[size_t(v)] = kept;
      std::copy(first, first + unique, adjacency.items.begin() + kept);
      kept += unique;
    }
    adjacency.begin[size_t(n_nodes)] = kept;
    adjacency.items.resize(size_t(kept));
    std::vector<bool> node_locked(n_nodes, false);
    for (int b = 0; b < n_fine; ++b)
      if (locked[b]) node_locked[node_of[b]] = true;

    const std::vector<int> aggregate =
        aggregate_nodes(adjacency, position, node_locked, options.cluster_size);
    const int n_clusters = aggregate.empty() ? 0 : *std::max_element(aggregate.begin(), aggregate.end()) + 1;
    if (n_clusters * 3 > n_nodes * 2) break;  // cannot coarsen much further (handles, islands)
    end_node.clear();  // each edge once (lower node first), as a pair of clusters
    for (int v = 0; v < n_nodes; ++v)
      for (int k = adjacency.begin[size_t(v)]; k < adjacency.begin[size_t(v) + 1]; ++k) {
        const int u = adjacency.items[size_t(k)];
        if (u <= v || aggregate[size_t(u)] == aggregate[size_t(v)]) continue;
        end_node.push_back(aggregate[size_t(v)]);
        end_node.push_back(aggregate[size_t(u)]);
      }
    for (int b = 0; b < n_fine; ++b) node_of[b] = aggregate[node_of[b]];
    h.cluster_of.push_back(node_of);
    h.cluster_count.push_back(n_clusters);
    n_nodes = n_clusters;
  }
  return h;
}

}  // namespace primo
