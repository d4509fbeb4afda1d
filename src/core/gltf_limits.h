#pragma once
// What a glTF asset's node tree may ask of Assimp, checked on its JSON before Assimp walks it.
// Assimp's glTF readers recurse once per level of JSON nesting and of the node tree, and
// instantiate a node once per path that reaches it: JSON nested 200,000 deep and a chain of
// 20,000 nodes overflowed the stack, 40 nodes each listing the next twice asked for 2^40
// instances, and a node that is its own descendant never ends.

#include <string>
#include <string_view>

namespace primo::detail {

// Nodes below the root at most (real assets nest a few dozen levels).
constexpr int kMaxGltfNodeDepth = 1000;
// Node instances the scene may expand to, at most (every path from a root to a node counts).
constexpr double kMaxGltfNodeInstances = 1e6;

// Throws Error "<path>: cannot read: <rule>" when the JSON of a .gltf, or of a .glb's JSON
// chunk (`bytes` as read_gltf_json_part gives them), nests deeper than kMaxJsonDepth, when a
// node lists a child that does not exist or is its own ancestor, or when the node tree is
// deeper than kMaxGltfNodeDepth or expands to more than kMaxGltfNodeInstances instances.
// JSON that does not parse is left to Assimp, which names the problem.
void check_gltf_node_tree(std::string_view bytes, const std::string& path);

}  // namespace primo::detail
