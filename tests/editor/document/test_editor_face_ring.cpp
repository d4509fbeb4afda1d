// Edge loops: the ring of quads across an edge on a grid and a cylinder, its stops at
// boundaries and non-quads, and Alt+click selecting it in the editor.

#include <gtest/gtest.h>

#include "document/selection/face_ring.h"
#include "support/editor_harness.h"
#include "primo/mesh/polygon_soup.h"

using namespace primo;
using namespace primo::editor;
using harness::Harness;

TEST(EditorFaceRing, CrossesAGridBetweenItsBoundaries) {
  // 4 x 3 quads, face = row * 4 + column; vertex = row * 5 + column.
  const MeshTopology t = build_topology(make_grid(4, 3, 4, 3, FaceShape::Quads));
  // A vertical edge between columns 1 and 2 in row 1 (vertices 7 and 12): the ring runs along
  // the row.
  EXPECT_EQ(face_ring(t, 7, 12), (std::vector<int>{4, 5, 6, 7}));
  EXPECT_EQ(face_ring(t, 12, 7), (std::vector<int>{4, 5, 6, 7}));  // either direction
  // A horizontal edge between rows 0 and 1 in column 2 (vertices 7 and 8): along the column.
  EXPECT_EQ(face_ring(t, 7, 8), (std::vector<int>{2, 6, 10}));
  // A boundary edge has one face to start from.
  EXPECT_EQ(face_ring(t, 0, 1), (std::vector<int>{0, 4, 8}));
  EXPECT_TRUE(face_ring(t, 0, 6).empty());  // a diagonal is no edge
  EXPECT_TRUE(face_ring(t, 0, 99).empty());
}

TEST(EditorFaceRing, ClosesAroundACylinderAndNeedsQuads) {
  const int segments = 8, bands = 3;
  const MeshTopology t = build_topology(make_cylinder(1.0, 2.0, segments, bands, FaceShape::Quads));
  // The vertical edge at segment 0 of band 1 (vertices 8 and 16): around the cylinder.
  const std::vector<int> around = face_ring(t, segments, 2 * segments);
  ASSERT_EQ(int(around.size()), segments);
  for (int f : around)
    EXPECT_NEAR(t.rest_geometry.centroid[size_t(f)].y(), t.rest_geometry.centroid[size_t(around[0])].y(), 1e-12);
  // A horizontal edge (vertices 8 and 9): along the cylinder, boundary to boundary.
  EXPECT_EQ(int(face_ring(t, segments, segments + 1).size()), bands);

  const MeshTopology tri = build_topology(make_cylinder(1.0, 2.0, segments, bands, FaceShape::Triangles));
  EXPECT_TRUE(face_ring(tri, segments, 2 * segments).empty());

  // A strip quad, quad, triangle: the ring stops before the triangle.
  PolygonSoup soup;
  soup.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0),
                 Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(2, 1, 0)};
  soup.faces = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 6}};
  const MeshTopology strip = build_topology(mesh_from_soup(soup, "strip"));
  EXPECT_EQ(face_ring(strip, 0, 4), (std::vector<int>{0, 1}));
}

TEST(EditorFaceRing, NearestEdgeOfAFaceOnScreen) {
  const MeshTopology t = build_topology(make_grid(1, 1, 1, 1, FaceShape::Quads));
  std::vector<Eigen::Vector2d> screen;
  for (const Vec3& p : t.rest_points) screen.emplace_back(100 * p.x(), 100 * p.y());
  const FaceEdge e = nearest_edge_of_face(t, 0, screen, {95, 40});  // near x = 1
  EXPECT_NEAR(screen[size_t(e.a)].x(), 100, 1e-12);
  EXPECT_NEAR(screen[size_t(e.b)].x(), 100, 1e-12);
}

namespace {

// Alt(+Shift)+click on face f, a third of the way from its centroid to the middle of its
// edge (a, b).
void alt_click_near_edge(Harness& s, int f, int a, int b, int mods) {
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;
  const Vec3 c = t.rest_geometry.centroid[size_t(f)];
  const Vec3 m = 0.5 * (t.rest_points[size_t(a)] + t.rest_points[size_t(b)]);
  const Vec3 q = c + (m - c) / 3.0;
  const glm::dvec3 p = e.camera().project(glm::dvec3(q.x(), q.y(), q.z()));
  s.event(InputEvent::cursor(p.x, p.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, mods | GLFW_MOD_ALT));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, mods | GLFW_MOD_ALT));
}

