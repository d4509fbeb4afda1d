#pragma once
// What a mesh file carries beside positions and faces: texture coordinates, normals, vertex
// colours, materials and a skin (docs/mesh-io.md, "Attributes"). They belong to face corners (a UV seam
// or a hard edge gives one vertex several values), so each is a table of values and, for every
// face corner, an index into it. Corners are counted in face order: corner k of face f is
// corner first_corner(f) + k, the faces being those of the mesh the attributes were read with.
// A pose moves positions only: saving writes every attribute as read, with normals recomputed
// from the posed faces; the skin's vertex weights belong to vertices, not corners.

#include <array>
#include <string>
#include <vector>

#include "primo/mesh/mesh.h"

namespace primo {

// Values shared by face corners: `corner[c]` indexes `values`, -1 where corner c has none.
template <int N>
struct CornerValues {
  std::vector<std::array<double, N>> values;
  std::vector<int> corner;
};

// An image a texture shows: a file (`uri` as the source wrote it, relative to `folder`) or
// bytes the source embedded (`bytes` with their `mime_type`).
struct MeshImage {
  std::string name;
  std::string uri;
  std::string folder;  // the source file's folder, where a relative uri is found
  std::string mime_type;
  std::string bytes;
};

// A texture slot of a material: `image` indexes MeshAttributes::images (-1: none), `texcoord`
// the UV set it reads.
struct MaterialTexture {
  int image = -1;
  int texcoord = 0;
};

// A material as glTF's metallic-roughness model holds it; formats with other models (FBX's
// Phong) give their diffuse colour and texture as the base colour.
struct MeshMaterial {
  std::string name;
  std::array<double, 4> base_color{1, 1, 1, 1};
  double metallic = 1.0;
  double roughness = 1.0;
  std::array<double, 3> emissive{0, 0, 0};
  bool double_sided = false;
  std::string alpha_mode = "OPAQUE";  // OPAQUE, MASK or BLEND
  double alpha_cutoff = 0.5;
  MaterialTexture base_color_texture, metallic_roughness_texture, normal_texture, occlusion_texture,
      emissive_texture;
};

// A joint of a skin: a node of the file's hierarchy whose motion moves the vertices it weighs.
// Matrices are 4x4, column-major as glTF stores them.
struct SkinJoint {
  std::string name;
  int parent = -1;  // an earlier joint of the same skin; -1 for a root
  // The joint's rest transform relative to its parent joint (to the scene for a root), with the
  // transforms of nodes between them folded in.
  std::array<double, 16> rest{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  // From the mesh's coordinates as PriMo holds them (the scene's node transforms baked in) to the
  // joint's own coordinates in the bind pose.
  std::array<double, 16> inverse_bind{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};

// The most influences a vertex keeps: what glTF's JOINTS_0 and WEIGHTS_0 hold.
inline constexpr int kSkinInfluences = 4;

// A skin: joints and, per mesh vertex, up to kSkinInfluences (joint, weight) pairs whose weights
// sum to 1 (unused slots: joint 0, weight 0). A posed mesh is the skin's new bind-pose shape.
struct MeshSkin {
  std::vector<SkinJoint> joints;
  std::vector<std::array<int, kSkinInfluences>> vertex_joints;
  std::vector<std::array<double, kSkinInfluences>> vertex_weights;

  bool empty() const { return joints.empty(); }
};

struct MeshAttributes {
  // UV sets (u, v with v up, as OBJ and OpenGL have it; glTF's own v runs down and is flipped
  // on reading and writing).
  std::vector<CornerValues<2>> texcoords;
  // Vertex colour sets (r, g, b, a in [0, 1]).
  std::vector<CornerValues<4>> colors;
  // Normal slots: `normal_corner[c]` is corner c's slot (-1: none), `n_normals` their number.
  // Their values are not kept: they are recomputed from the faces (corner_normals).
  std::vector<int> normal_corner;
  int n_normals = 0;
  // Per face, an index into `materials` (-1: none); empty when the file assigns none.
  std::vector<int> face_material;
  std::vector<MeshMaterial> materials;
  std::vector<MeshImage> images;
  // The skin of a scene file's skinned meshes (empty for other files and unskinned scenes).
  MeshSkin skin;
  // An OBJ file's text and path: an OBJ of the same mesh is written as this text with only
  // its `v` and `vn` lines replaced (docs/mesh-io.md, "OBJ").
  std::string obj_text;
  std::string obj_path;

  bool empty() const {
    return texcoords.empty() && colors.empty() && n_normals == 0 && face_material.empty() &&
           skin.empty() && obj_text.empty();
  }
};

// The first corner of every face and, last, the number of corners (size n_faces + 1).
std::vector<int> first_corners(const Mesh& mesh);

// The value of every normal slot: the normalized sum of the area vectors of the faces whose
// corners use it (each face once), so that a hard edge stays hard and a smooth surface smooth.
// A slot no face uses, or whose faces cancel, gets +z.
std::vector<Vec3> corner_normals(const Mesh& mesh, const MeshAttributes& attributes);

// Throws Error "<source>: ..." when the attributes do not fit the mesh (a corner table of the
// wrong size, an index out of its table, a non-finite value; a skin whose weights are negative,
// not finite or do not sum to 1, whose joint indices or parents are out of range, or whose
// matrices are not finite): what a reader checks before it
// hands them on, and a writer before it writes them.
void check_attributes(const Mesh& mesh, const MeshAttributes& attributes,
                      const std::string& source);

}  // namespace primo
