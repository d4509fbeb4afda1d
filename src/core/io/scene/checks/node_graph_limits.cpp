#include "node_graph_limits.h"

#include <algorithm>

namespace primo::detail {

std::string node_graph_problem(const std::vector<std::vector<size_t>>& children,
                               const std::function<std::string(size_t)>& name) {
  const size_t n = children.size();
  std::vector<size_t> waiting(n, 0);
  for (const auto& list : children)
    for (const size_t c : list) ++waiting[c];
  // Kahn's order from the nodes without parents: what it cannot reach lies on a cycle or
  // below one. The same pass counts each node's instances (paths from a root) and its depth.
  std::vector<size_t> order;
  order.reserve(n);
  std::vector<double> instances(n, 0.0);
  std::vector<int> depth(n, 0);
  for (size_t v = 0; v < n; ++v)
    if (waiting[v] == 0) {
      order.push_back(v);
      instances[v] = 1.0;
    }
  double total = 0.0;
  for (size_t i = 0; i < order.size(); ++i) {
    const size_t v = order[i];
    total += instances[v];
    if (total > kMaxSceneNodeInstances)
      return "its node tree expands to more than " + std::to_string(long(kMaxSceneNodeInstances)) +
             " node instances (nodes listed as children more than once multiply)";
    if (depth[v] > kMaxSceneNodeDepth)
      return "its node tree is deeper than " + std::to_string(kMaxSceneNodeDepth) + " levels (" +
             name(v) + ")";
    for (const size_t c : children[v]) {
      instances[c] = std::min(instances[c] + instances[v], 2 * kMaxSceneNodeInstances);
      depth[c] = std::max(depth[c], depth[v] + 1);
      if (--waiting[c] == 0) order.push_back(c);
    }
  }
  if (order.size() == n) return "";
  for (size_t v = 0; v < n; ++v)
    if (std::count(children[v].begin(), children[v].end(), v))
      return name(v) + " is its own parent";
  const size_t on_cycle = size_t(
      std::find_if(waiting.begin(), waiting.end(), [](size_t w) { return w > 0; }) - waiting.begin());
  return "its node tree has a cycle (it reaches " + name(on_cycle) + ")";
}

}  // namespace primo::detail
