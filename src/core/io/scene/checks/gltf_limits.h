#pragma once
// What a glTF asset's node tree may ask of Assimp, checked on its JSON before Assimp walks it.
// Assimp's glTF readers recurse once per level of JSON nesting and of the node tree, and
// instantiate a node once per path that reaches it: JSON nested 200,000 deep and a chain of
// 20,000 nodes overflowed the stack, 40 nodes each listing the next twice asked for 2^40
// instances, and a node that is its own descendant never ends.

#include <nlohmann/json.hpp>
#include <string>

namespace primo::detail {

// Throws Error "<path>: cannot read: <rule>" when a node of `outline` (gltf_outline, which
// also limits the JSON's nesting) lists a child that does not exist, when the node tree has a
// cycle, is deeper than kMaxSceneNodeDepth or expands to more than kMaxSceneNodeInstances
// instances (node_graph_limits.h). JSON that did not parse is left to Assimp, which names the problem.
void check_gltf_node_tree(const nlohmann::json& outline, const std::string& path);

}  // namespace primo::detail
