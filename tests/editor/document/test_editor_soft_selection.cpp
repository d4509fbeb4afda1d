// Soft selection: a handle's falloff reaches the free faces around it with Blender's smooth
// weights, pulls them after the handle, and saves as forces that `primo deform` solves to the
// pose the editor shows.

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <limits>
#include <utility>

#include "document/document.h"
#include "document/scenario_bridge.h"
#include "document/selection/soft_selection.h"
#include "support/editor_harness.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/geometry.h"
#include "primo/scenario/scenario.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;

using harness::faces_where;
using harness::settle;

TEST(EditorSoftSelection, SmoothFalloffIsBlendersSmoothstep) {
  EXPECT_EQ(smooth_falloff(0.0), 0.0);
  EXPECT_EQ(smooth_falloff(1.0), 1.0);
  EXPECT_DOUBLE_EQ(smooth_falloff(0.5), 0.5);
  EXPECT_DOUBLE_EQ(smooth_falloff(0.25), 3 * 0.0625 - 2 * 0.015625);
  EXPECT_EQ(smooth_falloff(-1.0), 0.0);
  EXPECT_EQ(smooth_falloff(2.0), 1.0);
}

TEST(EditorSoftSelection, FalloffReachesFreeFacesWithinTheRadius) {
  const MeshTopology t = build_topology(make_cylinder(0.25, 2.0, 12, 20, FaceShape::Quads));
  const std::vector<int> top = faces_where(t, 1.9, 2.0);
  FaceMask taken(size_t(t.n_faces), 0);
  apply_selection(taken, top, SelectOp::Add);
  apply_selection(taken, faces_where(t, 1.75, 1.8), SelectOp::Add);  // another group's band
  const double radius = 0.5;
  const std::vector<FalloffFace> falloff = falloff_faces(t, top, radius, taken);
  ASSERT_FALSE(falloff.empty());
  double shares = 0.0;
  for (const FalloffFace& f : falloff) {
    EXPECT_FALSE(taken[size_t(f.face)]) << f.face;
    double d = 1e9;
    for (int h : top)
      d = std::min(d, (t.rest_geometry.centroid[size_t(f.face)] - t.rest_geometry.centroid[size_t(h)]).norm());
    EXPECT_LT(d, radius);
    EXPECT_DOUBLE_EQ(f.weight, smooth_falloff(1.0 - d / radius));
    shares += f.share;
  }
  EXPECT_LT(shares, 1.0);
  // Every free face within the radius is in it.
  for (int f = 0; f < t.n_faces; ++f) {
    if (taken[size_t(f)]) continue;
    double d = 1e9;
    for (int h : top)
      d = std::min(d, (t.rest_geometry.centroid[size_t(f)] - t.rest_geometry.centroid[size_t(h)]).norm());
    const bool in = std::any_of(falloff.begin(), falloff.end(), [&](const FalloffFace& x) { return x.face == f; });
    EXPECT_EQ(in, d < radius * (1 - 1e-9)) << f;
  }
  EXPECT_TRUE(falloff_faces(t, top, 0.0, taken).empty());
}

TEST(EditorSoftSelection, AFadingHandleBendsMoreAroundItAndDeformReproducesIt) {
  const std::string dir = test::temp_dir();
  std::vector<Vec3> without;
  for (const bool soft : {false, true}) {
    Editor editor;
    const int top = harness::open_tube_with_fixed_base(editor, dir);
    Document& doc = *editor.document();
    const MeshTopology& t = *doc.topology;
    if (soft) {
      editor.set_falloff_radius(top, 0.6);
      ASSERT_TRUE(doc.state.handles[size_t(top)].falloff);
      doc.state.handles[size_t(top)].stiffness = 50.0;
    }
    doc.state.handles[size_t(top)].pose.translate = Vec3(0.6, 0.0, 0.0);
    editor.commit("pull");
    ASSERT_TRUE(settle(editor));
    const std::vector<Vec3> shown = editor.positions();
    if (!soft) {
      without = shown;
      continue;
    }
    // Just under the handle the tube follows it further than without the falloff.
    const FalloffFace& near = doc.state.handles[size_t(top)].falloff->back();
    int vertex = t.face_vertices[size_t(t.face_begin[size_t(near.face)])];
    EXPECT_GT(shown[size_t(vertex)].x() - without[size_t(vertex)].x(), 0.01)
        << "face " << near.face << " of weight " << near.weight;

    // Saved: one force a falloff face, as the editor solves them.
    const std::string scenario = dir + "/soft.json";
    ASSERT_TRUE(editor.save_scenario(scenario));
    const Scenario saved = load_scenario(scenario);
    ASSERT_EQ(saved.forces.size(), doc.state.handles[size_t(top)].falloff->size());
    const ResolvedScenario r = resolve_scenario(saved, *doc.mesh);
    const DeformationInputs in = deformation_inputs(doc.state);
    ASSERT_EQ(r.forces.size(), in.forces.size());
    for (size_t i = 0; i < in.forces.size(); ++i) {
      EXPECT_EQ(r.forces[i].faces, in.forces[i].faces);
      EXPECT_LT((r.forces[i].target_offset - in.forces[i].target_offset).norm(), 1e-12);
      EXPECT_NEAR(r.forces[i].stiffness, in.forces[i].stiffness, 1e-12 * in.forces[i].stiffness);
    }
    const test::CommandResult run = test::run_primo("deform " + scenario + " -o " + dir + "/out.obj");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Mesh out = load_mesh(dir + "/out.obj");
    std::vector<Vec3> deformed;
    for (auto v : out.vertices()) deformed.push_back(out.point(v));
    const double apart = largest_point_distance(deformed, shown) / t.bbox_diagonal;
    std::cout << "[ metric   ] soft selection over " << in.forces.size()
              << " faces: primo deform of the saved scenario is " << apart
              << " of the diagonal from the editor's pose\n";
    EXPECT_LT(apart, 1e-8);
  }
}

TEST(EditorSoftSelection, FalloffFacesAreThoseOfComparingWithEveryHandleFace) {
  // The lookup of nearby handle faces must give exactly the faces and weights of the plain
  // rule: the distance to the nearest of all the handle's rest centroids.
  const MeshTopology t = build_topology(make_cylinder(0.25, 2.0, 24, 60, FaceShape::Triangles));
  const std::vector<int> top = faces_where(t, 1.2, 2.0);
  FaceMask taken(size_t(t.n_faces), 0);
  apply_selection(taken, top, SelectOp::Add);
  const auto& centroid = t.rest_geometry.centroid;
  for (double radius : {1e-9, 0.013, 0.05, 0.31, 0.7, 5.0}) {
    std::vector<std::pair<int, double>> expected;
    for (int f = 0; f < t.n_faces; ++f) {
      if (taken[size_t(f)]) continue;
      double d = std::numeric_limits<double>::infinity();
      for (int h : top) d = std::min(d, (centroid[size_t(f)] - centroid[size_t(h)]).norm());
      const double w = smooth_falloff(1.0 - d / radius);
      if (w > 0.0) expected.emplace_back(f, w);
    }
    const std::vector<FalloffFace> got = falloff_faces(t, top, radius, taken);
    ASSERT_EQ(got.size(), expected.size()) << "radius " << radius;
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].face, expected[i].first) << "radius " << radius;
      EXPECT_EQ(got[i].weight, expected[i].second) << "radius " << radius;
    }
  }
}
