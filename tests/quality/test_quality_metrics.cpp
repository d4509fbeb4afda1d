// Quality metrics (src/quality): analytic cases whose every figure is known in closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "quality/cgal_deformation.h"
#include "quality/mesh_quality.h"
#include "quality/self_intersections.h"
#include "support/test_support.h"

namespace primo::quality {
namespace {

Mesh scaled(const Mesh& mesh, double s) {
  Mesh m = mesh;
  for (auto v : m.vertices()) m.point(v) *= s;
  return m;
}

Mesh soup_mesh(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& faces) {
  PolygonSoup soup;
  soup.points = points;
  soup.faces = faces;
  return mesh_from_soup(soup, "test mesh");
}

TEST(QualityMetrics, OpenCylinderVolumeIsThePrismOfItsCappedPolygon) {
  // The caps fan to the ring centres, so the capped open cylinder is exactly a prism over the
  // regular 12-gon: volume (n/2) r^2 sin(2 pi / n) * length.
  const int n = 12;
  const double r = 0.25, length = 2.0;
  const Mesh cylinder = make_cylinder(r, length, n, 8, FaceShape::Triangles);
  const double expected = 0.5 * n * r * r * std::sin(2 * M_PI / n) * length;
  EXPECT_NEAR(capped_volume(cylinder), expected, 1e-12);

  const QualityMetrics m = measure_quality(cylinder, scaled(cylinder, 1.5));
  EXPECT_EQ(m.boundary_loops, 2);
  ASSERT_TRUE(m.volume_change_percent.has_value());
  EXPECT_NEAR(*m.volume_change_percent, 100.0 * (1.5 * 1.5 * 1.5 - 1.0), 1e-9);
  EXPECT_NEAR(m.area_change_percent, 100.0 * (1.5 * 1.5 - 1.0), 1e-9);
  EXPECT_NEAR(m.edge_change_rms_percent, 50.0, 1e-9);
  EXPECT_NEAR(m.edge_change_max_percent, 50.0, 1e-9);
  EXPECT_NEAR(m.dihedral_change_max_deg, 0.0, 1e-9);  // scaling keeps every angle
  EXPECT_EQ(m.fold_overs, 0);
  EXPECT_EQ(m.self_intersecting_pairs, 0);
}

TEST(QualityMetrics, ClosedQuadBarScaledAlongOneAxis) {
  // A polygon mesh: the closed bar of quads, stretched by 2 along its length.
  const Mesh bar = make_bar(0.2, 1.0, 2, 5);
  Mesh stretched = bar;
  for (auto v : stretched.vertices()) stretched.point(v).y() *= 2.0;
  EXPECT_NEAR(capped_volume(bar), 0.2 * 0.2 * 1.0, 1e-12);
  const QualityMetrics m = measure_quality(bar, stretched);
  EXPECT_EQ(m.boundary_loops, 0);
  EXPECT_NEAR(*m.volume_change_percent, 100.0, 1e-9);
  EXPECT_NEAR(m.edge_change_max_percent, 100.0, 1e-9);  // the edges along y double
  EXPECT_NEAR(m.dihedral_change_max_deg, 0.0, 1e-9);    // still a box
  EXPECT_EQ(m.self_intersecting_pairs, 0);
  EXPECT_EQ(m.faces, int(bar.n_faces()));
}

TEST(QualityMetrics, RigidMotionChangesNothing) {
  const Mesh sphere = make_icosphere(2);
  Mesh moved = sphere;
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (auto v : moved.vertices()) moved.point(v) = R * moved.point(v) + Vec3(3, -1, 2);
  const QualityMetrics m = measure_quality(sphere, moved);
  EXPECT_NEAR(*m.volume_change_percent, 0.0, 1e-9);
  EXPECT_NEAR(m.area_change_percent, 0.0, 1e-9);
  EXPECT_LT(m.dihedral_change_max_deg, 1e-5);
  EXPECT_LT(m.edge_change_max_percent, 1e-9);
  EXPECT_EQ(m.interior_edges, int(sphere.n_edges()));
}

TEST(QualityMetrics, FoldedSheetCountsOneFoldOverAndNoIntersection) {
  // Two quads sharing the edge x = 1; the second is folded back over the first by 170 degrees
  // about that edge. The dihedral angle goes from 0 to 170 degrees: one fold-over. The faces
  // only share their edge, so they do not intersect.
  const std::vector<std::vector<int>> quads = {{0, 1, 4, 3}, {1, 2, 5, 4}};
  const std::vector<Vec3> flat = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0},
                                  {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
  const double a = 170.0 * M_PI / 180.0;
  std::vector<Vec3> folded = flat;
  folded[2] = Vec3(1.0 + std::cos(a), 0.0, std::sin(a));
  folded[5] = Vec3(1.0 + std::cos(a), 1.0, std::sin(a));
  const QualityMetrics m = measure_quality(soup_mesh(flat, quads), soup_mesh(folded, quads));
  EXPECT_EQ(m.interior_edges, 1);
  EXPECT_NEAR(m.dihedral_change_max_deg, 170.0, 1e-9);
  EXPECT_NEAR(m.dihedral_change_rms_deg, 170.0, 1e-9);
  EXPECT_EQ(m.fold_overs, 1);
  EXPECT_EQ(m.self_intersecting_pairs, 0);
  EXPECT_NEAR(m.edge_change_max_percent, 0.0, 1e-9);
  EXPECT_FALSE(m.volume_change_percent.has_value());  // a flat sheet has no volume

  // Folded by 140 degrees it is not a fold-over.
  const double b = 140.0 * M_PI / 180.0;
  folded[2] = Vec3(1.0 + std::cos(b), 0.0, std::sin(b));
  folded[5] = Vec3(1.0 + std::cos(b), 1.0, std::sin(b));
  EXPECT_EQ(measure_quality(soup_mesh(flat, quads), soup_mesh(folded, quads)).fold_overs, 0);
}

TEST(SelfIntersections, TwoCrossingTrianglesAreOnePair) {
  // A triangle in the z = 0 plane pierced by a vertical one.
  const Mesh crossing = soup_mesh({{0, 0, 0}, {2, 0, 0}, {0, 2, 0},
                                   {0.5, 0.5, -1}, {0.5, 0.5, 1}, {0.6, 0.4, 1}},
                                  {{0, 1, 2}, {3, 4, 5}});
  const SelfIntersections s = find_self_intersections(crossing);
  ASSERT_EQ(s.face_pairs.size(), 1u);
  EXPECT_EQ(s.face_pairs[0], std::make_pair(0, 1));
  EXPECT_EQ(s.degenerate_triangles, 0);
  EXPECT_EQ(measure_quality(crossing, crossing).self_intersecting_pairs, 1);
}

TEST(SelfIntersections, DisjointAndEdgeSharingTrianglesAreNone) {
  const Mesh disjoint = soup_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                   {0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.5}},
                                  {{0, 1, 2}, {3, 4, 5}});
  EXPECT_TRUE(find_self_intersections(disjoint).face_pairs.empty());
  // Two triangles sharing an edge, folded to a sharp 10-degree wedge: touching is not crossing.
  const Mesh wedge = soup_mesh({{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {std::cos(0.17), 0.5, std::sin(0.17)}},
                               {{0, 2, 1}, {0, 1, 3}});
  EXPECT_TRUE(find_self_intersections(wedge).face_pairs.empty());
}

TEST(SelfIntersections, CrossingQuadsAreOnePairOfOriginalFaces) {
  // Two quads crossing along a line that passes through both triangles of each: four triangle
  // pairs intersect, but they are one pair of faces. The two triangles of one quad never count.
  const Mesh quads = soup_mesh({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0},
                                {-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}},
                               {{0, 1, 2, 3}, {4, 5, 6, 7}});
  const SelfIntersections s = find_self_intersections(quads);
  ASSERT_EQ(s.face_pairs.size(), 1u);
  EXPECT_EQ(s.face_pairs[0], std::make_pair(0, 1));
}

