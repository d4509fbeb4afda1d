#pragma once
// A vertex animation as one glTF 2.0 file (docs/mesh-io.md, "Vertex animations"): the rest
// mesh as save_mesh writes it to glTF, with the attributes it was read with (UVs, colours,
// materials: a mesh per material, sharing the vertices), every kept frame a morph target of
// each of its meshes (its displacement from the rest positions, and of the normals), and one
// animation of the meshes' weights that shows frame i at its time: weight 1 on target i and 0
// on the others, linear in between. The weights are frames x frames floats, which bounds the
// frame count of a file in practice.
//
// Frames are added one at a time and stored as the file will hold them (float32), so memory
// follows the file's size, not frames x vertices x doubles.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_attributes.h"

namespace primo {

namespace detail {
struct GltfVertices;
}

// The largest vertex animation file written (1 GiB); mesh_animation_size_bound above it is
// refused before anything is solved or written.
inline constexpr std::uint64_t kMaxAnimationFileBytes = std::uint64_t(1) << 30;

// What a file at `path` (.glb, or .gltf with its buffer in base64) of `frames` targets on
// `rest` with `attributes` can weigh at most: every target dense (positions and normals, 24
// bytes a glTF vertex: a vertex per face corner at most with attributes), the UVs and colours,
// the images, the weights (frames x frames floats) and times, the JSON. Throws Error for
// another extension.
std::uint64_t mesh_animation_size_bound(const Mesh& rest, std::uint64_t frames,
                                        const std::string& path,
                                        const MeshAttributes& attributes = {});

class MeshAnimation {
 public:
  // `attributes`: those `rest` was read with (LoadedMesh::attributes), written as save_mesh
  // writes them; throws Error when they do not fit the mesh.
  explicit MeshAnimation(const Mesh& rest, const MeshAttributes& attributes = {});

  // Adds a keyframe: `positions` (one per vertex of the rest mesh) shown at `seconds`, its
  // target named `name`. A target that moves fewer than a third of the vertices (as float32:
  // a vertex moves when its float32 position differs from the rest's) is written as a sparse
  // accessor, indices and values of the moved vertices; the others are dense. Times must not
  // decrease; a time equal to the previous one as float32 becomes the next float32 after it
  // (glTF's key times increase strictly). Throws Error naming the vertex for a position that
  // is not finite or beyond float32, and for a wrong count or a time that goes back or is not
  // finite.
  void add_frame(double seconds, const std::vector<Vec3>& positions, const std::string& name);
  size_t frames() const { return times_.size(); }

  // The file: GLB for a .glb `path`, JSON with the buffer embedded for .gltf; `path` names it
  // in errors and its stem names the node. Throws Error "<path>: ..." for another extension, an
  // animation without frames or a rest mesh glTF cannot hold.
  std::string file_bytes(const std::string& path) const;

 private:
  // Where the targets' data lie in `buffer_`; file_bytes numbers them after the rest mesh's.
  struct View {
    size_t offset = 0, length = 0;
    bool vertex_data = false;  // an ARRAY_BUFFER target (sparse parts have none)
  };
  struct Accessor {
    size_t count = 0;  // elements
    int components = 1;  // 1 SCALAR, 3 VEC3
    int view = -1;       // -1: the sparse values alone
    size_t sparse_count = 0;  // > 0: sparse, its indices and values in the next two views
    int sparse_indices = -1, sparse_values = -1;
    std::vector<float> min, max;  // empty: not written
  };
  struct Target {
    int position = 0, normal = 0;  // accessors
  };
  int add_accessor(const std::vector<float>& values, int components, bool bounds);
  int add_view(const std::string& bytes, bool vertex_data);

  Mesh rest_, posed_;
  MeshAttributes attributes_;
  // The file's vertices: the mesh's, or with attributes a copy per distinct corner.
  std::shared_ptr<const detail::GltfVertices> vertices_;
  std::vector<float> rest_positions_, rest_normals_;
  std::vector<float> times_;
  double last_seconds_ = 0.0;
  std::vector<std::string> names_;
  std::vector<Target> targets_;
  std::vector<Accessor> accessors_;
  std::vector<View> views_;
  std::string buffer_;
};

// Throws Error unless `path` ends in .glb or .gltf and check_output_path accepts it.
void check_animation_output_path(const std::string& path);

}  // namespace primo
