#include "gltf_limits.h"

#include <algorithm>
#include <vector>

#include "node_graph_limits.h"
#include "primo/util/error.h"

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
    }
  }
  const std::string problem =
      node_graph_problem(children, [](size_t v) { return "node " + std::to_string(v); });
  if (!problem.empty()) refuse(path, problem);
}

}  // namespace primo::detail