TEST(QualityMetrics, DifferentConnectivityIsAnErrorNamingTheFiles) {
  const Mesh a = make_cylinder(0.25, 2.0, 8, 4, FaceShape::Triangles);
  const Mesh b = make_cylinder(0.25, 2.0, 8, 5, FaceShape::Triangles);
  try {
    measure_quality(a, b, "rest.obj", "posed.obj");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("posed.obj"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rest.obj"), std::string::npos) << e.what();
  }
  // Same counts, other corners.
  const Mesh quads = make_grid(1, 1, 2, 2, FaceShape::Triangles);
  Mesh flipped = make_grid(1, 1, 2, 2, FaceShape::Triangles);
  std::vector<std::vector<int>> faces;
  for (auto f : quads.faces()) {
    faces.emplace_back();
    for (auto v : f.vertices()) faces.back().push_back(v.idx());
  }
  std::swap(faces[0], faces[1]);
  std::vector<Vec3> points;
  for (auto v : quads.vertices()) points.push_back(quads.point(v));
  EXPECT_THROW(measure_quality(quads, soup_mesh(points, faces)), Error);
}

TEST(CgalPeers, ControlVerticesReachTheirTargetsAndIdentityStaysAtRest) {
  const Mesh cylinder = make_cylinder(0.25, 2.0, 8, 10, FaceShape::Triangles);
  std::vector<int> control;
  std::vector<Vec3> at_rest, shifted;
  for (auto v : cylinder.vertices()) {
    const Vec3& p = cylinder.point(v);
    if (p.y() < 1e-9 || p.y() > 2.0 - 1e-9) {
      control.push_back(v.idx());
      at_rest.push_back(p);
      shifted.push_back(p.y() > 1.0 ? Vec3(p + Vec3(0.3, 0, 0)) : p);
    }
  }
  for (PeerMethod method : {PeerMethod::Arap, PeerMethod::SrArap}) {
    const PeerResult rest = deform_with_cgal(cylinder, control, at_rest, method);
    for (auto v : cylinder.vertices())
      EXPECT_LT((rest.positions[size_t(v.idx())] - cylinder.point(v)).norm(), 1e-9);
    const PeerResult moved = deform_with_cgal(cylinder, control, shifted, method);
    for (size_t i = 0; i < control.size(); ++i)
      EXPECT_LT((moved.positions[size_t(control[i])] - shifted[i]).norm(), 1e-9);
    // The free middle follows part of the way.
    double mid_x = 0.0;
    int mid_count = 0;
    for (auto v : cylinder.vertices())
      if (std::abs(cylinder.point(v).y() - 1.0) < 1e-9) {
        mid_x += moved.positions[size_t(v.idx())].x() - cylinder.point(v).x();
        ++mid_count;
      }
    ASSERT_GT(mid_count, 0);
    EXPECT_GT(mid_x / mid_count, 0.05);
    EXPECT_LT(mid_x / mid_count, 0.25);
  }
  EXPECT_THROW(deform_with_cgal(make_grid(1, 1, 2, 2, FaceShape::Quads), {0}, {Vec3::Zero()},
                                PeerMethod::Arap),
               Error);
}

TEST(QualityLayering, CgalIsIncludedOnlyByTheQualityLibrarySources) {
  // CGAL's headers are heavy: only src/quality/*.cpp may include them, never a header (which
  // would carry them into every user) nor the core, the editor or the commands.
  namespace fs = std::filesystem;
  const std::string cgal_include = std::string("#include <") + "CGAL/";  // not this file itself
  std::vector<std::string> allowed, offending;
  for (const char* folder : {"include", "src", "tests"})
    for (const auto& entry : fs::recursive_directory_iterator(test::source_path(folder))) {
      const fs::path path = entry.path();
      if (path.extension() != ".h" && path.extension() != ".cpp") continue;
      std::ifstream in(path);
      std::stringstream text;
      text << in.rdbuf();
      if (text.str().find(cgal_include) == std::string::npos) continue;
      const bool in_quality_source =
          path.parent_path().filename() == "quality" && path.extension() == ".cpp";
      (in_quality_source ? allowed : offending).push_back(path.string());
    }
  for (const std::string& path : offending) ADD_FAILURE() << path << " includes CGAL";
  EXPECT_EQ(allowed.size(), 2u);  // self_intersections.cpp, cgal_deformation.cpp
}

}  // namespace
}  // namespace primo::quality
