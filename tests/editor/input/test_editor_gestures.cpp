// Commands while the mouse is still down: a drag holds its handle by index, so a command that
// removes or renumbers handles (Delete, undo, redo, opening a file) must end or cancel the
// drag; the drag must never go on with another handle, least of all a fixed region.

#include <gtest/gtest.h>

#include "support/editor_harness.h"
#include "primo/io/mesh_io.h"
#include "document/scenario_bridge.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;
using primo::editor::harness::Harness;

namespace {

// Spot's control mesh with a handle on the head (made first: "Handle 1") and its legs a fixed
// region ("Fixed 2"), settled at rest.
struct PosedSpot {
  Harness s{load_mesh(primo::test::source_path("assets/meshes/spot_control_mesh.obj"))};
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;

  PosedSpot() {
    select([](const Vec3& c) { return (c - Vec3(0.0, 0.55, -0.45)).norm() < 0.3; });
    e.make_handle(HandleMode::Pose);
    select([](const Vec3& c) { return c.y() < -0.55; });
    e.make_handle(HandleMode::Fixed);
  }
  template <class Take>
  void select(Take take) {
    FaceMask m(size_t(t.n_faces), 0);
    for (int f = 0; f < t.n_faces; ++f) m[size_t(f)] = take(t.rest_geometry.centroid[size_t(f)]);
    e.document()->state.selection = std::make_shared<const FaceMask>(m);
    e.commit("Select");
  }
  // Presses on the head and moves the mouse halfway.
  void start_dragging_the_head(double& x, double& y) {
    ASSERT_TRUE(e.handle_window_position("Handle 1", x, y));
    s.event(InputEvent::cursor(x, y));
    s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
    for (int k = 1; k <= 4; ++k) s.event(InputEvent::cursor(x + 15 * k, y - 10 * k));
    ASSERT_EQ(e.gesture(), Editor::Gesture::DragHandle);
  }
  // The rest of the drag, with the button still down, then the release.
  void go_on_and_release(double x, double y) {
    for (int k = 5; k <= 8; ++k) s.event(InputEvent::cursor(x + 15 * k, y - 10 * k));
    s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  }
  const HandleGroup* handle(const std::string& name) const {
    for (const HandleGroup& g : e.document()->state.handles)
      if (g.name == name) return &g;
    return nullptr;
  }
  // The largest distance of a fixed-region vertex from its rest position, once settled.
  double fixed_region_moved() {
    EXPECT_TRUE(s.settle());
    const HandleGroup* fixed = handle("Fixed 2");
    EXPECT_NE(fixed, nullptr);
    if (!fixed) return 0.0;
    EXPECT_TRUE(fixed->pose.is_identity()) << "the fixed region has a pose";
    double moved = 0.0;
    for (const int f : *fixed->faces)
      for (int k = t.face_begin[f]; k < t.face_begin[f + 1]; ++k) {
        const int v = t.face_vertices[size_t(k)];
        moved = std::max(moved, (e.positions()[size_t(v)] - t.rest_points[size_t(v)]).norm());
      }
    return moved;
  }
};

}  // namespace

TEST(EditorGestures, DeleteDuringADragEndsItAndTheFixedRegionStays) {
  PosedSpot spot;
  ASSERT_TRUE(spot.s.settle());
  double x, y;
  spot.start_dragging_the_head(x, y);
  spot.s.key(GLFW_KEY_DELETE);  // the active handle: the head, being dragged
  EXPECT_EQ(spot.e.gesture(), Editor::Gesture::None) << "the drag ended";
  spot.go_on_and_release(x, y);
  ASSERT_EQ(spot.e.document()->state.handles.size(), 1u);
  EXPECT_EQ(spot.e.document()->state.handles[0].mode, HandleMode::Fixed);
  EXPECT_LT(spot.fixed_region_moved(), 1e-9 * spot.s.diagonal());
  // The drag so far is a step of its own, then the deletion.
  const UndoStack& history = spot.e.document()->history;
  EXPECT_EQ(history.label(history.position()), "Delete 'Handle 1'");
  EXPECT_EQ(history.label(history.position() - 1), "Drag 'Handle 1'");
  // Saved, the fixed region has no transform.
  const Scenario saved = export_scenario(spot.e.document()->state, "spot.obj", "", SolverSpec{});
  ASSERT_EQ(saved.handles.size(), 1u);
  EXPECT_EQ(saved.handles[0].transform.translate, Vec3::Zero());
  EXPECT_EQ(saved.handles[0].transform.angle_deg, 0.0);
}

