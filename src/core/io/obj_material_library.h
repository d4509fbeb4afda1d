#pragma once
// Internal to the core library: the material libraries (.mtl) an OBJ names, read for the
// colours and textures its materials carry into other formats (docs/mesh-io.md, "OBJ").

#include <string>

#include "primo/mesh/mesh_attributes.h"

namespace primo::detail {

// Fills the materials `attributes` hold (by name, from `usemtl`) with the base colour (Kd, d)
// and base colour texture (map_Kd) of the libraries the OBJ text's `mtllib` lines name,
// relative to `obj_path`'s folder. A library that cannot be read or parsed leaves the materials
// with their names: the returned note says which ("" when every library was read).
std::string read_obj_material_libraries(MeshAttributes& attributes, const std::string& obj_path);

}  // namespace primo::detail
