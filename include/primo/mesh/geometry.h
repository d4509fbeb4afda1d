#pragma once
// Face and mesh measures exactly as the scenario format defines them.

#include <vector>

#include "primo/mesh/mesh.h"

namespace primo {

// Per-face centroid (vertex average), Newell vector area a_F = 1/2 sum (p_k - c) x (p_k+1 - c),
// area |a_F| and unit normal a_F / |a_F|, indexed by face index.
struct FaceGeometry {
  std::vector<Vec3> centroid;
  std::vector<Vec3> vector_area;
  std::vector<double> area;
  std::vector<Vec3> normal;
};

FaceGeometry compute_face_geometry(const Mesh& mesh);

// Unit vertex normals: normalized sum of incident faces' vector areas (area-weighted unit
// normals). A vertex with no face, or whose vector areas cancel (to 1e-12 of their summed
// areas), gets the zero vector.
std::vector<Vec3> compute_vertex_normals(const Mesh& mesh, const FaceGeometry& faces);

// Mean length over unique undirected edges.
double mean_edge_length(const Mesh& mesh);

// Length of the diagonal of the axis-aligned bounding box of the vertices faces use (isolated
// vertices do not count: one far away would change every length scaled by the diagonal).
double bounding_box_diagonal(const Mesh& mesh);

// The largest distance between corresponding points of two lists of the same length (two
// poses of one mesh's vertices): how far apart two shapes look. Throws std::invalid_argument
// when the lengths differ.
double largest_point_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

// Area-weighted mean of the given faces' centroids.
Vec3 area_weighted_centroid(const FaceGeometry& faces, const std::vector<int>& face_indices);

}  // namespace primo
