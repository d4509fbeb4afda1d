// The coarse proxy drawn for big meshes while the camera moves.

#include <gtest/gtest.h>

#include "primo/mesh_generators.h"
#include "proxy_mesh.h"

using namespace primo;
using namespace primo::editor;

TEST(EditorProxy, FitsTheBudgetAndIndexesTheMesh) {
  const MeshTopology t = build_topology(make_cylinder(0.25, 2.0, 120, 200, FaceShape::Quads));
  EXPECT_TRUE(cluster_triangles(t, int(t.triangle_face.size())).empty()) << "small enough as it is";
  const ProxyTriangles p = cluster_triangles(t, 6000);
  ASSERT_FALSE(p.empty());
  EXPECT_LE(p.triangle_face.size(), 6000u);
  EXPECT_GT(p.triangle_face.size(), 1500u) << "not coarser than needed";
  ASSERT_EQ(p.triangles.size(), 3 * p.triangle_face.size());
  for (size_t i = 0; i < p.triangle_face.size(); ++i) {
    EXPECT_GE(p.triangle_face[i], 0);
    EXPECT_LT(p.triangle_face[i], t.n_faces);
    const unsigned a = p.triangles[3 * i], b = p.triangles[3 * i + 1], c = p.triangles[3 * i + 2];
    EXPECT_TRUE(a != b && b != c && a != c);
    EXPECT_LT(std::max({a, b, c}), unsigned(t.n_vertices));
  }
}
