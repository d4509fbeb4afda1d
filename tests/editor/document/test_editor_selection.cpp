// Editor selection: mask operations on a grid, and which faces a brush, box or lasso takes
// from a pick image and projected centroids.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "document/selection/mesh_topology.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "view/screen_region.h"
#include "document/selection/selection.h"

using namespace primo;
using namespace primo::editor;

namespace {

// 4 x 3 grid of quads; face index = row * 4 + column.
MeshTopology grid() { return build_topology(make_grid(4, 3, 4, 3, FaceShape::Quads)); }

}  // namespace

TEST(EditorSelection, ReplaceAddSubtract) {
  FaceMask m(6, 0);
  apply_selection(m, {1, 2}, SelectOp::Add);
  EXPECT_EQ(selected_faces(m), (std::vector<int>{1, 2}));
  apply_selection(m, {4}, SelectOp::Add);
  EXPECT_EQ(selected_faces(m), (std::vector<int>{1, 2, 4}));
  apply_selection(m, {2, 5}, SelectOp::Subtract);
  EXPECT_EQ(selected_faces(m), (std::vector<int>{1, 4}));
  apply_selection(m, {0}, SelectOp::Replace);
  EXPECT_EQ(selected_faces(m), (std::vector<int>{0}));
  apply_selection(m, {-1, 99}, SelectOp::Add);  // out of range: ignored
  EXPECT_EQ(count_selected(m), 1);
}

TEST(EditorSelection, GrowShrinkInvertClearAll) {
  const MeshTopology t = grid();
  ASSERT_EQ(t.n_faces, 12);
  FaceMask m(12, 0);
  m[5] = 1;  // row 1, column 1
  grow_selection(m, t);
  // Every face sharing a vertex with face 5: rows 0-2, columns 0-2.
  EXPECT_EQ(selected_faces(m), (std::vector<int>{0, 1, 2, 4, 5, 6, 8, 9, 10}));
  shrink_selection(m, t);  // column 2 touches column 3
  EXPECT_EQ(selected_faces(m), (std::vector<int>{0, 1, 4, 5, 8, 9}));
  invert_selection(m);
  EXPECT_EQ(selected_faces(m), (std::vector<int>{2, 3, 6, 7, 10, 11}));
  clear_selection(m);
  EXPECT_EQ(count_selected(m), 0);
  select_all(m);
  EXPECT_EQ(count_selected(m), 12);
}

TEST(EditorSelection, ShapesContainTheirPoints) {
  const ScreenShape c = ScreenShape::circle({10, 10}, 5);
  EXPECT_TRUE(c.contains({13, 13}));
  EXPECT_FALSE(c.contains({14, 14}));
  const ScreenShape b = ScreenShape::box({20, 5}, {10, 15});  // any corner order
  EXPECT_TRUE(b.contains({10, 5}));
  EXPECT_TRUE(b.contains({15, 10}));
  EXPECT_FALSE(b.contains({21, 10}));
  // An L-shaped lasso: the notch is outside.
  const ScreenShape l = ScreenShape::lasso({{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}});
  EXPECT_TRUE(l.contains({2, 8}));
  EXPECT_TRUE(l.contains({8, 2}));
  EXPECT_FALSE(l.contains({8, 8}));
  int x0, y0, x1, y1;
  c.bounds(x0, y0, x1, y1);
  EXPECT_EQ(x0, 5);
  EXPECT_EQ(y1, 16);
}

TEST(EditorSelection, FootprintTakesSeenFacesAndVisibleSmallOnes) {
  // A 4x4 pick image: face 7 on the left half at depth 1, background on the right.
  PickImage image;
  image.width = image.height = 4;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      image.face.push_back(x < 2 ? 7 : -1);
      image.depth.push_back(x < 2 ? 1.0f : std::numeric_limits<float>::infinity());
    }
  std::vector<ProjectedPoint> centroids(10);
  centroids[3] = {1.5, 1.5, 1.0};   // in front of face 7's depth: visible, too small to own a pixel
  centroids[4] = {1.5, 2.5, 5.0};   // behind face 7: hidden
  centroids[5] = {3.5, 3.5, 2.0};   // over the background: visible
  centroids[6] = {30.0, 30.0, 1.0}; // outside the shape
  centroids[8] = {1.0, 1.0, -1.0};  // behind the eye
  const ScreenShape box = ScreenShape::box({0, 0}, {4, 4});
  EXPECT_EQ(faces_in_shape(box, image, centroids, false, 0.1), (std::vector<int>{3, 5, 7}));
  EXPECT_EQ(faces_in_shape(box, image, centroids, true, 0.1), (std::vector<int>{3, 4, 5, 7}));
  // Face 7 is not taken where the shape misses its pixels.
  const ScreenShape right = ScreenShape::box({2.2, 0}, {4, 4});
  EXPECT_EQ(faces_in_shape(right, image, centroids, false, 0.1), (std::vector<int>{5}));
}

TEST(EditorSelection, LinkedFacesStopAtGapsAndSharpEdges) {
  // A closed box-shaped bar: its four long sides meet at 90-degree edges.
  const Mesh bar = make_bar(0.2, 1.0, 2, 6);
  const MeshTopology t = build_topology(bar);
  FaceMask mask(size_t(t.n_faces), 0);
  mask[0] = 1;
  FaceMask by_angle = mask;
  select_linked(by_angle, t, 30.0);
  // Exactly the faces whose normal is the first face's: one flat side (or end cap).
  const Vec3 n0 = t.rest_geometry.normal[0];
  for (int f = 0; f < t.n_faces; ++f)
    EXPECT_EQ(by_angle[f] != 0, t.rest_geometry.normal[f].dot(n0) > 0.999) << "face " << f;
  EXPECT_GT(count_selected(by_angle), 1);
  FaceMask all = mask;
  select_linked(all, t);  // one connected piece: everything
  EXPECT_EQ(count_selected(all), t.n_faces);
  // Two separate pieces: linked stays in the first.
  PolygonSoup soup;
  soup.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(2, 0, 0),
                 Vec3(2, 1, 0), Vec3(5, 0, 0), Vec3(6, 0, 0), Vec3(6, 1, 0)};
  soup.faces = {{0, 1, 2, 3}, {1, 4, 5, 2}, {6, 7, 8}};
  const MeshTopology two = build_topology(mesh_from_soup(soup, "two pieces"));
  FaceMask m(3, 0);
  m[0] = 1;
  select_linked(m, two);
  EXPECT_EQ(m, (FaceMask{1, 1, 0}));
}
