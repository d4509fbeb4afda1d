#pragma once
// The order the solvers number a mesh's faces, vertices and prism corners in, whatever order
// its file gave them. Files from different tools list the same surface in different orders
// (a Loop step appends its new vertices, an exporter writes faces by material, a scan's
// faces come as the scanner met them); the solvers sweep bodies, sum joints and gather
// vertices in index order, so an order that scatters neighbours over memory made a 238k-face
// frame 2.35 times slower, and clusters seeded in file order were different clusters.
//
// The solver's order depends on the geometry alone: faces breadth first over their edges
// (Cuthill-McKee) from a face at the far end of each component, neighbours taken along a
// Hilbert curve through the face centroids; each face's vertex cycle starting at its
// lexicographically smallest point; vertices in the order those faces first reach them. Two
// files of the same surface in any vertex and face order, with any cycle starting corner,
// give the same solver mesh, so the same bits up to the renumbering (faces whose centroids
// coincide exactly are the only ones ranked by their file order).

#include <cstdint>
#include <vector>

#include "primo/mesh/mesh.h"

namespace primo {

struct MeshOrder {
  // Solver face i is the file's face face_of[i]. Its vertex cycle is the file face's cycle
  // turned on by face_rotation[i]: solver corner j is the file face's corner
  // (j + face_rotation[i]) % degree.
  std::vector<int> face_of;
  std::vector<int> face_rotation;
  // Solver vertex i is the file's vertex vertex_of[i] (vertices no face uses come last, in
  // file order).
  std::vector<int> vertex_of;

  int n_faces() const { return int(face_of.size()); }
  int n_vertices() const { return int(vertex_of.size()); }
  // The inverses: the solver's number of each file face and vertex.
  std::vector<int> solver_faces() const;
  std::vector<int> solver_vertices() const;
  // Per-face values (motions, factors) from file order to solver order and back.
  template <class T>
  std::vector<T> faces_to_solver(const std::vector<T>& file_values) const {
    std::vector<T> out;
    out.reserve(face_of.size());
    for (int f : face_of) out.push_back(file_values[size_t(f)]);
    return out;
  }
  template <class T>
  std::vector<T> faces_to_file(const std::vector<T>& solver_values) const {
    std::vector<T> out(solver_values.size());
    for (size_t i = 0; i < face_of.size(); ++i) out[size_t(face_of[i])] = solver_values[i];
    return out;
  }
};

// The file's own order (no renumbering).
MeshOrder identity_order(const Mesh& mesh);

// The solver's order for `mesh` (above).
MeshOrder locality_order(const Mesh& mesh);

// A copy of `mesh`'s connectivity and points renumbered by `order` (no other properties).
// Throws Error when OpenMesh cannot build a face in that order.
Mesh reordered_mesh(const Mesh& mesh, const MeshOrder& order);
// The same into the empty `out`: false, instead of an exception, when OpenMesh cannot.
bool build_reordered_mesh(const Mesh& mesh, const MeshOrder& order, Mesh& out);

// `mesh` with its vertices and faces randomly renumbered and each face's cycle starting at a
// random corner, the same for the same seed: the same surface as another tool might write it
// (tests and `primo bench scaling`). Points only.
Mesh shuffled_mesh(const Mesh& mesh, std::uint64_t seed);

// The position of a point of the cube [0, 2^bits)^3 along the Hilbert curve through it
// (bits <= 21): points near each other on the curve are near each other in space.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits);

}  // namespace primo
