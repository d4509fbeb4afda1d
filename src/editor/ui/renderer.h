#pragma once
// Draws the mesh and reads the pick buffer. Buffers are uploaded only when told: the
// topology once per mesh (fan triangles, polygon edges, triangle -> face), positions and
// normals per solver result, per-face overlay colours when they change, prism corners when
// shown. The pick pass (face id and eye depth per pixel) is rendered on demand, only when
// the geometry or the camera changed since the last one.

#include <cstdint>
#include <string>
#include <vector>

#include "camera.h"
#include "editor.h"
#include "gl.h"
#include "gl_shader.h"
#include "mesh_topology.h"

namespace primo::editor {

class MeshRenderer : public Picker {
 public:
  // Loads the shaders from `shader_folder`; throws primo::Error (path and GL log) on failure.
  explicit MeshRenderer(const std::string& shader_folder);
  ~MeshRenderer() override;
  MeshRenderer(const MeshRenderer&) = delete;
  MeshRenderer& operator=(const MeshRenderer&) = delete;

  // The camera pick passes use (the editor's).
  void set_camera(const Camera* camera) { camera_ = camera; }
  void set_topology(const MeshTopology& topology);
  void set_geometry(const std::vector<float>& positions, const std::vector<float>& normals);
  void set_prism_corners(const std::vector<float>& corners);  // empty: none to show
  void set_face_colors(const std::vector<std::uint32_t>& colors);
  bool has_mesh() const { return triangle_count_ > 0; }

  // Draws background and mesh into the rectangle (GL window coordinates, origin bottom-left)
  // of the current framebuffer.
  void draw(const DisplaySettings& display, int x, int y, int width, int height);

  PickImage read(int x0, int y0, int width, int height) override;

 private:
  void render_pick();

  const Camera* camera_ = nullptr;
  ShaderProgram mesh_, pick_, lines_, background_;
  GLuint vao_ = 0, position_vbo_ = 0, normal_vbo_ = 0, triangle_ebo_ = 0, edge_ebo_ = 0;
  GLuint triangle_face_buffer_ = 0, triangle_face_texture_ = 0;
  GLuint color_buffer_ = 0, color_texture_ = 0;
  GLuint prism_vao_ = 0, prism_vbo_ = 0, prism_ebo_ = 0;
  GLuint empty_vao_ = 0;
  GLsizei triangle_count_ = 0, edge_index_count_ = 0, prism_index_count_ = 0;
  bool prisms_uploaded_ = false;

  GLuint pick_fbo_ = 0, pick_id_ = 0, pick_depth_ = 0, pick_z_ = 0;
  int pick_width_ = 0, pick_height_ = 0;
  std::uint64_t geometry_version_ = 1, picked_version_ = 0;
  glm::dmat4 picked_matrix_{0.0};
};

}  // namespace primo::editor
