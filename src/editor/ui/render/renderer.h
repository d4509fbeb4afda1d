#pragma once
// Draws the mesh and reads the pick buffer. Buffers are uploaded only when told: the
// topology once per mesh (fan triangles, polygon edges, triangle -> face), positions and
// normals per solver result, per-face overlay colours when they change, prism corners when
// shown. The scene is drawn into an offscreen target (multisampled when asked) and copied to
// the window; it is drawn again only when the camera, the geometry, the colours or the display
// settings changed, so frames where only the panels change cost a copy. While the camera
// moves, a big mesh is drawn through its proxy (a decimated stand-in). The pick pass (face id and
// eye depth per pixel) is rendered on demand, only when the geometry or the camera changed
// since the last one. The ground grid (ground_grid.h) is drawn under the mesh, blended and
// depth-tested, and never into the pick pass: it cannot be picked.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "view/camera.h"
#include "editor.h"
#include "gl.h"
#include "gl_shader.h"
#include "view/ground_grid.h"
#include "document/selection/mesh_topology.h"
#include "document/proxy_mesh.h"

namespace primo::editor {

class MeshRenderer : public Picker {
 public:
  // Loads the shaders from `shader_folder`; throws primo::Error (path and GL log) on failure.
  // `samples`: multisampling of the scene (0 for none).
  MeshRenderer(const std::string& shader_folder, int samples);
  ~MeshRenderer() override;
  MeshRenderer(const MeshRenderer&) = delete;
  MeshRenderer& operator=(const MeshRenderer&) = delete;

  // The camera pick passes use (the editor's).
  void set_camera(const Camera* camera) { camera_ = camera; }
  // A new mesh: drawn in full until set_proxy gives it a stand-in.
  void set_topology(const MeshTopology& topology);
  void set_proxy(const ProxyTriangles& proxy);
  void set_geometry(const std::vector<float>& positions, const std::vector<float>& normals);
  void set_prism_corners(const std::vector<float>& corners);  // empty: none to show
  void set_face_colors(const std::vector<std::uint32_t>& colors);
  // Vertex mode's points (vertex indices): every vertex shown, and the selected ones drawn
  // larger; both empty in face mode.
  void set_vertex_points(const std::vector<unsigned>& shown, const std::vector<unsigned>& selected);
  // The wireframe's edges (pairs of vertex indices): the topology's, less those of hidden faces.
  void set_edges(const std::vector<unsigned>& edges);
  void set_ground_grid(const GroundGrid& grid);
  bool has_mesh() const { return triangle_count_ > 0; }

  // Draws background and mesh into the rectangle (GL window coordinates, origin bottom-left)
  // of the window's framebuffer.
  void draw(const DisplaySettings& display, int x, int y, int width, int height);
  // A fingerprint of the scene draw() would show with these settings now: equal to the last
  // one when the picture of the 3D view would be the same (view/shown_picture.h). Tracks the
  // camera's motion as draw() does.
  std::uint64_t scene_fingerprint(const DisplaySettings& display, int width, int height);
  // Whether the last draw used the proxy (the camera was moving).
  bool drew_proxy() const { return drew_proxy_; }
  // A gesture is under way (drag, stroke, orbit): big meshes stay on the proxy until it ends.
  void set_interactive(bool interactive) { interactive_ = interactive; }
  // The camera moved or a gesture was under way at the last draw, or a moment before it.
  bool in_motion() const { return in_motion_; }

  PickImage read(int x0, int y0, int width, int height) override;
  // Small meshes always; big ones (with a proxy) while the pick pass is current.
  bool cheap_to_read() const override;

 private:
  void render_pick();
  bool pick_current() const;
  void render_scene(const DisplaySettings& display, int width, int height, bool proxy);
  void render_grid();
  void ensure_scene_target(int width, int height);

  const Camera* camera_ = nullptr;
  ShaderProgram mesh_, pick_, lines_, background_, grid_program_;
  GLuint vao_ = 0, position_vbo_ = 0, normal_vbo_ = 0, triangle_ebo_ = 0, edge_ebo_ = 0;
  GLuint triangle_face_buffer_ = 0, triangle_face_texture_ = 0;
  GLuint color_buffer_ = 0, color_texture_ = 0;
  GLuint prism_vao_ = 0, prism_vbo_ = 0, prism_ebo_ = 0;
  GLuint empty_vao_ = 0;
  GLsizei triangle_count_ = 0, edge_index_count_ = 0, prism_index_count_ = 0;
  GLuint point_ebo_ = 0, selected_point_ebo_ = 0;
  GLsizei point_count_ = 0, selected_point_count_ = 0;
  bool prisms_uploaded_ = false;
  GLuint proxy_ebo_ = 0, proxy_face_buffer_ = 0, proxy_face_texture_ = 0;
  GLsizei proxy_count_ = 0;
  GLuint grid_vao_ = 0, grid_vbo_ = 0;
  GLsizei grid_vertex_count_ = 0;
  GroundGrid grid_;

  // Offscreen scene and what it shows.
  int samples_ = 0;
  GLuint scene_fbo_ = 0, scene_color_ = 0, scene_depth_ = 0;
  int scene_width_ = 0, scene_height_ = 0;
  std::uint64_t colors_version_ = 1;
  struct SceneKey {
    glm::dmat4 matrix{0.0};
    std::uint64_t geometry = 0, colors = 0;
    bool smooth = false, wireframe = false, prisms = false, grid = false, proxy = false;
    int width = 0, height = 0;
    bool operator==(const SceneKey& o) const {
      return matrix == o.matrix && geometry == o.geometry && colors == o.colors &&
             smooth == o.smooth && wireframe == o.wireframe && prisms == o.prisms &&
             grid == o.grid && proxy == o.proxy && width == o.width && height == o.height;
    }
  };
  SceneKey drawn_;
  SceneKey scene_key(const DisplaySettings& display, int width, int height);
  std::uint64_t scene_serial_ = 0;  // increases with every scene drawn
  glm::dmat4 last_matrix_{0.0};
  std::chrono::steady_clock::time_point last_motion_;
  bool drew_proxy_ = false, interactive_ = false, in_motion_ = false;

  GLuint pick_fbo_ = 0, pick_id_ = 0, pick_depth_ = 0, pick_z_ = 0;
  int pick_width_ = 0, pick_height_ = 0;
  std::uint64_t geometry_version_ = 1, picked_version_ = 0;
  std::uint64_t hidden_faces_hash_ = 0;  // which faces the colours hide
  glm::dmat4 picked_matrix_{0.0};
};

}  // namespace primo::editor
