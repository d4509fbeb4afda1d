#pragma once
// The first bytes of a scene file against the format its extension names. Assimp picks its
// reader by content: when the reader of the extension declines the bytes, it tries each of
// its forty others, so a file named .gltf could reach the PLY, ASE, OpenGEX or BVH readers,
// several of which crash or hang on hostile input, and PriMo's own hardened OBJ, PLY and OFF
// readers would be bypassed by a rename. So each extension opens one door: its format's
// signature is checked before Assimp sees the bytes, and Assimp is left only that format's
// readers (read_scene_file).

#include <string>
#include <string_view>

namespace primo::detail {

// How many leading bytes the checks read.
constexpr size_t kSignatureBytes = 4096;

// The format the bytes look like ("PLY", "OBJ", "glTF", ...), or "" when none PriMo knows.
std::string format_of_bytes(std::string_view head);

// Throws Error "<path>: cannot read: not a glTF file (it looks like PLY: rename it .ply)"
// when `head` (the file's first kSignatureBytes, or all of it) does not begin as the format
// of `path`'s extension (.gltf, .glb, .fbx, .dae, .3mf) begins.
void check_scene_signature(std::string_view head, const std::string& path);

}  // namespace primo::detail
