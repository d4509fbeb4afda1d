#pragma once
// Meshes from the scene formats artists export: glTF 2.0 (.gltf, .glb), FBX, COLLADA (.dae) and
// 3MF, read through Assimp (docs/mesh-io.md, "Scene formats"). A scene holds more than one
// polygon mesh: every mesh of the scene's node tree is taken with its node's transform, the
// vertices the exporter split for UVs or normals are merged by position (their UVs, normals and
// colours kept per face corner, with the materials and the skin: LoadedMesh::attributes), and
// what reading the file merged, kept or left out (animations, ...) is said in a one-line note.
// load_mesh (mesh_io.h) reads these formats too and drops the note.

#include <string>

#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_attributes.h"

namespace primo {

// A loaded mesh, and what reading its file changed or left out.
struct LoadedMesh {
  Mesh mesh;
  // One line for the user, "" when there is nothing to say (OFF, PLY, STL, OM; for an OBJ, a
  // material library that cannot be read):
  // "<path>: 2 meshes joined into one: ...; merged 16 vertex copies ...; ignored: ...".
  std::string note;
  // UVs, normals, colours, materials and skin, for save_mesh(mesh, attributes, path) to write
  // back.
  MeshAttributes attributes = {};
};

// True when the extension (any letter case) is one read through Assimp: .gltf .glb .fbx .dae
// .3mf.
bool is_scene_file(const std::string& path);

// load_mesh with the note: the editor shows it in its status line, `primo deform` and
// `primo replay` print it on stderr. Throws Error naming the file, as load_mesh does.
LoadedMesh load_mesh_noted(const std::string& path);

}  // namespace primo
