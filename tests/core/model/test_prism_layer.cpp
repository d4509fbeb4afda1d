#include "primo/model/prism_layer.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_generators.h"

using namespace primo;

namespace {

std::vector<Mesh> sample_meshes() {
  return {make_cylinder(0.3, 1.0, 12, 8, FaceShape::Quads),
          make_cylinder(0.3, 1.0, 12, 8, FaceShape::Triangles), make_bar(0.2, 1.0, 2, 6),
          make_icosphere(2), make_grid(1.0, 0.5, 6, 3, FaceShape::Quads)};
}

}  // namespace

TEST(PrismLayer, CornersFollowTheScenarioDefinition) {
  const Mesh mesh = make_grid(2.0, 1.0, 2, 1, FaceShape::Quads);  // 2 unit squares, normal +z
  PrismParameters p;
  p.height = 0.5;
  p.width = 0.5;
  const PrismLayer layer = build_prism_layer(mesh, p);
  EXPECT_DOUBLE_EQ(layer.mean_edge_length, 1.0);
  ASSERT_EQ(layer.joints.size(), 1u);
  // Face 0 = [0,1]x[0,1], centroid (0.5, 0.5): the width-scaled copy of vertex (1,0) is
  // (0.75, 0.25); the offset is h = 0.5 * mean edge along +z.
  const int k = layer.corner_begin[0] + 1;
  EXPECT_EQ(layer.corner_vertex[k], 1);
  EXPECT_LT((layer.corner_point[k] - Vec3(0.75, 0.25, 0)).norm(), 1e-15);
  EXPECT_LT((layer.corner_offset[k] - Vec3(0, 0, 0.5)).norm(), 1e-15);
  // w_ij = |e|^2 / (|F_i| + |F_j|) = 1 / 2.
  EXPECT_DOUBLE_EQ(layer.joints[0].weight, 0.5);
}

TEST(PrismLayer, HeightFactorIsTheMinimumOverIncidentFaces) {
  const Mesh mesh = make_grid(2.0, 1.0, 2, 1, FaceShape::Quads);
  PrismParameters p;
  p.face_height_factor = {0.25, 1.0};
  const PrismLayer layer = build_prism_layer(mesh, p);
  // Vertex 1 (shared, bottom middle) takes 0.25 in both faces; vertex 2 (face 1 only) 1.
  for (int k = 0; k < int(layer.corner_vertex.size()); ++k) {
    const int v = layer.corner_vertex[k];
    const double expected = (v == 0 || v == 1 || v == 3 || v == 4) ? 0.25 : 1.0;
    EXPECT_NEAR(layer.corner_offset[k].norm(), expected, 1e-15) << "vertex " << v;
  }
}

TEST(PrismLayer, ZeroLengthBlendedDirectionIsAnError) {
  // A doubly covered triangle (two faces, opposite orientations, all edges shared) is a
  // closed manifold whose vertex normals cancel: with blend 0 there is no extrusion direction.
  Mesh mesh;
  auto v0 = mesh.add_vertex(Vec3(0, 0, 0)), v1 = mesh.add_vertex(Vec3(1, 0, 0));
  auto v2 = mesh.add_vertex(Vec3(0, 1, 0));
  mesh.add_face(v0, v1, v2);
  mesh.add_face(v1, v0, v2);
  ASSERT_EQ(mesh.n_faces(), 2u);
  try {
    build_prism_layer(mesh, PrismParameters{});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("face 0, vertex 0"), std::string::npos) << e.what();
  }
  // The plate blend uses face normals only, which are fine.
  PrismParameters plate;
  plate.normal_blend = 1.0;
  EXPECT_NO_THROW(build_prism_layer(mesh, plate));
}

TEST(PrismLayer, RestStateHasZeroEnergy) {
  for (const Mesh& mesh : sample_meshes()) {
    Deformer d(mesh, PrismParameters{}, {});
    EXPECT_LT(d.energy(), 1e-28) << mesh.n_faces() << " faces";
  }
}

