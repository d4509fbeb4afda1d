#include "renderer.h"

#include <glm/gtc/type_ptr.hpp>
#include <algorithm>
#include <limits>

#include "view/face_colors.h"

namespace primo::editor {
namespace {

void upload_matrix(GLint location, const glm::dmat4& m) {
  const glm::mat4 f(m);
  glUniformMatrix4fv(location, 1, GL_FALSE, glm::value_ptr(f));
}

constexpr float kBaseColor[3] = {0.74f, 0.72f, 0.69f};

}  // namespace

MeshRenderer::MeshRenderer(const std::string& shader_folder, int samples)
    : mesh_(shader_folder, "mesh.vert", "mesh.frag"),
      pick_(shader_folder, "mesh.vert", "pick.frag"),
      lines_(shader_folder, "lines.vert", "lines.frag"),
      background_(shader_folder, "background.vert", "background.frag"),
      grid_program_(shader_folder, "grid.vert", "grid.frag") {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &position_vbo_);
  glGenBuffers(1, &normal_vbo_);
  glGenBuffers(1, &triangle_ebo_);
  glGenBuffers(1, &edge_ebo_);
  glGenBuffers(1, &point_ebo_);
  glGenBuffers(1, &selected_point_ebo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, position_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, normal_vbo_);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, triangle_ebo_);
  glBindVertexArray(0);

  glGenVertexArrays(1, &prism_vao_);
  glGenBuffers(1, &prism_vbo_);
  glGenBuffers(1, &prism_ebo_);
  glBindVertexArray(prism_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, prism_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, prism_ebo_);
  glBindVertexArray(0);
  glGenVertexArrays(1, &empty_vao_);

  glGenVertexArrays(1, &grid_vao_);
  glGenBuffers(1, &grid_vbo_);
  glBindVertexArray(grid_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, grid_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 4 * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  glBindVertexArray(0);

  glGenBuffers(1, &triangle_face_buffer_);
  glGenTextures(1, &triangle_face_texture_);
  glGenBuffers(1, &color_buffer_);
  glGenTextures(1, &color_texture_);
  glGenBuffers(1, &proxy_ebo_);
  glGenBuffers(1, &proxy_face_buffer_);
  glGenTextures(1, &proxy_face_texture_);
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples_ = std::clamp(samples, 0, int(max_samples));
}

MeshRenderer::~MeshRenderer() {
  const GLuint buffers[] = {position_vbo_, normal_vbo_, triangle_ebo_, edge_ebo_,
                            triangle_face_buffer_, color_buffer_, prism_vbo_, prism_ebo_,
                            proxy_ebo_, proxy_face_buffer_, grid_vbo_, point_ebo_,
                            selected_point_ebo_};
  glDeleteBuffers(GLsizei(std::size(buffers)), buffers);
  const GLuint textures[] = {triangle_face_texture_, color_texture_, pick_id_, pick_depth_,
                             proxy_face_texture_};
  glDeleteTextures(GLsizei(std::size(textures)), textures);
  const GLuint arrays[] = {vao_, prism_vao_, empty_vao_, grid_vao_};
  glDeleteVertexArrays(GLsizei(std::size(arrays)), arrays);
  const GLuint renderbuffers[] = {pick_z_, scene_color_, scene_depth_};
  glDeleteRenderbuffers(GLsizei(std::size(renderbuffers)), renderbuffers);
  const GLuint framebuffers[] = {pick_fbo_, scene_fbo_};
  glDeleteFramebuffers(GLsizei(std::size(framebuffers)), framebuffers);
}

void MeshRenderer::set_proxy(const ProxyTriangles& proxy) {
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, proxy_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(proxy.triangles.size() * sizeof(unsigned)),
               proxy.triangles.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, proxy_face_buffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(proxy.triangle_face.size() * sizeof(int)),
               proxy.triangle_face.data(), GL_STATIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, proxy_face_texture_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_R32I, proxy_face_buffer_);
  proxy_count_ = GLsizei(proxy.triangle_face.size());
}

