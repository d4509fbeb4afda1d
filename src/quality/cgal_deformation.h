#pragma once
// The peers PriMo is compared with: CGAL's Surface_mesh_deformation (as-rigid-as-possible
// surface modeling, Sorkine and Alexa 2007, and its smoothed-rotation variant SR-ARAP, Levi
// and Gotsman 2014). CGAL's headers stay in cgal_deformation.cpp.

#include <vector>

#include "primo/mesh/mesh.h"
#include "stopwatch.h"

namespace primo::quality {

enum class PeerMethod {
  Arap,    // CGAL::ORIGINAL_ARAP
  SrArap,  // CGAL::SRE_ARAP (default smoothing weight alpha 0.02)
};

const char* peer_method_name(PeerMethod method);  // "ARAP", "SR-ARAP"

struct PeerSettings {
  // CGAL's relative energy change between consecutive iterations at which deform() stops.
  double tolerance = 1e-6;
  unsigned max_iterations = 1000;  // a cap only; the tolerance ends the solve before it
};

struct PeerResult {
  std::vector<Vec3> positions;  // by vertex index
  Seconds seconds;              // preprocess (Laplacian assembly and factorization) + deform
};

// Deforms a triangle mesh with every vertex in the region of interest, the given control
// vertices moved to their targets (one target per control vertex) and the rest free.
// Throws Error when the mesh has a face that is not a triangle, when a control index is out
// of range, or when CGAL's preprocessing fails (a singular system).
PeerResult deform_with_cgal(const Mesh& triangle_mesh, const std::vector<int>& control_vertices,
                            const std::vector<Vec3>& targets, PeerMethod method,
                            const PeerSettings& settings = {});

}  // namespace primo::quality
