#pragma once
// Internal to the core library: writing glTF 2.0 (docs/mesh-io.md, "glTF"). save_mesh writes
// the bytes atomically.

#include <string>

#include "primo/mesh.h"

namespace primo::detail {

// The mesh as glTF 2.0: one node, one mesh, one triangle primitive with POSITION (float32),
// NORMAL (area-weighted vertex normals) and uint32 indices. glTF holds triangles only, so every
// face is fan-triangulated around its first corner; the node's extras keep the face sizes
// ("primo_face_sizes": "4x2928", runs of size x count) so that PriMo reads the faces back as
// they were. `binary`: GLB; otherwise a .gltf JSON with the buffer embedded as a base64 data
// URI. `name` names the node (the file's stem). Throws Error "<path>: ..." for a mesh without
// faces, which glTF cannot hold.
std::string gltf_bytes(const Mesh& mesh, bool binary, const std::string& name,
                       const std::string& path);

// The name of the node extras key above.
inline constexpr const char* kFaceSizesKey = "primo_face_sizes";

}  // namespace primo::detail