void MeshRenderer::set_topology(const MeshTopology& t) {
  set_proxy(ProxyTriangles{});
  glBindVertexArray(vao_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, triangle_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(t.triangles.size() * sizeof(unsigned)),
               t.triangles.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, edge_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(t.edges.size() * sizeof(unsigned)),
               t.edges.data(), GL_STATIC_DRAW);
  triangle_count_ = GLsizei(t.triangle_face.size());
  edge_index_count_ = GLsizei(t.edges.size());

  glBindBuffer(GL_TEXTURE_BUFFER, triangle_face_buffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(t.triangle_face.size() * sizeof(int)),
               t.triangle_face.data(), GL_STATIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, triangle_face_texture_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_R32I, triangle_face_buffer_);

  // Prism cages: per corner a bottom (2k) and a top (2k + 1) vertex; bottom ring, top ring,
  // and the vertical edges.
  std::vector<unsigned> lines;
  for (int f = 0; f < t.n_faces; ++f) {
    const int b = t.face_begin[f], n = t.degree(f);
    for (int k = 0; k < n; ++k) {
      const unsigned c = unsigned(b + k), d = unsigned(b + (k + 1) % n);
      lines.insert(lines.end(), {2 * c, 2 * d, 2 * c + 1, 2 * d + 1, 2 * c, 2 * c + 1});
    }
  }
  glBindVertexArray(prism_vao_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, prism_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(lines.size() * sizeof(unsigned)), lines.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  prism_index_count_ = GLsizei(lines.size());
  prisms_uploaded_ = false;
  set_face_colors(std::vector<std::uint32_t>(size_t(t.n_faces), 0u));
  ++geometry_version_;
}

void MeshRenderer::set_geometry(const std::vector<float>& positions, const std::vector<float>& normals) {
  glBindBuffer(GL_ARRAY_BUFFER, position_vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions.size() * sizeof(float)), positions.data(),
               GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, normal_vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(normals.size() * sizeof(float)), normals.data(),
               GL_DYNAMIC_DRAW);
  ++geometry_version_;
}

void MeshRenderer::set_prism_corners(const std::vector<float>& corners) {
  prisms_uploaded_ = !corners.empty();
  ++geometry_version_;  // the scene shows them
  if (!prisms_uploaded_) return;
  glBindBuffer(GL_ARRAY_BUFFER, prism_vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(corners.size() * sizeof(float)), corners.data(),
               GL_DYNAMIC_DRAW);
}

void MeshRenderer::set_face_colors(const std::vector<std::uint32_t>& colors) {
  glBindBuffer(GL_TEXTURE_BUFFER, color_buffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(colors.size() * sizeof(std::uint32_t)),
               colors.data(), GL_DYNAMIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, color_texture_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA8, color_buffer_);
  ++colors_version_;
  // Hiding or revealing faces changes what can be picked: the pick pass is drawn again.
  std::uint64_t hidden = 0;
  for (size_t f = 0; f < colors.size(); ++f)
    if (is_hidden_color(colors[f])) hidden = hidden * 1000003u + f + 1;
  if (hidden != hidden_faces_hash_) picked_version_ = 0;
  hidden_faces_hash_ = hidden;
}

void MeshRenderer::set_edges(const std::vector<unsigned>& edges) {
  glBindVertexArray(0);  // an index buffer bound now must not become a VAO's own
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, edge_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(edges.size() * sizeof(unsigned)), edges.data(),
               GL_STATIC_DRAW);
  edge_index_count_ = GLsizei(edges.size());
  ++colors_version_;  // the scene shows them
}

void MeshRenderer::set_vertex_points(const std::vector<unsigned>& shown,
                                     const std::vector<unsigned>& selected) {
  glBindVertexArray(0);  // an index buffer bound now must not become a VAO's own
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, point_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(shown.size() * sizeof(unsigned)), shown.data(),
               GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, selected_point_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(selected.size() * sizeof(unsigned)),
               selected.data(), GL_DYNAMIC_DRAW);
  point_count_ = GLsizei(shown.size());
  selected_point_count_ = GLsizei(selected.size());
  ++colors_version_;  // the scene shows them
}

