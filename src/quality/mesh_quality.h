#pragma once
// How good a deformation looks, measured by comparing the deformed mesh with its rest mesh
// (same vertices and faces, any polygons): volume and area change, bending (dihedral angles),
// stretching (edge lengths), fold-overs and self-intersections. docs/quality.md gives the
// exact definitions. No CGAL here: the exact self-intersection test sits behind
// self_intersections.h.

#include <optional>
#include <string>

#include "primo/mesh/mesh.h"

namespace primo::quality {

// A dihedral angle above this between the two face normals of an interior edge is a fold-over:
// the surface turns back on itself there.
inline constexpr double kFoldOverDegrees = 150.0;

struct QualityMetrics {
  int vertices = 0;
  int faces = 0;
  int interior_edges = 0;
  int boundary_loops = 0;  // capped for the volume
  // Enclosed volume with every boundary loop capped by a fan to the loop's centroid. Absent
  // when the rest volume is zero (a flat sheet), where a relative change means nothing.
  double rest_volume = 0.0;
  double deformed_volume = 0.0;
  std::optional<double> volume_change_percent;
  double rest_area = 0.0;
  double deformed_area = 0.0;
  double area_change_percent = 0.0;
  // |dihedral_deformed - dihedral_rest| over interior edges, in degrees; the dihedral angle is
  // the angle between the two faces' Newell normals (0 on a flat surface).
  double dihedral_change_rms_deg = 0.0;
  double dihedral_change_max_deg = 0.0;
  // |l_deformed - l_rest| / l_rest over all edges, in percent.
  double edge_change_rms_percent = 0.0;
  double edge_change_max_percent = 0.0;
  int fold_overs = 0;  // interior edges whose deformed normals are more than 150 degrees apart
  int self_intersecting_pairs = 0;  // distinct original faces of the deformed mesh
  int degenerate_triangles = 0;     // of the deformed mesh's triangulation (see self_intersections.h)
};

// Throws Error unless both meshes have the same vertex count, face count and face corners
// (vertex indices in the same order). The names are the meshes' files, used in the message.
void check_same_connectivity(const Mesh& rest, const Mesh& deformed, const std::string& rest_name,
                             const std::string& deformed_name);

// All metrics of `deformed` against `rest`. Throws Error (with the names) when the connectivity
// differs.
QualityMetrics measure_quality(const Mesh& rest, const Mesh& deformed,
                               const std::string& rest_name = "rest mesh",
                               const std::string& deformed_name = "deformed mesh");

// The volume enclosed by the mesh with its boundary loops capped: each face fanned about its
// centroid, each boundary loop fanned about the loop's vertex centroid, and the signed volumes
// of the tetrahedra with the origin summed (positive for outward-facing normals).
double capped_volume(const Mesh& mesh);

}  // namespace primo::quality
