// The coarse proxy drawn for big meshes while the camera moves or a gesture is under way.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <thread>
#include <utility>

#include "document/document.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "document/proxy_mesh.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;

namespace {

using DirectedEdges = std::map<std::pair<unsigned, unsigned>, int>;

DirectedEdges directed_edges(const std::vector<unsigned>& triangles) {
  DirectedEdges count;
  for (size_t i = 0; i < triangles.size(); i += 3)
    for (int k = 0; k < 3; ++k) ++count[{triangles[i + k], triangles[i + (k + 1) % 3]}];
  return count;
}

// A proxy of a closed manifold mesh has no holes, fins or flipped triangles: every directed
// edge occurs once and its twin once (the mesh's orientation kept).
void expect_closed_and_oriented(const ProxyTriangles& p) {
  const DirectedEdges count = directed_edges(p.triangles);
  int repeated = 0, open = 0;
  for (const auto& [edge, n] : count) {
    if (n != 1) ++repeated;
    if (!count.count({edge.second, edge.first})) ++open;
  }
  EXPECT_EQ(repeated, 0) << "directed edges used by more than one triangle (fins or flips)";
  EXPECT_EQ(open, 0) << "edges with one side only (holes)";
}

Vec3 triangle_normal(const std::vector<Vec3>& points, const unsigned* t) {
  return (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]);
}

// Each proxy triangle faces the way its source face does, at `points`: no back faces show.
void expect_facing_like_the_mesh(const MeshTopology& t, const ProxyTriangles& p,
                                 const std::vector<Vec3>& points) {
  int against = 0;
  for (size_t i = 0; i < p.triangle_face.size(); ++i) {
    const int f = p.triangle_face[i];
    const Vec3 c = face_centroid(t, points, f);
    const Vec3 source = face_vector_area(t, points, f, c).normalized();
    if (triangle_normal(points, &p.triangles[3 * i]).normalized().dot(source) < 0.0) ++against;
  }
  EXPECT_EQ(against, 0) << "of " << p.triangle_face.size() << " proxy triangles face backwards";
}

// Longest edge over the height on it.
double worst_aspect_ratio(const ProxyTriangles& p, const std::vector<Vec3>& points) {
  double worst = 0.0;
  for (size_t i = 0; i < p.triangle_face.size(); ++i) {
    const unsigned* tri = &p.triangles[3 * i];
    double longest = 0.0;
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (points[tri[(k + 1) % 3]] - points[tri[k]]).norm());
    const double area2 = triangle_normal(points, tri).norm();
    worst = std::max(worst, longest * longest / std::max(area2, 1e-300));
  }
  return worst;
}

void expect_indexes_the_mesh(const MeshTopology& t, const ProxyTriangles& p) {
  ASSERT_EQ(p.triangles.size(), 3 * p.triangle_face.size());
  for (size_t i = 0; i < p.triangle_face.size(); ++i) {
    ASSERT_GE(p.triangle_face[i], 0);
    ASSERT_LT(p.triangle_face[i], t.n_faces);
    const unsigned a = p.triangles[3 * i], b = p.triangles[3 * i + 1], c = p.triangles[3 * i + 2];
    ASSERT_TRUE(a != b && b != c && a != c);
    ASSERT_LT(std::max({a, b, c}), unsigned(t.n_vertices));
  }
}

}  // namespace

TEST(EditorProxy, FitsTheBudgetAndIndexesTheMesh) {
  const MeshTopology t = build_topology(make_cylinder(0.25, 2.0, 120, 200, FaceShape::Quads));
  EXPECT_TRUE(decimate_triangles(t, int(t.triangle_face.size())).empty())
      << "small enough as it is";
  const ProxyTriangles p = decimate_triangles(t, 6000);
  ASSERT_FALSE(p.empty());
  EXPECT_LE(p.triangle_face.size(), 6000u);
  EXPECT_GT(p.triangle_face.size(), 4000u) << "not coarser than needed";
  expect_indexes_the_mesh(t, p);
}

TEST(EditorProxy, ABigMeshIsDecimatedInPartsToTheSameStandInOnAnyNumberOfThreads) {
  // 48,000 triangles: cut into parts that are decimated side by side, then joined and
  // decimated once more, their seams free. The parts depend on the mesh only.
  const MeshTopology t = build_topology(make_cylinder(0.25, 2.0, 160, 150, FaceShape::Quads));
  const ProxyTriangles one = decimate_triangles(t, 8000, nullptr, 1);
  const ProxyTriangles three = decimate_triangles(t, 8000, nullptr, 3);
  EXPECT_EQ(one.triangles, three.triangles);
  EXPECT_EQ(one.triangle_face, three.triangle_face);
  EXPECT_LE(one.triangle_face.size(), 8000u);
  EXPECT_GT(one.triangle_face.size(), 6000u) << "not coarser than needed";
  expect_indexes_the_mesh(t, one);
  expect_facing_like_the_mesh(t, one, t.rest_points);
  EXPECT_LT(worst_aspect_ratio(one, t.rest_points), 40.0) << "needles along the seams";
}

