#pragma once
// The layer of prisms extruded from the mesh faces (paper Sect. 3; scenario format "prisms"),
// in rest coordinates, and the elastic joints between neighbouring prisms.

#include <string>
#include <vector>

#include "primo/model/bilinear_inner_product.h"
#include "primo/model/constraints.h"
#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_order.h"

namespace primo {

// The shared side of two neighbouring prisms i = face[0], j = face[1] across the mesh edge
// (a, b), with a -> b the edge's direction in face[0]. Side s is prism face[s]'s own side
// patch f00 = a_s - h_a d_sa, f10 = b_s - h_b d_sb, f01 = a_s + h_a d_sa, f11 = b_s + h_b d_sb
// (both sides use the same (a, b) order so that u matches u), made from the prism corners
// corner[s][0] (a's) and corner[s][1] (b's): PrismLayer::joint_side. Its modes are not kept
// here: the rigid system keeps them relative to its bodies, and a second copy cost 192 bytes
// a joint (290 MB at a million faces).
struct Joint {
  int face[2];
  int vertex[2];  // a, b
  int corner[2][2];  // per side, the corners of a and b
  double weight;  // w_ij = |e_ij|^2 / (|F_i| + |F_j|)
};

struct PrismLayer {
  double mean_edge_length = 0.0;
  double bounding_box_diagonal = 0.0;
  int n_vertices = 0;

  // Per face (index = face index).
  std::vector<Vec3> face_centroid;
  std::vector<double> face_area;

  // Prism corners, face f owning [corner_begin[f], corner_begin[f + 1]) in the face's vertex
  // order: the width-scaled copy of the vertex (mid-surface) and the extrusion offset h d,
  // so the prism's corners are corner_point +- corner_offset.
  std::vector<int> corner_begin;
  std::vector<int> corner_vertex;
  std::vector<Vec3> corner_point;
  std::vector<Vec3> corner_offset;
  // Vertex -> its corners, in corner order: vertex v's are
  // vertex_corners[vertex_corner_begin[v] .. vertex_corner_begin[v + 1]) (gathers per vertex
  // run in parallel and add in the order a scatter over the faces would).
  std::vector<int> vertex_corner_begin;
  std::vector<int> vertex_corners;

  // One joint per interior edge; boundary edges have none.
  std::vector<Joint> joints;

  int n_faces() const { return int(face_centroid.size()); }
  int degree(int face) const { return corner_begin[face + 1] - corner_begin[face]; }
  // The side patch from corner a to corner b of one face: f00 = a's bottom, f10 = b's
  // bottom, f01 = a's top, f11 = b's top.
  PatchCorners corner_patch(int a, int b) const;
  // Side patch of a face towards its k-th edge (corner k to corner k + 1), boundary or not.
  PatchCorners side_patch(int face, int k) const;
  // The modes of a joint's side s (Joint).
  PatchModes joint_side(const Joint& joint, int side) const;
};

// Builds the layer. `params.face_*_factor` may be empty (all 1). Throws Error naming the face
// and vertex when a blended extrusion direction has zero length, and when the parameters are
// not finite or the factors have the wrong size. When `mesh` is a file's mesh renumbered by
// `order` (the solver's numbering), errors name the file's face and vertex.
PrismLayer build_prism_layer(const Mesh& mesh, const PrismParameters& params,
                             const MeshOrder* order = nullptr);

}  // namespace primo
