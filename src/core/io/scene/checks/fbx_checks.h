#pragma once
// What an FBX file's structure may ask of Assimp, checked on its bytes before Assimp reads
// them. Assimp's FBX reader recurses once per level of record nesting and once per level of
// the model tree it builds from the file's connections, with no cycle check: a model that is
// its own parent, or two models that are each other's, crashed it, and a model connected twice
// to each of a chain of parents multiplies into an instancing bomb.

#include <string>
#include <string_view>

namespace primo::detail {

// Record (binary) or brace (ASCII) nesting at most; real files nest fewer than ten levels.
constexpr int kMaxFbxNesting = 64;

// Throws Error "<path>: cannot read: not an FBX file PriMo accepts (<rule>)" when the records
// of a binary FBX run past their parent or the file, nest deeper than kMaxFbxNesting, or when
// the models' parent connections ("OO" connections between models, and to the root 0) form a
// cycle, a tree deeper than kMaxSceneNodeDepth or one of more than kMaxSceneNodeInstances
// instances (node_graph_limits.h). `bytes` are the whole file, binary or ASCII.
void check_fbx_before_assimp(std::string_view bytes, const std::string& path);

}  // namespace primo::detail
