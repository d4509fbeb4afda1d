// Hide and reveal: the mask operations, and a hidden face left out of drawing, picking and
// every way of selecting while it deforms with the mesh.

#include <gtest/gtest.h>

#include "document/selection/face_visibility.h"
#include "document/selection/shown_edges.h"
#include "support/editor_harness.h"
#include "view/face_colors.h"

using namespace primo;
using namespace primo::editor;
using harness::Harness;

namespace {

// A box drag from corner to corner of the viewport with the Select tool.
void box_select_everything(Harness& s, int mods = 0) {
  s.editor.tools.tool = Tool::Select;
  s.editor.tools.shape = SelectShape::Box;
  s.event(InputEvent::cursor(1, 1));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, mods));
  s.event(InputEvent::cursor(799, 599));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, mods));
}

std::vector<int> hidden_faces(const Editor& e) {
  const HiddenFaces& h = e.document()->state.hidden;
  return h ? selected_faces(*h) : std::vector<int>{};
}

}  // namespace

TEST(EditorVisibility, HideRevealAndIsolateMasks) {
  FaceMask hidden(6, 0), selection{1, 1, 0, 0, 0, 0};
  EXPECT_EQ(hide_selected(hidden, selection), 2);
  EXPECT_EQ(hidden, (FaceMask{1, 1, 0, 0, 0, 0}));
  EXPECT_EQ(count_selected(selection), 0);  // hidden faces are never selected
  selection = {0, 0, 0, 1, 0, 0};
  EXPECT_EQ(hide_unselected(hidden, selection), 3);  // 2, 4, 5; 0 and 1 already were
  EXPECT_EQ(hidden, (FaceMask{1, 1, 1, 0, 1, 1}));
  EXPECT_EQ(selection, (FaceMask{0, 0, 0, 1, 0, 0}));
  EXPECT_EQ(reveal_all(hidden, selection), 5);
  EXPECT_EQ(count_selected(hidden), 0);
  EXPECT_EQ(count_selected(selection), 6);  // what came back is selected, with what was

  const HiddenFaces some = std::make_shared<const FaceMask>(FaceMask{0, 1, 0});
  const HiddenFaces none = std::make_shared<const FaceMask>(FaceMask{0, 0, 0});
  EXPECT_TRUE(same_hidden(nullptr, none));
  EXPECT_FALSE(same_hidden(nullptr, some));
  EXPECT_TRUE(is_hidden(some, 1));
  EXPECT_FALSE(is_hidden(some, 7));
  std::vector<int> faces{0, 1, 2};
  drop_hidden(faces, some);
  EXPECT_EQ(faces, (std::vector<int>{0, 2}));
}

