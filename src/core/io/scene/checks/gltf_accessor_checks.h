#pragma once
// What a glTF 2.0 asset's buffers, buffer views, accessors, mesh primitives, skins and
// animation samplers may ask of Assimp, checked on its JSON and its buffers' bytes before
// Assimp reads them. Assimp 5.2 trusts the numbers: an 814-byte asset with a sparse accessor of
// 100,000,000 vertices and no buffer view made it allocate 2.4 GB, a triangle strip of one
// index asked for 2^64 bytes, a line strip of one index wrote past its faces, a skinned mesh
// without inverse bind matrices crashed it, a byteStride smaller than the element read
// overlapping floats, a sparse accessor on a strided view and an index past the vertices read
// the wrong bytes (garbage positions, a dropped face), all without a word. Each is refused in
// one line naming the rule and the item.

#include <cstdint>
#include <deque>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace primo::detail {

// The bytes of each buffer of a glTF's outline (gltf_outline) as Assimp reads them.
struct GltfBufferBytes {
  // Per buffer: its bytes, or nullopt where they cannot be seen before Assimp (the checks
  // that need them are then left out for that buffer).
  std::vector<std::optional<std::string_view>> bytes;
  // Per buffer: where the bytes come from, for messages ("the GLB's binary chunk").
  std::vector<std::string> source;
  // Decoded data: URIs and files read; `bytes` may point into these or into the asset.
  std::deque<std::string> storage;
  bool glb = false;  // a .glb, whose buffer 0 is its binary chunk
};

// The buffers' bytes of the asset `bytes` (the .gltf's text or the whole .glb), as Assimp finds
// them: in a .glb, buffer 0 is always the binary chunk (Assimp ignores that buffer's uri);
// a data: URI is decoded as Assimp decodes it (base64 or raw); when `folder` is given, a uri
// names a file in it (the name as written). Points into `bytes`, which must outlive the result.
GltfBufferBytes gltf_buffer_bytes(const nlohmann::json& outline, std::string_view bytes,
                                  const std::optional<std::string>& folder);

// The most elements an accessor may have (what Assimp can count), and the most bytes of zeros
// an accessor without a buffer view may ask Assimp to allocate (a sparse one is allocated).
constexpr uint64_t kMaxGltfAccessorCount = 0xFFFFFFFFu;
constexpr uint64_t kMaxGltfViewlessBytes = uint64_t(1) << 28;

// Throws Error "<path>: cannot read: not a glTF file PriMo accepts (<rule>)" when
// - a buffer declares more bytes than it holds (binary chunk, data: URI, file), or its data:
//   URI begins its data after 127 characters;
// - a buffer view names no buffer, runs past its buffer's byteLength, or has a byteStride
//   outside 4..252 or not a multiple of 4;
// - an accessor has an unknown componentType or type, a count outside
//   1..kMaxGltfAccessorCount, names no buffer view, reads past its view (byteOffset +
//   (count - 1) x stride + element), has a stride smaller than its element, or has no view and
//   more elements than the largest accessor with one or than kMaxGltfViewlessBytes hold;
// - a sparse accessor's indices or values run past their views or have a byteStride, its count
//   is not 1..the accessor's, an index is not below the accessor's count, or its base view is
//   strided (Assimp 5.2 copies it as if it were packed);
// - a primitive has an unknown mode, no POSITION or a POSITION that is not float VEC3,
//   attributes or morph targets whose counts differ from POSITION's, indices that are not
//   unsigned SCALAR or point past POSITION's count (sparse substitutions included), fewer than
//   2 vertices for a line loop or strip, fewer than 3 for a triangle strip or fan, or a number
//   of triangle corners that is not a multiple of 3;
// - a node names a mesh that does not exist, or has a mesh and a skin whose inverseBindMatrices
//   are missing, not float MAT4 or fewer than its joints, or whose primitives' JOINTS_n name a
//   joint the skin lacks or whose float WEIGHTS_n are negative or not finite;
// - an animation sampler names an accessor that does not exist, or is CUBICSPLINE with fewer
//   than 3 outputs per input.
// JSON that did not parse, and glTF 1 (objects by id), are left to Assimp.
void check_gltf_accessors(const nlohmann::json& outline, const GltfBufferBytes& buffers,
                          const std::string& path);

}  // namespace primo::detail