// The front face (normal +z) whose centroid is nearest (x, y), and its edge running along y
// on its +x side.
int front_face_near(const MeshTopology& t, double x, double y, int& a, int& b) {
  int best = -1;
  for (int f = 0; f < t.n_faces; ++f) {
    if (t.rest_geometry.normal[size_t(f)].z() < 0.9) continue;
    const Vec3 c = t.rest_geometry.centroid[size_t(f)];
    if (best < 0 || std::hypot(c.x() - x, c.y() - y) <
                        std::hypot(t.rest_geometry.centroid[size_t(best)].x() - x,
                                   t.rest_geometry.centroid[size_t(best)].y() - y))
      best = f;
  }
  const double cx = t.rest_geometry.centroid[size_t(best)].x();
  a = b = -1;
  for (int k = t.face_begin[size_t(best)]; k < t.face_begin[size_t(best) + 1]; ++k) {
    const int v = t.face_vertices[size_t(k)];
    if (t.rest_points[size_t(v)].x() > cx) (a < 0 ? a : b) = v;
  }
  return best;
}

}  // namespace

TEST(EditorFaceRing, AltClickSelectsTheRingAndShiftAltAddsOne) {
  Harness s;  // a bar of quads along y, seen from the front (+z)
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;
  int a, b;
  const int f = front_face_near(t, 0.0, 0.45, a, b);
  ASSERT_GE(b, 0);
  alt_click_near_edge(s, f, a, b, 0);
  // The ring around the bar at the clicked face's height: 2 faces on each of 4 sides.
  const std::vector<int> ring = selected_faces(*e.document()->state.selection);
  ASSERT_EQ(ring.size(), 8u);
  for (int g : ring)
    EXPECT_NEAR(t.rest_geometry.centroid[size_t(g)].y(), t.rest_geometry.centroid[size_t(f)].y(), 1e-12);
  const int g = front_face_near(t, 0.0, 0.75, a, b);
  alt_click_near_edge(s, g, a, b, GLFW_MOD_SHIFT);
  EXPECT_EQ(count_selected(*e.document()->state.selection), 16);
  alt_click_near_edge(s, g, a, b, 0);  // without Shift: that ring alone
  EXPECT_EQ(count_selected(*e.document()->state.selection), 8);
  EXPECT_TRUE(e.document()->history.can_undo());

  // An Alt+drag still orbits and leaves the selection alone.
  const glm::dvec3 eye = e.camera().eye();
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, GLFW_MOD_ALT));
  s.event(InputEvent::cursor(500, 300));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, GLFW_MOD_ALT));
  EXPECT_GT(glm::length(e.camera().eye() - eye), 1e-3);
  EXPECT_EQ(count_selected(*e.document()->state.selection), 8);
}

TEST(EditorFaceRing, OnTrianglesTheStatusBarSaysLoopsNeedQuads) {
  Harness s(make_cylinder(0.3, 1.0, 12, 6, FaceShape::Triangles));
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;
  // The face facing the camera nearest the view's centre.
  int f = -1;
  double best = 1e9;
  for (int k = 0; k < t.n_faces; ++k) {
    const Vec3 c = t.rest_geometry.centroid[size_t(k)];
    const glm::dvec3 w(c.x(), c.y(), c.z());
    const Vec3 n = t.rest_geometry.normal[size_t(k)];
    if (glm::dot(glm::dvec3(n.x(), n.y(), n.z()), w - e.camera().eye()) >= 0) continue;
    const glm::dvec3 p = e.camera().project(w);
    const double d = std::hypot(p.x - 400, p.y - 300);
    if (d < best) best = d, f = k;
  }
  ASSERT_GE(f, 0);
  const int v0 = t.face_vertices[size_t(t.face_begin[size_t(f)])];
  const int v1 = t.face_vertices[size_t(t.face_begin[size_t(f)] + 1)];
  alt_click_near_edge(s, f, v0, v1, 0);
  EXPECT_EQ(count_selected(*e.document()->state.selection), 0);
  ASSERT_TRUE(e.current_message());
  EXPECT_NE(e.current_message()->text.find("need quads"), std::string::npos) << e.current_message()->text;
}
