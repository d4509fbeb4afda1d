#pragma once
// Reading and writing meshes. Vertex and face order are those of the file, so face and
// vertex indices in scenarios mean what they mean in the file.

#include <string>
#include <string_view>

#include "primo/mesh/polygon_soup.h"

namespace primo {

// Reads OBJ, OFF, PLY, STL or OM, parsed by PriMo (OpenMesh's readers are not safe on hostile
// files: docs/mesh-io.md; OBJ, OFF and OM keep doubles), and the scene formats glTF 2.0 (.gltf,
// .glb), FBX, COLLADA (.dae) and 3MF through Assimp, as primo/io/mesh_import.h says
// (load_mesh_noted also returns what was merged and ignored). The result is validated as
// `mesh_from_soup` does. Throws Error naming the file: unreadable, unknown extension, syntax
// error (with line number), truncated data, a count larger than the file, empty mesh, out of
// memory, and every problem `mesh_from_soup` reports.
Mesh load_mesh(const std::string& path);

// The soup a file's bytes hold, not yet validated; `path` picks the format by its extension
// and names the file in errors. load_mesh is mesh_from_soup(parse_mesh_bytes(file bytes)).
// The fuzz targets (fuzz/) call this with arbitrary bytes: it must throw Error or return,
// never crash, hang or allocate more than a small multiple of the input.
PolygonSoup parse_mesh_bytes(std::string_view bytes, const std::string& path);

// Writes the mesh by extension (OBJ, OFF, PLY, STL, OM, glTF .gltf/.glb) through a temporary
// file in the same folder that is renamed into place (primo/io/output_files.h), so a failure never
// leaves a partial file. OBJ and OFF are written with 17 significant digits. STL and glTF hold
// triangles only, so n-gons are fan-triangulated in the written file (glTF keeps the face sizes
// for PriMo to read back). FBX, COLLADA and 3MF are refused. Throws Error naming the file on
// failure.
void save_mesh(const Mesh& mesh, const std::string& path);

// save_mesh with the attributes the mesh was read with (LoadedMesh::attributes): OBJ writes
// them as `vt`, `vn`, `usemtl` and `mtllib` (the read file's text with only `v` and `vn`
// changed when it was an OBJ), glTF as texture coordinates, colours, normals, materials and
// images; OFF, PLY, STL and OM hold none of them. Normals are recomputed from the mesh
// (corner_normals). Throws Error naming the file, also when the attributes do not fit the mesh.
void save_mesh(const Mesh& mesh, const MeshAttributes& attributes, const std::string& path);

// What save_mesh(mesh, attributes, path) leaves out, for the user to read beside the result:
// "<path>: the skin (9 joints) is not saved: OBJ holds none; save as .gltf or .glb to keep it"
// for a skin saved to any format but glTF; "" when the file keeps everything it can be asked to.
std::string save_note(const MeshAttributes& attributes, const std::string& path);

// The bytes save_mesh writes for `path`'s format (what primo::StagedOutputs stages, so that a
// command can write a mesh and its statistics together). Throws Error naming `path`.
std::string mesh_file_bytes(const Mesh& mesh, const std::string& path);
std::string mesh_file_bytes(const Mesh& mesh, const MeshAttributes& attributes,
                            const std::string& path);

}  // namespace primo