TEST(EditorGestures, UndoRedoAndOpenDuringADragCancelIt) {
  {  // Undo during the drag: the drag is cancelled, then the step before it is undone.
    PosedSpot spot;
    double x, y;
    spot.start_dragging_the_head(x, y);
    spot.s.key(GLFW_KEY_Z, GLFW_MOD_CONTROL);
    EXPECT_EQ(spot.e.gesture(), Editor::Gesture::None);
    spot.go_on_and_release(x, y);
    EXPECT_EQ(spot.handle("Fixed 2"), nullptr) << "the fixed region's making was undone";
    ASSERT_NE(spot.handle("Handle 1"), nullptr);
    EXPECT_TRUE(spot.handle("Handle 1")->pose.is_identity()) << "the drag was cancelled";
  }
  {  // Redo during the drag (of a deletion of the head, undone): the head goes again.
    PosedSpot spot;
    spot.e.delete_handle(0);
    spot.e.undo();
    double x, y;
    spot.start_dragging_the_head(x, y);
    spot.s.key(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT);
    EXPECT_EQ(spot.e.gesture(), Editor::Gesture::None);
    spot.go_on_and_release(x, y);
    ASSERT_EQ(spot.e.document()->state.handles.size(), 1u);
    EXPECT_LT(spot.fixed_region_moved(), 1e-9 * spot.s.diagonal());
  }
  {  // A file opened during the drag: the drag ends with the old document.
    PosedSpot spot;
    double x, y;
    spot.start_dragging_the_head(x, y);
    spot.e.adopt(make_document(make_bar(0.2, 1.0, 2, 10), "bar.obj"));
    EXPECT_EQ(spot.e.gesture(), Editor::Gesture::None);
    spot.go_on_and_release(x, y);
    EXPECT_TRUE(spot.e.document()->state.handles.empty());
  }
}

TEST(EditorGestures, DeleteDuringADragOfTheShippedScenarioLeavesTheOthersAlone) {
  // feet (fixed), head (position only), tail lift (a spring): deleting the head renumbers the
  // spring into the head's place.
  Harness s;
  s.editor.adopt(load_document(primo::test::source_path("assets/scenarios/spot-pose.json")));
  Editor& e = s.editor;
  ASSERT_TRUE(s.settle());
  const EditState before = e.document()->state;
  ASSERT_EQ(before.handles.size(), 3u);
  double x, y;
  ASSERT_TRUE(e.handle_window_position("head", x, y));
  s.event(InputEvent::cursor(x, y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  for (int k = 1; k <= 4; ++k) s.event(InputEvent::cursor(x + 15 * k, y - 10 * k));
  ASSERT_EQ(e.gesture(), Editor::Gesture::DragHandle);
  e.set_active_handle(1);
  s.key(GLFW_KEY_DELETE);
  for (int k = 5; k <= 8; ++k) s.event(InputEvent::cursor(x + 15 * k, y - 10 * k));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const auto& handles = e.document()->state.handles;
  ASSERT_EQ(handles.size(), 2u);
  EXPECT_EQ(handles[0].name, "feet");
  EXPECT_TRUE(handles[0].pose == before.handles[0].pose);
  EXPECT_EQ(handles[1].name, "tail lift");
  EXPECT_TRUE(handles[1].pose == before.handles[2].pose) << "the spring's pull is as it was";
}