void MeshRenderer::set_ground_grid(const GroundGrid& grid) {
  // Per vertex: x, y, z, and 1 on a major line.
  std::vector<float> vertices;
  for (const GridLine& line : grid_lines(grid))
    for (const glm::dvec3& p : {line.a, line.b})
      vertices.insert(vertices.end(), {float(p.x), float(p.y), float(p.z), line.major ? 1.0f : 0.0f});
  glBindBuffer(GL_ARRAY_BUFFER, grid_vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(),
               GL_STATIC_DRAW);
  grid_vertex_count_ = GLsizei(vertices.size() / 4);
  grid_ = grid;
  ++geometry_version_;  // the scene shows it
}

void MeshRenderer::ensure_scene_target(int width, int height) {
  if (scene_fbo_ && width == scene_width_ && height == scene_height_) return;
  if (!scene_fbo_) {
    glGenFramebuffers(1, &scene_fbo_);
    glGenRenderbuffers(1, &scene_color_);
    glGenRenderbuffers(1, &scene_depth_);
  }
  glBindRenderbuffer(GL_RENDERBUFFER, scene_color_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, scene_depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, scene_color_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, scene_depth_);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  scene_width_ = width;
  scene_height_ = height;
  drawn_ = SceneKey{};
}

MeshRenderer::SceneKey MeshRenderer::scene_key(const DisplaySettings& display, int width,
                                               int height) {
  SceneKey key;
  key.matrix = camera_ ? camera_->projection() * camera_->view() : glm::dmat4(1.0);
  // The proxy while the camera moves or a gesture is under way, and for a moment after (so
  // that a frame without motion in the middle of an orbit does not draw the full mesh).
  const auto now = std::chrono::steady_clock::now();
  if (key.matrix != last_matrix_ || interactive_) last_motion_ = now;
  last_matrix_ = key.matrix;
  in_motion_ = now - last_motion_ < std::chrono::milliseconds(300);
  key.proxy = proxy_count_ > 0 && in_motion_;
  key.geometry = geometry_version_;
  key.colors = colors_version_;
  key.smooth = display.smooth;
  key.wireframe = display.wireframe;
  key.prisms = display.prisms;
  key.grid = display.grid;
  key.width = width;
  key.height = height;
  return key;
}

std::uint64_t MeshRenderer::scene_fingerprint(const DisplaySettings& display, int width,
                                              int height) {
  const SceneKey key = scene_key(display, width, height);
  // The scene drawn last is kept: a key equal to it draws the same picture, any other one
  // (even one drawn earlier) a different one.
  if (key == drawn_ && scene_fbo_) return scene_serial_;
  return scene_serial_ + 1;
}