TEST(PrismLayer, OneRigidMotionOfEveryPrismHasZeroEnergy) {
  std::mt19937 rng(1);
  std::normal_distribution<double> n;
  for (const Mesh& mesh : sample_meshes()) {
    Deformer d(mesh, PrismParameters{}, {});
    RigidTransform m;
    m.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
    m.translation = Vec3(n(rng), n(rng), n(rng));
    d.set_face_motions(std::vector<RigidTransform>(mesh.n_faces(), m));
    EXPECT_LT(d.energy(), 1e-26) << mesh.n_faces() << " faces";
    const std::vector<Vec3> moved = d.vertex_positions();
    for (auto v : mesh.vertices())
      EXPECT_LT((moved[v.idx()] - m.apply(mesh.point(v))).norm(), 1e-13);
  }
}

TEST(PrismLayer, WidthAndPlateBlendGiveRestEnergy) {
  const Mesh mesh = make_icosphere(2);
  PrismParameters shrink;
  shrink.width = 0.9;
  EXPECT_GT(Deformer(mesh, shrink, {}).energy(), 1e-6);
  PrismParameters plate;
  plate.normal_blend = 1.0;
  EXPECT_GT(Deformer(mesh, plate, {}).energy(), 1e-6);
  // A flat grid has vertex normal == face normal: the plate blend changes nothing there.
  const Mesh flat = make_grid(1.0, 1.0, 4, 4, FaceShape::Quads);
  EXPECT_LT(Deformer(flat, plate, {}).energy(), 1e-28);
}

TEST(PrismLayer, EnergyMatchesTheSixteenTermFormula) {
  // Bend a cylinder arbitrarily, then compare the engine's energy with a direct evaluation
  // of sum_ij w_ij <f_ij - f_ji, f_ij - f_ji>_2 from the moved corners.
  const Mesh mesh = make_cylinder(0.3, 1.0, 8, 5, FaceShape::Quads);
  Deformer d(mesh, PrismParameters{}, {});
  std::mt19937 rng(9);
  std::normal_distribution<double> n(0.0, 0.2);
  std::vector<RigidTransform> motions(mesh.n_faces());
  for (RigidTransform& m : motions) {
    m.rotation = Eigen::AngleAxisd(n(rng), Vec3(n(rng), n(rng), 1).normalized()).toRotationMatrix();
    m.translation = Vec3(n(rng), n(rng), n(rng));
  }
  d.set_face_motions(motions);
  const PrismLayer& layer = d.prisms();  // in the solver's numbering
  motions = d.order().faces_to_solver(motions);
  double expected = 0.0;
  for (const Joint& j : layer.joints) {
    PatchCorners diff;
    for (int s = 0; s < 2; ++s) {
      const int f = j.face[s];
      PatchCorners moved;
      int ka = -1, kb = -1;
      for (int k = layer.corner_begin[f]; k < layer.corner_begin[f + 1]; ++k) {
        if (layer.corner_vertex[k] == j.vertex[0]) ka = k;
        if (layer.corner_vertex[k] == j.vertex[1]) kb = k;
      }
      moved = {motions[f].apply(layer.corner_point[ka] - layer.corner_offset[ka]),
               motions[f].apply(layer.corner_point[kb] - layer.corner_offset[kb]),
               motions[f].apply(layer.corner_point[ka] + layer.corner_offset[ka]),
               motions[f].apply(layer.corner_point[kb] + layer.corner_offset[kb])};
      for (int c = 0; c < 4; ++c) diff[c] = s == 0 ? moved[c] : Vec3(diff[c] - moved[c]);
    }
    expected += j.weight * bilinear_inner_product(diff, diff);
  }
  EXPECT_GT(expected, 1e-3);
  EXPECT_NEAR(d.energy(), expected, 1e-12 * expected);
}
