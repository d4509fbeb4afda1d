// Editor handle groups: creation poses, taking faces from other groups, engine inputs.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "document/edit_state.h"
#include "primo/mesh/mesh_generators.h"

using namespace primo;
using namespace primo::editor;

namespace {

struct Grid {
  MeshTopology topology = build_topology(make_grid(4, 3, 4, 3, FaceShape::Quads));
  EditState state = initial_edit_state(12);
};

}  // namespace

TEST(EditorHandles, NewGroupAtRestIsIdentity) {
  Grid g;
  const int h = add_handle(g.state, g.topology, g.topology.rest_points, {5, 1, 5}, HandleMode::Pose);
  ASSERT_EQ(h, 0);
  const HandleGroup& group = g.state.handles[0];
  EXPECT_EQ(*group.faces, (std::vector<int>{1, 5}));
  EXPECT_TRUE(group.pose.is_identity());
  EXPECT_EQ(group.name, "Handle 1");
  EXPECT_EQ(g.state.active, 0);
  EXPECT_TRUE(group.center.isApprox(Vec3(1.5, 1.0, 0.0)));
}

TEST(EditorHandles, NewGroupOnDeformedMeshKeepsItsPose) {
  Grid g;
  // The whole mesh rotated by 30 degrees about z and shifted.
  const Eigen::AngleAxisd rot(0.5236, Vec3::UnitZ());
  std::vector<Vec3> moved;
  for (const Vec3& p : g.topology.rest_points) moved.push_back(rot * p + Vec3(0.3, -0.2, 1.0));
  add_handle(g.state, g.topology, moved, {0, 1, 4}, HandleMode::Pose);
  const RigidTransform t = g.state.handles[0].transform();
  for (int v : {0, 1, 5, 6})
    EXPECT_LT((t.apply(g.topology.rest_points[v]) - moved[v]).norm(), 1e-12);
  // A spring starts where its faces are.
  add_handle(g.state, g.topology, moved, {11}, HandleMode::Spring);
  const HandleGroup& spring = g.state.handles[1];
  const Vec3 rest_c = g.topology.rest_geometry.centroid[11];
  EXPECT_LT((rest_c + spring.pose.translate - (rot * rest_c + Vec3(0.3, -0.2, 1.0))).norm(), 1e-12);
}

TEST(EditorHandles, NewGroupTakesFacesAndDropsEmptiedGroups) {
  Grid g;
  add_handle(g.state, g.topology, g.topology.rest_points, {0, 1}, HandleMode::Pose);
  add_handle(g.state, g.topology, g.topology.rest_points, {2, 3}, HandleMode::Fixed);
  g.state.handles[0].pose.translate = Vec3(0, 0, 1);
  add_handle(g.state, g.topology, g.topology.rest_points, {1, 2, 3}, HandleMode::Position);
  ASSERT_EQ(g.state.handles.size(), 2u);
  EXPECT_EQ(*g.state.handles[0].faces, (std::vector<int>{0}));
  // What is left keeps its motion; its pivot moves to the rest centroid of what is left.
  EXPECT_TRUE(g.state.handles[0].center.isApprox(g.topology.rest_geometry.centroid[0]));
  EXPECT_TRUE(g.state.handles[0].pose.translate.isApprox(Vec3(0, 0, 1)));
  EXPECT_EQ(g.state.handles[1].mode, HandleMode::Position);
  EXPECT_EQ(g.state.active, 1);
  remove_handle(g.state, 1);
  EXPECT_EQ(g.state.active, 0);
  remove_handle(g.state, 0);
  EXPECT_EQ(g.state.active, -1);
}