void MeshRenderer::draw(const DisplaySettings& display, int x, int y, int width, int height) {
  if (width <= 0 || height <= 0) return;
  ensure_scene_target(width, height);
  const SceneKey key = scene_key(display, width, height);
  if (!(key == drawn_)) {
    ++scene_serial_;
    glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
    render_scene(display, width, height, key.proxy);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    drawn_ = key;
  }
  drew_proxy_ = key.proxy;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, scene_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, width, height, x, y, x + width, y + height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void MeshRenderer::render_scene(const DisplaySettings& display, int width, int height, bool proxy) {
  glViewport(0, 0, width, height);
  glClear(GL_DEPTH_BUFFER_BIT);

  // 1. Background gradient.
  glDisable(GL_DEPTH_TEST);
  background_.use();
  glUniform3f(background_.uniform("top_color"), 0.235f, 0.245f, 0.27f);
  glUniform3f(background_.uniform("bottom_color"), 0.105f, 0.11f, 0.12f);
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (!has_mesh() || !camera_) return;

  // 2. Surface, pushed back a little so that lines on it win the depth test.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  mesh_.use();
  upload_matrix(mesh_.uniform("view"), camera_->view());
  upload_matrix(mesh_.uniform("projection"), camera_->projection());
  glUniform1i(mesh_.uniform("smooth_shading"), display.smooth ? 1 : 0);
  glUniform3fv(mesh_.uniform("base_color"), 1, kBaseColor);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, proxy ? proxy_face_texture_ : triangle_face_texture_);
  glUniform1i(mesh_.uniform("triangle_face"), 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, color_texture_);
  glUniform1i(mesh_.uniform("face_color"), 1);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(vao_);
  if (proxy) {
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, proxy_ebo_);
    glDrawElements(GL_TRIANGLES, 3 * proxy_count_, GL_UNSIGNED_INT, nullptr);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, triangle_ebo_);  // the VAO's own index buffer
  } else {
    glDrawElements(GL_TRIANGLES, 3 * triangle_count_, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);

  // 3. The ground grid, where the mesh does not hide it.
  if (display.grid && grid_vertex_count_ > 0) render_grid();

  // 4. Lines: polygon edges and prism cages, blended, not writing depth (not over a proxy).
  if (!proxy && (display.wireframe || (display.prisms && prisms_uploaded_))) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    lines_.use();
    upload_matrix(lines_.uniform("view"), camera_->view());
    upload_matrix(lines_.uniform("projection"), camera_->projection());
    if (display.wireframe) {
      glUniform4f(lines_.uniform("color"), 0.06f, 0.07f, 0.09f, 0.55f);
      glBindVertexArray(vao_);
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, edge_ebo_);
      glDrawElements(GL_LINES, edge_index_count_, GL_UNSIGNED_INT, nullptr);
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, triangle_ebo_);  // the VAO's own index buffer
    }
    if (display.prisms && prisms_uploaded_) {
      glUniform4f(lines_.uniform("color"), 0.35f, 0.75f, 1.0f, 0.35f);
      glBindVertexArray(prism_vao_);
      glDrawElements(GL_LINES, prism_index_count_, GL_UNSIGNED_INT, nullptr);
    }
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }

  // 5. Vertex mode: the vertices as points on the surface, the selected ones larger.
  if (!proxy && point_count_ + selected_point_count_ > 0) {
    lines_.use();
    upload_matrix(lines_.uniform("view"), camera_->view());
    upload_matrix(lines_.uniform("projection"), camera_->projection());
    glBindVertexArray(vao_);
    glPointSize(3.0f);
    glUniform4f(lines_.uniform("color"), 0.05f, 0.05f, 0.06f, 1.0f);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, point_ebo_);
    glDrawElements(GL_POINTS, point_count_, GL_UNSIGNED_INT, nullptr);
    glPointSize(7.0f);
    glUniform4f(lines_.uniform("color"), 1.0f, 0.6f, 0.11f, 1.0f);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, selected_point_ebo_);
    glDrawElements(GL_POINTS, selected_point_count_, GL_UNSIGNED_INT, nullptr);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, triangle_ebo_);  // the VAO's own index buffer
    glPointSize(1.0f);
  }
  glBindVertexArray(0);
  glDisable(GL_DEPTH_TEST);
}

void MeshRenderer::render_grid() {
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);  // a line of the floor never hides anything
  grid_program_.use();
  upload_matrix(grid_program_.uniform("view"), camera_->view());
  upload_matrix(grid_program_.uniform("projection"), camera_->projection());
  const glm::vec3 center(grid_.center), normal(grid_.normal), eye(camera_->eye()),
      forward(camera_->forward());
  glUniform3fv(grid_program_.uniform("center"), 1, glm::value_ptr(center));
  glUniform3fv(grid_program_.uniform("normal"), 1, glm::value_ptr(normal));
  glUniform1f(grid_program_.uniform("radius"), float(grid_.half_size()));
  glUniform3fv(grid_program_.uniform("eye"), 1, glm::value_ptr(eye));
  glUniform3fv(grid_program_.uniform("view_direction"), 1, glm::value_ptr(forward));
  glUniform1i(grid_program_.uniform("orthographic"), camera_->orthographic() ? 1 : 0);
  // Light lines on the dark background, faint enough not to compete with the model.
  glUniform4f(grid_program_.uniform("minor_color"), 0.62f, 0.65f, 0.70f, 0.16f);
  glUniform4f(grid_program_.uniform("major_color"), 0.70f, 0.73f, 0.78f, 0.34f);
  glBindVertexArray(grid_vao_);
  glDrawArrays(GL_LINES, 0, grid_vertex_count_);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

