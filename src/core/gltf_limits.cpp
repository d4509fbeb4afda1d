#include "gltf_limits.h"

#include <algorithm>
#include <vector>

#include "primo/error.h"

namespace primo::detail {
namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& rule) {
  throw Error(path + ": cannot read: not a glTF file PriMo accepts (" + rule + ")");
}

}  // namespace

void check_gltf_node_tree(const nlohmann::json& json, const std::string& path) {
  if (json.is_discarded() || !json.is_object()) return;
  const auto nodes_it = json.find("nodes");
  if (nodes_it == json.end() || !nodes_it->is_array()) return;
  const nlohmann::json& nodes = *nodes_it;
  const size_t n = nodes.size();
  // Children per node, checked for range.
  std::vector<std::vector<size_t>> children(n);
  std::vector<int> parents(n, 0);
  for (size_t v = 0; v < n; ++v) {
    if (!nodes[v].is_object()) continue;
    const auto list = nodes[v].find("children");
    if (list == nodes[v].end() || !list->is_array()) continue;
    for (const nlohmann::json& child : *list) {
      if (!child.is_number_integer() || child.get<long long>() < 0 ||
          child.get<unsigned long long>() >= n)
        refuse(path, "node " + std::to_string(v) + " lists a child " + child.dump() +
                         " that does not exist; the file has " + std::to_string(n) + " nodes");
      children[v].push_back(child.get<size_t>());
      ++parents[child.get<size_t>()];
    }
  }
  // Kahn's order from the nodes without parents: what it cannot reach lies on a cycle. The
  // same pass counts each node's instances (paths from a root) and its depth.
  std::vector<size_t> order;
  order.reserve(n);
  std::vector<int> waiting = parents;
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
    if (total > kMaxGltfNodeInstances)
      refuse(path, "its node tree expands to more than " + std::to_string(long(kMaxGltfNodeInstances)) +
                       " node instances (nodes listed as children more than once multiply)");
    if (depth[v] > kMaxGltfNodeDepth)
      refuse(path, "its node tree is deeper than " + std::to_string(kMaxGltfNodeDepth) +
                       " levels (node " + std::to_string(v) + ")");
    for (const size_t c : children[v]) {
      instances[c] = std::min(instances[c] + instances[v], 2 * kMaxGltfNodeInstances);
      depth[c] = std::max(depth[c], depth[v] + 1);
      if (--waiting[c] == 0) order.push_back(c);
    }
  }
  if (order.size() < n) {
    const size_t on_cycle = size_t(std::find_if(waiting.begin(), waiting.end(),
                                                [](int w) { return w > 0; }) - waiting.begin());
    refuse(path, "its node tree has a cycle, through or above node " + std::to_string(on_cycle));
  }
}

}  // namespace primo::detail
