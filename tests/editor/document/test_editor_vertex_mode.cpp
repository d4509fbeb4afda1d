// Vertex mode: converting between vertices and faces, picking vertices with a box and a click,
// and a handle made from vertices taking every face that touches one.

#include <gtest/gtest.h>

#include "document/selection/vertex_selection.h"
#include "support/editor_harness.h"

using namespace primo;
using namespace primo::editor;
using harness::Harness;

namespace {

// 4 x 3 quads; face = row * 4 + column, vertex = row * 5 + column.
MeshTopology grid() { return build_topology(make_grid(4, 3, 4, 3, FaceShape::Quads)); }

// The model's front view, orthographic: a vertex behind another projects onto it.
void front_view(Editor& e) {
  CameraPose pose = e.camera().pose();
  pose.yaw = pose.pitch = 0.0;
  e.camera().set_pose(pose);
  e.camera().set_orthographic(true);
}

std::vector<int> selected_vertex_list(const Editor& e) {
  const auto& v = e.document()->state.vertex_selection;
  return v ? selected_faces(*v) : std::vector<int>{};
}

}  // namespace

TEST(EditorVertexMode, ConvertsBetweenVerticesAndFaces) {
  const MeshTopology t = grid();
  FaceMask faces(12, 0);
  faces[5] = faces[6] = 1;  // row 1, columns 1 and 2
  const VertexMask corners = vertices_of_faces(t, faces);
  EXPECT_EQ(selected_faces(corners), (std::vector<int>{6, 7, 8, 11, 12, 13}));
  EXPECT_EQ(faces_within_vertices(t, corners), faces);  // face -> vertex -> face
  VertexMask one(size_t(t.n_vertices), 0);
  one[12] = 1;  // row 2, column 2: the corner of faces 5, 6, 9, 10
  EXPECT_EQ(selected_faces(faces_touching_vertices(t, one)), (std::vector<int>{5, 6, 9, 10}));
  EXPECT_EQ(count_selected(faces_within_vertices(t, one)), 0);
  EXPECT_EQ(selected_faces(corners_of(t, {0})), (std::vector<int>{0, 1, 5, 6}));

  // Points to draw: the corners of shown faces only.
  const HiddenFaces hidden = std::make_shared<const FaceMask>(FaceMask{1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  const std::vector<unsigned> shown = shown_vertices(t, hidden);
  EXPECT_EQ(shown.size(), size_t(t.n_vertices - 1));  // vertex 0 belongs to face 0 alone
  VertexMask both(size_t(t.n_vertices), 0);
  both[0] = both[1] = 1;
  EXPECT_EQ(selected_vertices(both, hidden, t), (std::vector<unsigned>{1}));
}

TEST(EditorVertexMode, BoxPicksVerticesAndAHandleTakesTheFacesAroundThem) {
  Harness s;  // the bar along y, seen from the front
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;
  s.select_where(0.9, 2.0);  // the top: its faces' corners become the vertex selection
  s.key(GLFW_KEY_1);
  ASSERT_EQ(e.selection_mode(), SelectionMode::Vertices);
  const VertexMask corners = vertices_of_faces(t, *e.document()->state.selection);
  EXPECT_EQ(*e.document()->state.vertex_selection, corners);

  // A box around the vertices at y = 0.5 only (between the face rows' centroids).
  front_view(e);
  e.tools.tool = Tool::Select;
  e.tools.shape = SelectShape::Box;
  const glm::dvec3 lo = e.camera().project(glm::dvec3(-0.2, 0.47, 0.1));
  const glm::dvec3 hi = e.camera().project(glm::dvec3(0.2, 0.53, 0.1));
  s.event(InputEvent::cursor(lo.x, lo.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::cursor(hi.x, hi.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const std::vector<int> picked = selected_vertex_list(e);
  ASSERT_FALSE(picked.empty());
  for (int v : picked) EXPECT_NEAR(t.rest_points[size_t(v)].y(), 0.5, 1e-9) << v;
  // No face has all its corners on one line: none is selected as a face.
  EXPECT_EQ(count_selected(*e.document()->state.selection), 0);

  // The handle takes every face touching a picked vertex: the rows above and below.
  e.make_handle(HandleMode::Pose);
  ASSERT_EQ(e.document()->state.handles.size(), 1u);
  VertexMask mask(size_t(t.n_vertices), 0);
  for (int v : picked) mask[size_t(v)] = 1;
  EXPECT_EQ(*e.document()->state.handles[0].faces, selected_faces(faces_touching_vertices(t, mask)));
  EXPECT_EQ(count_selected(*e.document()->state.vertex_selection), 0);  // used up, as faces are
}

TEST(EditorVertexMode, ClickPicksTheNearestCornerAndFaceModeKeepsWholeFaces) {
  Harness s;
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;
  s.key(GLFW_KEY_1);
  front_view(e);
  e.tools.tool = Tool::Select;
  e.tools.shape = SelectShape::Box;
  // On the front face centred at (0.05, 0.55, 0.1), a fifth of the way to its corner
  // (0.1, 0.5, 0.1).
  const glm::dvec3 p = e.camera().project(glm::dvec3(0.06, 0.54, 0.1));
  s.event(InputEvent::cursor(p.x, p.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const std::vector<int> picked = selected_vertex_list(e);
  ASSERT_EQ(picked.size(), 1u);
  EXPECT_LT((t.rest_points[size_t(picked[0])] - Vec3(0.1, 0.5, 0.1)).norm(), 1e-9);

  // Select all in vertex mode, then face mode: every face stays selected.
  s.key(GLFW_KEY_A);
  EXPECT_EQ(count_selected(*e.document()->state.vertex_selection), t.n_vertices);
  s.key(GLFW_KEY_3);
  EXPECT_EQ(e.selection_mode(), SelectionMode::Faces);
  EXPECT_EQ(count_selected(*e.document()->state.selection), t.n_faces);
  // Undo goes back into vertex mode with its selection.
  e.undo();
  EXPECT_EQ(e.selection_mode(), SelectionMode::Vertices);
  EXPECT_EQ(count_selected(*e.document()->state.vertex_selection), t.n_vertices);
  EXPECT_FALSE(e.has_unsaved_changes());
}
