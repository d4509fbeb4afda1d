#pragma once
// What a scene's node graph may ask of a reader that walks it recursively and instantiates a
// node once per path that reaches it (Assimp's glTF, FBX and COLLADA readers): no cycle (a
// node that is its own ancestor never ends), a bounded depth (each level is a stack frame)
// and a bounded number of instances (a node listed twice by each of 40 parents in a chain is
// 2^40 nodes).

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace primo::detail {

// Nodes below a root at most (real assets nest a few dozen levels).
constexpr int kMaxSceneNodeDepth = 1000;
// Node instances a scene may expand to, at most (every path from a root to a node counts).
constexpr double kMaxSceneNodeInstances = 1e6;

// The first of these rules that the graph `children` (children[v]: v's children, repeats
// counted) breaks, in words for a message, or "" when it breaks none. The roots are the nodes
// without parents. `name` names node v ("node 3", "model 2000").
std::string node_graph_problem(const std::vector<std::vector<size_t>>& children,
                               const std::function<std::string(size_t)>& name);

}  // namespace primo::detail
