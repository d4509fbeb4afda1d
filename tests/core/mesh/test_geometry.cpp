// Mesh measures (geometry.h) that lengths elsewhere are scaled by or compared with.

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh.h"

using namespace primo;

TEST(LargestPointDistance, IsTheLargestOfTheCorrespondingPointsDistances) {
  const std::vector<Vec3> a = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 0)};
  std::vector<Vec3> b = a;
  EXPECT_EQ(largest_point_distance(a, b), 0.0);
  b[1] += Vec3(0, 3, 4);   // 5 apart
  b[2] += Vec3(0, 0, -2);  // 2 apart
  EXPECT_DOUBLE_EQ(largest_point_distance(a, b), 5.0);
  EXPECT_DOUBLE_EQ(largest_point_distance(b, a), 5.0);
  // Corresponding points, not nearest ones: the same points in another order are apart.
  const std::vector<Vec3> swapped = {a[1], a[0], a[2]};
  EXPECT_DOUBLE_EQ(largest_point_distance(a, swapped), 1.0);
  EXPECT_EQ(largest_point_distance({}, {}), 0.0);
}

TEST(LargestPointDistance, RefusesListsOfDifferentLengths) {
  const std::vector<Vec3> three(3, Vec3::Zero()), two(2, Vec3::Zero());
  EXPECT_THROW(largest_point_distance(three, two), std::invalid_argument);
}

TEST(BoundingBoxDiagonal, CountsOnlyTheVerticesFacesUse) {
  Mesh mesh;
  const auto v0 = mesh.add_vertex(Mesh::Point(0, 0, 0));
  const auto v1 = mesh.add_vertex(Mesh::Point(3, 0, 0));
  const auto v2 = mesh.add_vertex(Mesh::Point(0, 4, 0));
  mesh.add_face(v0, v1, v2);
  EXPECT_DOUBLE_EQ(bounding_box_diagonal(mesh), 5.0);
  mesh.add_vertex(Mesh::Point(1e7, 0, 0));  // isolated: it would make every scaled length tiny
  EXPECT_DOUBLE_EQ(bounding_box_diagonal(mesh), 5.0);
}
