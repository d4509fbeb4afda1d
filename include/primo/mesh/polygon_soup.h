#pragma once
// A mesh as faces of vertex indices, and its validation into a Mesh: what every reader of
// primo/io/mesh_io.h returns, and what a mesh built from faces (subdivision) goes through.

#include <string>
#include <vector>

#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_attributes.h"

namespace primo {

// A polygon soup as a file lists it: points, faces as 0-based vertex indices, and what the file
// gives the faces' corners (UVs, normals, colours, materials; primo/mesh/mesh_attributes.h).
struct PolygonSoup {
  std::vector<Vec3> points;
  std::vector<std::vector<int>> faces;
  MeshAttributes attributes = {};
};

// Validates a soup and builds the mesh; `source` names it in errors (usually the file path).
// Throws Error for: no faces, an index out of range, a face with fewer than 3 vertices or a
// repeated vertex, a non-finite coordinate, a zero-area face, an edge with more than two faces,
// inconsistent orientation, and a non-manifold vertex. Each message names the first offending
// face/vertex indices.
Mesh mesh_from_soup(const PolygonSoup& soup, const std::string& source);

}  // namespace primo