TEST(EditorVisibility, HiddenFacesCannotBeSelectedOrPickedAndUndoBringsThemBack) {
  Harness s;
  Editor& e = s.editor;
  const int n = e.document()->n_faces();
  s.select_where(0.5, 2.0);  // the upper half
  const std::vector<int> upper = selected_faces(*e.document()->state.selection);
  ASSERT_GT(upper.size(), 0u);
  s.key(GLFW_KEY_H);
  EXPECT_EQ(hidden_faces(e), upper);
  EXPECT_EQ(count_selected(*e.document()->state.selection), 0);
  ASSERT_TRUE(e.current_message());
  EXPECT_NE(e.current_message()->text.find(std::to_string(upper.size()) + " faces hidden"),
            std::string::npos)
      << e.current_message()->text;
  EXPECT_FALSE(e.has_unsaved_changes());  // hiding is not work to lose

  // Box (with x-ray too), select all, invert and linked: none takes a hidden face.
  box_select_everything(s);
  EXPECT_EQ(count_selected(*e.document()->state.selection), n - int(upper.size()));
  e.tools.xray = true;
  box_select_everything(s);
  e.tools.xray = false;
  for (int f : upper) EXPECT_FALSE((*e.document()->state.selection)[size_t(f)]) << f;
  e.select_all();
  e.invert_selection();
  EXPECT_EQ(count_selected(*e.document()->state.selection), 0);
  e.select_all();
  e.select_linked(false);
  EXPECT_EQ(count_selected(*e.document()->state.selection), n - int(upper.size()));

  // A click on a hidden face picks nothing.
  const Vec3 c = e.document()->topology->rest_geometry.centroid[size_t(upper.back())];
  const glm::dvec3 p = e.camera().project(glm::dvec3(c.x(), c.y(), c.z()));
  e.clear_selection();
  e.tools.shape = SelectShape::Box;
  s.event(InputEvent::cursor(p.x, p.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  EXPECT_EQ(count_selected(*e.document()->state.selection), 0);

  // The overlay tells the shaders which faces to leave out.
  OverlayInputs in;
  in.state = &e.document()->state;
  in.n_faces = n;
  const std::vector<std::uint32_t> colors = face_overlay_colors(in);
  for (int f = 0; f < n; ++f)
    EXPECT_EQ(is_hidden_color(colors[size_t(f)]), is_hidden(e.document()->state.hidden, f)) << f;

  // Undo goes back through the selections to the hide, and before it.
  while (!hidden_faces(e).empty()) e.undo();
  EXPECT_EQ(count_selected(*e.document()->state.selection), int(upper.size()));
  e.redo();
  EXPECT_EQ(hidden_faces(e), upper);

  // Alt+H shows them again, selected; Shift+H isolates the selection.
  s.key(GLFW_KEY_H, GLFW_MOD_ALT);
  EXPECT_TRUE(hidden_faces(e).empty());
  EXPECT_EQ(selected_faces(*e.document()->state.selection), upper);
  s.key(GLFW_KEY_H, GLFW_MOD_SHIFT);
  EXPECT_EQ(int(hidden_faces(e).size()), n - int(upper.size()));
  EXPECT_EQ(selected_faces(*e.document()->state.selection), upper);
}

TEST(EditorVisibility, HiddenFacesDeformWithTheMesh) {
  // The same drag with and without the middle hidden: the same shape.
  std::vector<Vec3> shown, with_hidden, rest;
  for (bool hide : {false, true}) {
    Harness s;
    s.two_handles();
    if (hide) {
      s.select_where(0.3, 0.7);
      s.editor.hide_selected();
      ASSERT_GT(count_hidden(s.editor.document()->state.hidden), 0);
    }
    s.drag("Handle 2", 120, 0);  // after "Fixed 1"
    ASSERT_TRUE(s.settle());
    (hide ? with_hidden : shown) = s.editor.positions();
    rest = s.editor.document()->topology->rest_points;
  }
  ASSERT_EQ(shown.size(), with_hidden.size());
  double moved = 0.0;
  for (size_t v = 0; v < shown.size(); ++v) {
    EXPECT_LT((shown[v] - with_hidden[v]).norm(), 1e-9) << v;
    moved = std::max(moved, (shown[v] - rest[v]).norm());
  }
  EXPECT_GT(moved, 0.05);
}

TEST(EditorVisibility, TheWireframeLeavesOutTheEdgesOfHiddenFacesOnly) {
  // 4 x 3 quads; face = row * 4 + column, vertex = row * 5 + column.
  const MeshTopology t = build_topology(make_grid(4, 3, 4, 3, FaceShape::Quads));
  EXPECT_EQ(shown_edges(t, nullptr), t.edges);
  FaceMask mask(12, 0);
  mask[0] = 1;  // the corner face: its two boundary edges go, the two it shares stay
  const std::vector<unsigned> shown = shown_edges(t, std::make_shared<const FaceMask>(mask));
  EXPECT_EQ(shown.size() + 4, t.edges.size());
  auto has = [&](unsigned a, unsigned b) {
    for (size_t e = 0; e + 1 < shown.size(); e += 2)
      if ((shown[e] == a && shown[e + 1] == b) || (shown[e] == b && shown[e + 1] == a)) return true;
    return false;
  };
  EXPECT_FALSE(has(0, 1));
  EXPECT_FALSE(has(0, 5));
  EXPECT_TRUE(has(1, 6));
  EXPECT_TRUE(has(5, 6));
}
