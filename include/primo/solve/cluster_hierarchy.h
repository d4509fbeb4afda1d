#pragma once
// The levels of the hierarchical solver (paper Sect. 4.3): neighbouring bodies are grouped
// into clusters, and clusters into coarser clusters, until the coarsest level is small enough
// for global Newton matching. Handle bodies are never merged, so every handle stays one
// whole body at every level.
//
// Clustering is greedy aggregation on the body adjacency graph: a seed grows by repeatedly
// taking the unassigned neighbour nearest to the seed, which makes clusters compact (round
// rather than stringy) and of equal size; leftovers smaller than half the target size are
// merged into their smallest neighbouring cluster. It is linear in the number of bodies and
// deterministic.

#include <vector>

#include "primo/solve/block_matrix.h"
#include "primo/model/rigid_system.h"

namespace primo {

struct HierarchyOptions {
  int cluster_size = 8;              // bodies per cluster on every level
  int coarsest_max_bodies = 3000;    // stop coarsening below this many bodies (one level at least)
  int max_levels = 6;                // coarse levels at most
};

struct ClusterHierarchy {
  // cluster_of[l][b]: the level-(l+1) cluster of fine body b (level 0 = the fine bodies).
  std::vector<std::vector<int>> cluster_of;
  std::vector<int> cluster_count;  // per coarse level

  int coarse_levels() const { return int(cluster_of.size()); }
};

ClusterHierarchy build_cluster_hierarchy(const RigidSystem& fine, const HierarchyOptions& options);

// Greedy aggregation of one graph level (exposed for tests). Nodes with `locked` set stay
// alone. Returns the aggregate of every node; aggregates are numbered from 0.
// `adjacency` holds each node's neighbours (group v: node v's), sorted, without repeats.
std::vector<int> aggregate_nodes(const Groups& adjacency, const std::vector<Vec3>& position,
                                 const std::vector<bool>& locked, int target_size);

}  // namespace primo
