#pragma once
// The editor driven like a user, without a window, for the editor's tests: input events,
// settling the solver thread, and a stand-in picker that finds the face under the cursor from
// projected centroids.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <thread>

#include "editor.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/mesh_generators.h"

namespace primo::editor::harness {

// The front-facing face whose centroid projects nearest the pixel (within 12 pixels).
class CentroidPicker : public Picker {
 public:
  explicit CentroidPicker(const Editor& e) : e_(e) {}
  PickImage read(int x0, int y0, int w, int h) override {
    PickImage img;
    img.x0 = x0, img.y0 = y0, img.width = w, img.height = h;
    img.face.assign(size_t(w) * h, -1);
    img.depth.assign(size_t(w) * h, std::numeric_limits<float>::infinity());
    if (w != 1 || h != 1) return img;
    const MeshTopology& t = *e_.document()->topology;
    const std::vector<Vec3> c = face_centroids(t, e_.positions());
    double best = 12.0;
    for (int f = 0; f < t.n_faces; ++f) {
      const glm::dvec3 p(c[f].x(), c[f].y(), c[f].z());
      const glm::dvec3 n(t.rest_geometry.normal[f].x(), t.rest_geometry.normal[f].y(),
                         t.rest_geometry.normal[f].z());
      if (glm::dot(n, p - e_.camera().eye()) >= 0) continue;
      const glm::dvec3 s = e_.camera().project(p);
      const double d = glm::length(glm::dvec2(s.x - x0, s.y - y0));
      if (d < best) {
        best = d;
        img.face[0] = f;
        img.depth[0] = float(glm::dot(p - e_.camera().eye(), e_.camera().forward()));
      }
    }
    return img;
  }

 private:
  const Editor& e_;
};

// The faces whose rest centroid's y lies in [y_min, y_max].
inline std::vector<int> faces_where(const MeshTopology& t, double y_min, double y_max) {
  std::vector<int> faces;
  for (int f = 0; f < t.n_faces; ++f) {
    const double y = t.rest_geometry.centroid[size_t(f)].y();
    if (y >= y_min && y <= y_max) faces.push_back(f);
  }
  return faces;
}

// Updates `editor` until its solver has settled and no file task runs; false after 30 s.
inline bool settle(Editor& editor) {
  for (int i = 0; i < 6000; ++i) {
    editor.update(0.016);
    if (editor.settled() && !editor.file_task_running()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// Opens a tube (radius 0.25, 2 long, 12 x 20 quads, written to `dir`) with its base a fixed
// region and its top a handle, as one undo step; returns the top handle's index.
inline int open_tube_with_fixed_base(Editor& editor, const std::string& dir) {
  save_mesh(make_cylinder(0.25, 2.0, 12, 20, FaceShape::Quads), dir + "/tube.obj");
  editor.adopt(load_document(dir + "/tube.obj"));
  Document& doc = *editor.document();
  const MeshTopology& t = *doc.topology;
  add_handle(doc.state, t, t.rest_points, faces_where(t, 0.0, 0.1), HandleMode::Fixed);
  const int top = add_handle(doc.state, t, t.rest_points, faces_where(t, 1.9, 2.0), HandleMode::Pose);
  editor.commit("handles");
  return top;
}

struct Harness {
  Editor editor;
  CentroidPicker picker{editor};
  // A 0.2 x 1 x 0.2 bar of quads along y, unless given another mesh.
  explicit Harness(std::optional<Mesh> mesh = std::nullopt) {
    editor.set_viewport({0, 0, 800, 600, 1.0});
    editor.set_picker(&picker);
    editor.adopt(make_document(mesh ? std::move(*mesh) : make_bar(0.2, 1.0, 2, 10), ""));
  }
  void event(const InputEvent& e) {
    editor.handle_event(e, false, false);
    editor.update(0.016);
  }
  void key(int k, int mods = 0) {
    event(InputEvent::key_event(k, GLFW_PRESS, mods));
    event(InputEvent::key_event(k, GLFW_RELEASE, mods));
  }
  void select_where(double y_min, double y_max) {
    Document& d = *editor.document();
    FaceMask m(d.n_faces(), 0);
    for (int f = 0; f < d.n_faces(); ++f) {
      const double y = d.topology->rest_geometry.centroid[f].y();
      m[f] = y >= y_min && y <= y_max;
    }
    d.state.selection = std::make_shared<const FaceMask>(m);
    editor.commit("Select");
  }
  bool settle() {
    for (int i = 0; i < 6000; ++i) {
      editor.update(0.016);
      if (editor.settled()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
  // Fixed bottom, posed top.
  void two_handles() {
    select_where(-1, 0.06);
    editor.make_handle(HandleMode::Fixed);
    select_where(0.94, 2);
    editor.make_handle(HandleMode::Pose);
  }
  void drag(const std::string& handle, double dx, double dy, int steps = 8) {
    double x, y;
    ASSERT_TRUE(editor.handle_window_position(handle, x, y));
    event(InputEvent::cursor(x, y));
    event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
    for (int k = 1; k <= steps; ++k) event(InputEvent::cursor(x + dx * k / steps, y + dy * k / steps));
    event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  }
  // With the rotate gizmo shown: a quarter turn on screen round the outer (view) ring, from
  // 45 degrees (away from the axis rings), holding Ctrl to snap.
  void quarter_turn_of_the_view_ring() {
    GizmoKind kind;
    glm::dvec3 center;
    ASSERT_TRUE(editor.gizmo_visible(kind, center));
    const Camera& cam = editor.camera();
    const std::vector<glm::dvec2> ring = gizmo_ring(cam, center, GizmoPart::View);
    const glm::dvec3 c = cam.project(center);
    const glm::dvec2 start = ring[ring.size() / 8];
    const glm::dvec2 r = start - glm::dvec2(c.x, c.y);
    const glm::dvec2 end = glm::dvec2(c.x, c.y) + glm::dvec2(-r.y, r.x);
    ASSERT_EQ(gizmo_hit(GizmoKind::Rotate, cam, center, start), GizmoPart::View);
    event(InputEvent::cursor(start.x, start.y));
    event(InputEvent::key_event(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS, 0));
    event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, GLFW_MOD_CONTROL));
    event(InputEvent::cursor(end.x, end.y));
    event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, GLFW_MOD_CONTROL));
    event(InputEvent::key_event(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE, GLFW_MOD_CONTROL));
  }
  double diagonal() const { return editor.document()->topology->bbox_diagonal; }
};


}  // namespace primo::editor::harness
