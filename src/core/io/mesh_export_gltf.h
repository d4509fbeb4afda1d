#pragma once
// Internal to the core library: writing glTF 2.0 (docs/mesh-io.md, "glTF"). save_mesh writes
// the bytes atomically; the vertex animation writer (primo/io/mesh_animation_gltf.h) adds its
// morph targets to the same document.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_attributes.h"

namespace primo::detail {

using GltfJson = nlohmann::ordered_json;

// glTF's enumerations (the specification's names).
inline constexpr int kFloat = 5126;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kArrayBuffer = 34962;

// A glTF document before it becomes a file: its JSON without "buffers", and the one buffer's
// bytes (4-byte aligned), which its bufferViews address.
struct GltfDocument {
  GltfJson json;
  std::string buffer;
};

// The mesh as glTF 2.0: one node, one mesh, one triangle primitive with POSITION (float32),
// NORMAL (area-weighted vertex normals) and uint32 indices. glTF holds triangles only, so every
// face is fan-triangulated around its first corner; the node's extras keep the face sizes
// ("primo_face_sizes": "4x2928", runs of size x count) so that PriMo reads the faces back as
// they were. `name` names the node (the file's stem). Throws Error "<path>: ..." for a mesh
// without faces, which glTF cannot hold.
GltfDocument gltf_document(const Mesh& mesh, const std::string& name, const std::string& path);

// The document as a file: `binary`: GLB; otherwise a .gltf JSON with the buffer embedded as a
// base64 data URI. Throws Error "<path>: ..." for a GLB beyond its 4 GiB.
std::string gltf_file_bytes(GltfDocument document, bool binary, const std::string& path);

// gltf_file_bytes(gltf_document(...)).
std::string gltf_bytes(const Mesh& mesh, bool binary, const std::string& name,
                       const std::string& path);

// The NORMAL attribute: area-weighted vertex normals, unit length as glTF requires; a vertex
// without faces gets +z.
std::vector<Vec3> vertex_normals(const Mesh& mesh);

template <typename T>
void append_raw(std::string& out, const std::vector<T>& values) {
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// The same with the attributes the mesh was read with. Without any (attributes.empty() but for an
// OBJ's text) the file is the one above. With them, every face corner becomes a glTF vertex of its
// own where its UVs, colours or normal slot differ (corners that agree share one), the faces form
// one primitive per material (in the order the materials are first used, faces in file order within
// each), each the mesh of a node of its own with its face sizes and kVertexCopiesKey in the node's
// extras, and the primitives share TEXCOORD_n (v flipped to glTF's downward v), COLOR_n (float
// RGBA), NORMAL (corner_normals, or the vertex normals above when the file had none) and POSITION.
// Materials are written with their factors and textures; images are embedded in a GLB (a file the
// source refers to is read now), and in a .gltf embedded as a data URI when the source embedded
// them, else referred to relative to `path`'s folder. A skin adds JOINTS_0 (unsigned short) and
// WEIGHTS_0 (float) to the primitives, its joints as nodes after the mesh nodes and a skin the
// mesh nodes name (docs/mesh-io.md, "Attributes"). Throws Error "<path>: ..." as above, when an
// image file a GLB must embed cannot be read, and for a skin beyond glTF's 16-bit joint indices
// or an inverse bind matrix beyond float32.
std::string gltf_bytes(const Mesh& mesh, const MeshAttributes& attributes, bool binary,
                       const std::string& name, const std::string& path);

// The document gltf_bytes(mesh, attributes, ...) makes a file of: the plain one above without
// attributes, else one node and mesh per material, all sharing the vertex accessors.
GltfDocument gltf_document(const Mesh& mesh, const MeshAttributes& attributes, bool binary,
                           const std::string& name, const std::string& path);

// Whether the attributes change the glTF written (UVs, colours, normal slots, materials or a
// skin).
bool has_gltf_attributes(const MeshAttributes& attributes);

// The vertices of the file gltf_document(mesh, attributes, ...) writes: without attributes the
// mesh's own; with them one per distinct (vertex, normal slot, UVs, colours) of the corners,
// numbered in the order the corners first use them.
struct GltfVertices {
  std::vector<uint32_t> corner_vertex;  // per face corner, its glTF vertex
  std::vector<int> mesh_vertex;         // per glTF vertex, the mesh vertex it copies
  std::vector<int> normal_slot;         // per glTF vertex, its normal slot (-1: vertex normal)
  std::vector<size_t> first_corner;     // with attributes, per glTF vertex, its first corner
};
GltfVertices gltf_vertices(const Mesh& mesh, const MeshAttributes& attributes);

// The NORMAL of every glTF vertex: its slot's corner_normals, or vertex_normals without one.
std::vector<Vec3> gltf_vertex_normals(const Mesh& mesh, const MeshAttributes& attributes,
                                      const GltfVertices& vertices);

// The name of the node extras key above.
inline constexpr const char* kFaceSizesKey = "primo_face_sizes";
// A node extras key of files written with attributes: its vertices are copies per corner,
// merged by position when read back (as in files of other tools), its fans joined as above.
inline constexpr const char* kVertexCopiesKey = "primo_vertex_copies";

}  // namespace primo::detail
