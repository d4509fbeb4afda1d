#pragma once
// The files a glTF asset's buffers name (in a .gltf's JSON or a .glb's JSON chunk). Assimp
// opens them itself, past the checks every other input gets (input_files.h): a named pipe
// there blocked the import forever, and a folder or a device gave a puzzling byte-count error.
// So each is checked as an input first.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace primo::detail {

// The parts of a glTF's JSON that the checks before Assimp read: its buffers (with their data
// URIs), buffer views, accessors, meshes, nodes, scenes, skins and animations (other data URIs,
// such as embedded images, shortened), parsed once for all of them.
// `bytes` are the .gltf's text or at least the start of a .glb (its header and JSON chunk).
// Throws Error naming `path` when the JSON nests deeper than kMaxJsonDepth (json_limits.h);
// discarded when it does not parse, which is left to Assimp to name.
nlohmann::json gltf_outline(std::string_view bytes, const std::string& path);

// Throws Error "<path>: buffer K (<uri>): <file>: <problem>" for the first buffer of
// `outline` (gltf_outline) whose file is missing, not a regular file, or larger than an input
// may be; files are looked up beside `path`.
void check_gltf_buffer_files(const nlohmann::json& outline, const std::string& path);

// The JSON text of a .gltf (all of `bytes`) or of a .glb's JSON chunk (as much as `bytes` hold;
// empty without one).
std::string_view gltf_json_text(std::string_view bytes);

}  // namespace primo::detail
