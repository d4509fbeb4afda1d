#pragma once
// Internal to the core library: writing OBJ (docs/mesh-io.md, "OBJ"). save_mesh writes the
// bytes atomically.

#include <string>

#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_attributes.h"

namespace primo::detail {

// The mesh as OBJ, coordinates with 17 significant digits (read back as the same doubles).
// When `attributes` hold the text of the OBJ the mesh was read from (same vertex and face
// counts), that text is written with only its `v` lines (new positions; a colour after them
// kept) and `vn` lines (corner_normals) replaced, so every `vt`, face corner, `usemtl`, `g`, `o`,
// `s` and comment stays as it was; a `mtllib` line is rewritten to reach its library from
// `path`'s folder when that is another folder. Otherwise the attributes are written as `vt`
// (the first UV set), `vn` and `usemtl` lines with `v/vt/vn` corners.
std::string obj_bytes(const Mesh& mesh, const MeshAttributes& attributes, const std::string& path);

// A number with 17 significant digits, whatever the C locale; three of them with spaces.
void append_number(std::string& out, double value);
void append_point(std::string& out, const Vec3& p);

}  // namespace primo::detail
