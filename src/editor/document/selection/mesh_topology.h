#pragma once
// Flat arrays the editor derives once per opened mesh: faces as vertex lists, the fan
// triangulation that is drawn, unique edges for the wireframe, vertex-to-face incidence for
// growing selections, and the rest geometry. Also the per-snapshot derived quantities
// (vertex normals, face centroids) computed on these arrays without touching OpenMesh.

#include <vector>

#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh.h"

namespace primo::editor {

struct MeshTopology {
  int n_vertices = 0;
  int n_faces = 0;
  // Face f's vertices are face_vertices[face_begin[f] .. face_begin[f + 1]).
  std::vector<int> face_begin;
  std::vector<int> face_vertices;
  // Fan triangulation, 3 indices per triangle; triangle t belongs to face triangle_face[t].
  std::vector<unsigned> triangles;
  std::vector<int> triangle_face;
  // Unique undirected polygon edges (no fan diagonals), 2 indices per edge.
  std::vector<unsigned> edges;
  // Faces around vertex v are vertex_faces[vertex_face_begin[v] .. vertex_face_begin[v + 1]).
  std::vector<int> vertex_face_begin;
  std::vector<int> vertex_faces;

  std::vector<Vec3> rest_points;
  FaceGeometry rest_geometry;
  Vec3 bbox_min = Vec3::Zero();
  Vec3 bbox_max = Vec3::Zero();
  double bbox_diagonal = 0.0;

  int degree(int f) const { return face_begin[f + 1] - face_begin[f]; }
};

MeshTopology build_topology(const Mesh& mesh);

// Area-weighted unit vertex normals of the polygon mesh at `points` (Newell vector areas), as
// 3 floats per vertex. A vertex whose normals cancel gets (0, 0, 1).
void compute_vertex_normals(const MeshTopology& topology, const std::vector<Vec3>& points,
                            std::vector<float>& normals);

// Vertex-average centroid of face f at `points`, and its Newell vector area (about that
// centroid; its direction is the face normal, its length the area).
Vec3 face_centroid(const MeshTopology& topology, const std::vector<Vec3>& points, int f);
Vec3 face_vector_area(const MeshTopology& topology, const std::vector<Vec3>& points, int f,
                      const Vec3& centroid);
// Every face's centroid at `points`.
std::vector<Vec3> face_centroids(const MeshTopology& topology, const std::vector<Vec3>& points);
// Mean of the faces' centroids at `points`, weighted by their rest areas (at the rest points:
// the scenario format's area-weighted centroid).
Vec3 weighted_centroid(const MeshTopology& topology, const std::vector<Vec3>& points,
                       const std::vector<int>& faces);

// A sphere around `points`: the centre of their bounding box and the largest distance from it.
void bounding_sphere(const std::vector<Vec3>& points, Vec3& center, double& radius);

}  // namespace primo::editor
