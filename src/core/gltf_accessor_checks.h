#pragma once
// What a glTF 2.0 asset's buffers, buffer views, accessors and mesh primitives may ask of
// Assimp, checked on its JSON and its buffers' bytes before Assimp reads them. Assimp 5.2
// trusts the numbers: a 648-byte asset declaring an accessor of 100,000,000 vertices made it
// allocate 5 GB, a triangle strip of one index asked for 2^64 bytes, a byteStride smaller than
// the element read overlapping floats, a sparse accessor on a strided view and an index past
// the vertices read outside their arrays (garbage positions, a dropped face), all without a
// word. Each is refused in one line naming the rule and the item.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace primo::detail {

// The bytes of each buffer of `outline` (gltf_outline) that can be seen before Assimp: a
// .glb's binary chunk (its buffer without a uri), a base64 data: URI decoded, and when
// `folder` is given the file a uri names in it (as Assimp finds it). `bytes` are the whole
// asset (the .gltf's text or the whole .glb). nullopt where the bytes cannot be seen: the
// checks that need them are then left out for that buffer.
std::vector<std::optional<std::string>> gltf_buffer_bytes(const nlohmann::json& outline,
                                                          std::string_view bytes,
                                                          const std::optional<std::string>& folder);

// Throws Error "<path>: cannot read: not a glTF file PriMo accepts (<rule>)" when
// - a buffer view names no buffer, runs past its buffer's byteLength or past the buffer's
//   bytes, or has a byteStride outside 4..252 or not a multiple of 4;
// - an accessor has an unknown componentType or type, a count below 1, names no buffer view,
//   reads past its view (count x stride), or its view's stride is smaller than its element;
// - a sparse accessor's indices or values run past their views, its count exceeds the
//   accessor's, an index is not below the accessor's count, or its base view is strided
//   (Assimp 5.2 copies it as if it were packed);
// - a primitive has an unknown mode, no POSITION or a POSITION that is not float VEC3,
//   attributes or morph targets whose counts differ from POSITION's, indices that are not
//   unsigned SCALAR, fewer than 3 indices (or vertices) for a strip or fan, or an index past
//   POSITION's count.
// `buffers` are gltf_buffer_bytes'. JSON that did not parse is left to Assimp.
void check_gltf_accessors(const nlohmann::json& outline,
                          const std::vector<std::optional<std::string>>& buffers,
                          const std::string& path);

}  // namespace primo::detail