TEST(EditorHandles, DeformationInputsMapModes) {
  Grid g;
  for (auto [faces, mode] : std::vector<std::pair<std::vector<int>, HandleMode>>{
           {{0}, HandleMode::Fixed}, {{1}, HandleMode::Spring}, {{2}, HandleMode::Position},
           {{3}, HandleMode::Orientation}, {{4}, HandleMode::Pose}})
    add_handle(g.state, g.topology, g.topology.rest_points, faces, mode);
  g.state.handles[1].pose.translate = Vec3(0, 1, 0);
  g.state.handles[1].stiffness = 4.0;
  g.state.handles[4].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
  const DeformationInputs in = deformation_inputs(g.state);
  ASSERT_EQ(in.handles.size(), 4u);
  ASSERT_EQ(in.forces.size(), 1u);
  EXPECT_EQ(in.group_force[1], 0);
  EXPECT_EQ(in.group_handle[1], -1);
  EXPECT_EQ(in.handles[0].fix, Fix::All);
  EXPECT_EQ(in.handles[1].fix, Fix::Position);
  EXPECT_EQ(in.handles[2].fix, Fix::Orientation);
  EXPECT_EQ(in.forces[0].stiffness, 4.0);
  EXPECT_EQ(in.forces[0].target_offset, Vec3(0, 1, 0));
  // The pivot is fixed by a pure rotation about it.
  const HandleGroup& pose = g.state.handles[4];
  EXPECT_LT((in.handles[3].transform.apply(pose.center) - pose.center).norm(), 1e-15);

  // Poses alone keep the structure; modes, stiffness and factors do not.
  EditState moved = g.state;
  moved.handles[4].pose.translate = Vec3(1, 2, 3);
  EXPECT_TRUE(same_structure(g.state, moved));
  moved.handles[1].stiffness = 5.0;
  EXPECT_FALSE(same_structure(g.state, moved));
  moved = g.state;
  set_handle_mode(moved, 4, HandleMode::Position);
  EXPECT_FALSE(same_structure(g.state, moved));
  moved = g.state;
  moved.height_factor = std::make_shared<const std::vector<double>>(12, 1.0);
  EXPECT_TRUE(same_structure(g.state, moved)) << "all-ones factors equal no factors";
  moved.prisms.height = 0.5;
  EXPECT_FALSE(same_structure(g.state, moved));
}

TEST(EditorHandles, ResetAndSpringModeDropRotation) {
  Grid g;
  add_handle(g.state, g.topology, g.topology.rest_points, {0}, HandleMode::Pose);
  g.state.handles[0].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
  g.state.handles[0].pose.translate = Vec3(1, 0, 0);
  set_handle_mode(g.state, 0, HandleMode::Spring);
  EXPECT_TRUE(g.state.handles[0].pose.rotation.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs()));
  EXPECT_EQ(g.state.handles[0].pose.translate, Vec3(1, 0, 0));
  reset_handle(g.state, 0);
  EXPECT_TRUE(g.state.handles[0].pose.is_identity());
}

TEST(EditorHandles, SaysWhenOneHandleMovesTheWholeMeshRigidly) {
  const Mesh mesh = make_bar(0.2, 1.0, 2, 10);
  const MeshTopology t = build_topology(mesh);
  EditState s = initial_edit_state(t.n_faces);
  EXPECT_FALSE(moves_whole_mesh_rigidly(s));  // no handle: nothing moves
  add_handle(s, t, t.rest_points, {0, 1}, HandleMode::Pose);
  EXPECT_TRUE(moves_whole_mesh_rigidly(s));
  add_handle(s, t, t.rest_points, {5}, HandleMode::Spring);
  EXPECT_TRUE(moves_whole_mesh_rigidly(s)) << "a spring does not hold the mesh";
  add_handle(s, t, t.rest_points, {20, 21}, HandleMode::Fixed);
  EXPECT_FALSE(moves_whole_mesh_rigidly(s));
  remove_handle(s, 2);
  add_handle(s, t, t.rest_points, {30}, HandleMode::Position);
  EXPECT_FALSE(moves_whole_mesh_rigidly(s)) << "two handles pull against each other";
}