TEST(EditorProxy, APausedBuildWaitsAndThenGivesTheSameStandIn) {
  // The window pauses the build while the solver settles and nothing moves; it starts paused.
  auto t = std::make_shared<const MeshTopology>(
      build_topology(make_cylinder(0.25, 2.0, 160, 150, FaceShape::Quads)));
  const ProxyTriangles direct = decimate_triangles(*t, 8000);
  {
    ProxyBuild paused(t, 8000);
    // Several times what the whole decimation takes unpaused on this mesh.
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    EXPECT_EQ(paused.ready(), nullptr) << "a paused build went on";
  }  // destroyed while paused: cancelled, not waited for
  ProxyBuild build(t, 8000);
  build.set_paused(false);
  const ProxyTriangles& p = build.wait();
  EXPECT_EQ(p.triangles, direct.triangles);
  EXPECT_EQ(p.triangle_face, direct.triangle_face);
  ProxyBuild waited(t, 8000);  // wait() unpauses: a screenshot run must not hang on it
  EXPECT_EQ(waited.wait().triangles, direct.triangles);
}

TEST(EditorProxy, TheStandInWaitsOnlyOnAGpuWhileTheEditorSettlesAndNothingMoves) {
  // Drawn in software, motion needs the stand-in: it is never held back.
  for (const bool settled : {false, true})
    for (const bool moving : {false, true}) EXPECT_FALSE(stand_in_waits(true, settled, moving));
  EXPECT_TRUE(stand_in_waits(false, false, false));
  EXPECT_FALSE(stand_in_waits(false, true, false)) << "settled: the cores are free";
  EXPECT_FALSE(stand_in_waits(false, false, true)) << "in motion: the stand-in is drawn";
}

TEST(EditorProxy, ADocumentHasAStandInAboveTheThresholdItsRendererNeeds) {
  // 64,000 triangles: above what a software renderer draws in motion, far below a GPU's.
  const Mesh mesh = make_cylinder(0.25, 2.0, 160, 200, FaceShape::Triangles);
  const auto in_software = make_document(mesh, "", kStandInAboveInSoftware);
  const auto on_gpu = make_document(mesh, "", kStandInAboveOnGpu);
  const ProxyTriangles& stand_in = in_software->proxy->wait();
  EXPECT_FALSE(stand_in.empty());
  EXPECT_LE(stand_in.triangle_face.size(), 30000u);
  EXPECT_TRUE(on_gpu->proxy->wait().empty()) << "drawn in full on a GPU";
  EXPECT_NE(on_gpu->proxy->ready(), nullptr) << "nothing to wait for";
  EXPECT_EQ(make_document(mesh, "")->proxy->wait().triangles, stand_in.triangles)
      << "the default is the software renderer's";
}

TEST(EditorProxy, ThinPartsStayClosedWithoutHolesOrFins) {
  // A bar 1/40 as wide as it is long, dense enough that any grid coarse enough to reach the
  // budget puts its opposite sides in the same cell: clustering tore it open.
  const MeshTopology t = build_topology(make_bar(0.05, 2.0, 8, 400));
  const ProxyTriangles p = decimate_triangles(t, 3000);
  ASSERT_FALSE(p.empty());
  EXPECT_LE(p.triangle_face.size(), 3000u);
  expect_indexes_the_mesh(t, p);
  expect_closed_and_oriented(p);
  expect_facing_like_the_mesh(t, p, t.rest_points);
}

TEST(EditorProxy, OpenBoundariesAreKeptAndTheProxyFollowsADeformation) {
  const MeshTopology t = build_topology(make_cylinder(0.25, 2.0, 120, 200, FaceShape::Triangles));
  const ProxyTriangles p = decimate_triangles(t, 4000);
  ASSERT_FALSE(p.empty());
  // The proxy's one-sided edges are exactly the tube's two rims.
  const DirectedEdges mesh_edges = directed_edges(t.triangles);
  const DirectedEdges proxy_edges = directed_edges(p.triangles);
  int mesh_rim = 0, proxy_rim = 0, proxy_rim_on_mesh_rim = 0;
  for (const auto& [e, n] : mesh_edges)
    if (!mesh_edges.count({e.second, e.first})) ++mesh_rim;
  for (const auto& [e, n] : proxy_edges) {
    EXPECT_EQ(n, 1);
    if (proxy_edges.count({e.second, e.first})) continue;
    ++proxy_rim;
    if (mesh_edges.count(e) && !mesh_edges.count({e.second, e.first})) ++proxy_rim_on_mesh_rim;
  }
  EXPECT_EQ(proxy_rim, mesh_rim);
  EXPECT_EQ(proxy_rim_on_mesh_rim, mesh_rim);
  EXPECT_LT(worst_aspect_ratio(p, t.rest_points), 40.0) << "needles";

  // Bend the tube by 180 degrees (y along an arc): the proxy, which indexes the mesh's own
  // vertices, still faces the way the mesh does.
  std::vector<Vec3> bent = t.rest_points;
  const double radius = 2.0 / M_PI;
  for (Vec3& q : bent) {
    const double angle = q.y() / radius, r = radius - q.x();
    q = Vec3(radius - r * std::cos(angle), r * std::sin(angle), q.z());
  }
  expect_facing_like_the_mesh(t, p, bent);
}

TEST(EditorProxy, ARealMeshGivesAClosedStandInQuickly) {
  const std::string path = test::shared_path("meshes/koala.obj");
  if (!test::exists(path)) GTEST_SKIP() << "skipped: " << path << " is not present";
  const MeshTopology t = build_topology(load_mesh(path));
  const auto start = std::chrono::steady_clock::now();
  const ProxyTriangles p = decimate_triangles(t, 30000);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("koala: %zu -> %zu proxy triangles in %.2f s\n", t.triangle_face.size(),
              p.triangle_face.size(), seconds);
  EXPECT_LE(p.triangle_face.size(), 30000u);
  EXPECT_GT(p.triangle_face.size(), 25000u);
  expect_closed_and_oriented(p);
  expect_facing_like_the_mesh(t, p, t.rest_points);
}