void MeshRenderer::render_pick() {
  const int w = camera_->width(), h = camera_->height();
  if (!pick_fbo_ || w != pick_width_ || h != pick_height_) {
    if (!pick_fbo_) {
      glGenFramebuffers(1, &pick_fbo_);
      glGenTextures(1, &pick_id_);
      glGenTextures(1, &pick_depth_);
      glGenRenderbuffers(1, &pick_z_);
    }
    glBindTexture(GL_TEXTURE_2D, pick_id_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32I, w, h, 0, GL_RED_INTEGER, GL_INT, nullptr);
    glBindTexture(GL_TEXTURE_2D, pick_depth_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, w, h, 0, GL_RED, GL_FLOAT, nullptr);
    glBindRenderbuffer(GL_RENDERBUFFER, pick_z_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, pick_fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, pick_id_, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, pick_depth_, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, pick_z_);
    pick_width_ = w;
    pick_height_ = h;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, pick_fbo_);
  const GLenum attachments[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, attachments);
  glViewport(0, 0, w, h);
  const GLint no_face[4] = {-1, 0, 0, 0};
  const GLfloat far_away[4] = {std::numeric_limits<float>::infinity(), 0, 0, 0};
  glClearBufferiv(GL_COLOR, 0, no_face);
  glClearBufferfv(GL_COLOR, 1, far_away);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // The mesh alone: the ground grid and the overlays are never picked.
  pick_.use();
  upload_matrix(pick_.uniform("view"), camera_->view());
  upload_matrix(pick_.uniform("projection"), camera_->projection());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, triangle_face_texture_);
  glUniform1i(pick_.uniform("triangle_face"), 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, color_texture_);
  glUniform1i(pick_.uniform("face_color"), 1);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, 3 * triangle_count_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  picked_version_ = geometry_version_;
  picked_matrix_ = camera_->projection() * camera_->view();
}

bool MeshRenderer::pick_current() const {
  return picked_version_ == geometry_version_ && camera_->width() == pick_width_ &&
         camera_->height() == pick_height_ &&
         picked_matrix_ == camera_->projection() * camera_->view();
}

bool MeshRenderer::cheap_to_read() const {
  return proxy_count_ == 0 || (camera_ && pick_current());
}

PickImage MeshRenderer::read(int x0, int y0, int width, int height) {
  PickImage image;
  image.x0 = x0, image.y0 = y0;
  if (!camera_ || !has_mesh()) return image;
  const int w = camera_->width(), h = camera_->height();
  // Clip the request to the viewport.
  const int x1 = std::min(x0 + width, w), y1 = std::min(y0 + height, h);
  image.x0 = x0 = std::max(x0, 0);
  image.y0 = y0 = std::max(y0, 0);
  if (x1 <= x0 || y1 <= y0) return image;
  image.width = x1 - x0;
  image.height = y1 - y0;
  if (!pick_current()) render_pick();

  const size_t n = size_t(image.width) * image.height;
  std::vector<int> ids(n);
  std::vector<float> depth(n);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, pick_fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  const int gl_y = h - y1;  // GL rows start at the bottom
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(x0, gl_y, image.width, image.height, GL_RED_INTEGER, GL_INT, ids.data());
  glReadBuffer(GL_COLOR_ATTACHMENT1);
  glReadPixels(x0, gl_y, image.width, image.height, GL_RED, GL_FLOAT, depth.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  image.face.resize(n);
  image.depth.resize(n);
  for (int row = 0; row < image.height; ++row) {  // flip to rows from the top
    const size_t src = size_t(image.height - 1 - row) * image.width;
    std::copy_n(ids.begin() + src, image.width, image.face.begin() + size_t(row) * image.width);
    std::copy_n(depth.begin() + src, image.width, image.depth.begin() + size_t(row) * image.width);
  }
  return image;
}

}  // namespace primo::editor
