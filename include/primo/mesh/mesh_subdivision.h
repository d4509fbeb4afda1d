#pragma once
// Loop subdivision of triangle meshes, through OpenMesh's packaged subdivider: the benchmarks
// make large test meshes with it, and the tests check that the default material poses a model
// and its subdivided copy alike (docs/scenario-format.md, "prisms").

#include <string>

#include "primo/mesh/mesh.h"

namespace primo {

// `steps` Loop steps (each splits every triangle into four). The original vertices keep their
// indices (moved by Loop's smoothing rule); new vertices follow. Throws Error naming `source`
// when a face is not a triangle or the subdivider fails.
Mesh loop_subdivide(const Mesh& mesh, int steps, const std::string& source);

}  // namespace primo
