// Large steps (PathOptions): a jump of the targets is followed in sub-steps, so a one-step
// solve lands where a drag lands; and the default material is the same at every resolution.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>

#include "primo/solve/deformer.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_subdivision.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::bent_cylinder;
using primo::test::BentCylinder;
using primo::test::faces_where;

namespace {

SolveOptions converging(bool path) {
  SolveOptions o;
  o.max_iterations = 500;
  o.tolerance = 1e-8;
  o.path.enabled = path;
  return o;
}

// The handle's transform a fraction s of the way from rest, as a hand would drag and turn it
// about the handle's centre.
RigidTransform dragged(const RigidTransform& to, const Vec3& center, double s) {
  const Eigen::Quaterniond q(to.rotation);
  RigidTransform t;
  t.rotation = Eigen::Quaterniond::Identity().slerp(s, q).toRotationMatrix();
  t.translation = center + s * (to.apply(center) - center) - t.rotation * center;
  return t;
}

Vec3 handle_center(const Deformer& d, int handle) {
  return d.system().bodies[handle].rest_center;
}

}  // namespace

TEST(DeformerPath, HalfBendFromRestEndsNoHigherThanADrag) {
  // The paper's Figure 2 bend, 180 degrees, on the thin layer of prisms.height 1.
  const BentCylinder c = bent_cylinder(16, 24, 180.0, 0.0, Fix::All, FaceShape::Triangles);
  const RigidTransform target = c.handles[1].transform;

  // The drag: 30 frames of 3 iterations each, then converged.
  Deformer drag(c.mesh, PrismParameters{}, c.handles);
  const Vec3 center = handle_center(drag, 1);
  SolveOptions frame = converging(false);
  frame.max_iterations = 3;
  for (int k = 1; k <= 30; ++k) {
    drag.set_handle_transform(1, dragged(target, center, k / 30.0));
    drag.solve(frame);
  }
  const double dragged_energy = drag.solve(converging(false)).energy;

  Deformer one_step(c.mesh, PrismParameters{}, c.handles);
  const SolveReport direct = one_step.solve(converging(false));

  Deformer path(c.mesh, PrismParameters{}, c.handles);
  const SolveReport followed = path.solve(converging(true));

  std::cout << "[ metric   ] half bend, 768 triangles: drag E = " << dragged_energy
            << ", one step " << direct.energy << " (" << direct.iterations << " iterations), path "
            << followed.energy << " (" << followed.path_steps << " sub-steps, "
            << followed.path_iterations << " + " << followed.iterations << " iterations)\n";
  ASSERT_TRUE(direct.converged && followed.converged);
  EXPECT_GT(followed.path_steps, 0);
  EXPECT_LE(followed.energy, dragged_energy * 1.001);
  // Without the path this case lands in a worse minimum: the check above means something.
  EXPECT_GT(direct.energy, dragged_energy * 1.05);
}

TEST(DeformerPath, SmallMovesTakeNoSubStepsAndLargeOnesAreSplit) {
  const BentCylinder c = bent_cylinder(12, 16, 0.0);
  Deformer d(c.mesh, PrismParameters{}, c.handles);
  const Vec3 center = handle_center(d, 1);
  SolveOptions o = converging(true);
  auto turn = [&](double deg) {
    RigidTransform t;
    t.rotation = Eigen::AngleAxisd(deg * M_PI / 180.0, Vec3::UnitZ()).toRotationMatrix();
    t.translation = center - t.rotation * center;
    return t;
  };
  d.set_handle_transform(1, turn(5.0));
  EXPECT_FALSE(d.path_pending(o.path));
  EXPECT_EQ(d.solve(o).path_steps, 0);
  // 40 degrees further: ceil(40 / 15) = 3 steps, the last one at the target.
  d.set_handle_transform(1, turn(45.0));
  EXPECT_TRUE(d.path_pending(o.path));
  const SolveReport r = d.solve(o);
  EXPECT_EQ(r.path_steps, 2);
  EXPECT_FALSE(d.path_pending(o.path));
  // A move of the handle's centre by a third of the diagonal: 4 steps of at most 0.1.
  RigidTransform moved = turn(45.0);
  moved.translation += Vec3(c.diagonal / 3.0, 0.0, 0.0);
  d.set_handle_transform(1, moved);
  EXPECT_EQ(d.solve(o).path_steps, 3);
}

TEST(DeformerPath, APathResumedInSmallBudgetsEndsAtTheSameMinimum) {
  const BentCylinder c = bent_cylinder(16, 24, 150.0);
  Deformer whole(c.mesh, PrismParameters{}, c.handles);
  const SolveReport one_call = whole.solve(converging(true));
  ASSERT_TRUE(one_call.converged);

  // As the editor's solver thread does: a batch of 2 iterations per call.
  Deformer batched(c.mesh, PrismParameters{}, c.handles);
  SolveOptions o = converging(true);
  o.max_iterations = 2;
  o.path.max_iterations = 2;
  int calls = 0, sub_steps = 0;
  SolveReport r;
  do {
    r = batched.solve(o);
    sub_steps += r.path_steps;
    ++calls;
  } while (!r.converged && calls < 500);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(sub_steps, one_call.path_steps);
  EXPECT_GT(calls, one_call.path_steps / 2);  // the path was spread over several calls
  EXPECT_NEAR(r.energy, one_call.energy, 1e-6 * one_call.energy);
  EXPECT_LT(largest_point_distance(batched.vertex_positions(), whole.vertex_positions()),
            1e-4 * c.diagonal);
}

TEST(DeformerPath, APathResumedOneIterationAtATimeIsTheSamePath) {
  // The editor's first batches after an undo or redo are single iterations: a sub-step cut
  // short goes on in the next call, with the path's prediction, as if in one call.
  const BentCylinder c = bent_cylinder(16, 24, 150.0);
  for (const SolveMethod method : {SolveMethod::Global, SolveMethod::Hierarchical}) {
    SolveOptions o = converging(true);
    o.method = method;
    Deformer whole(c.mesh, PrismParameters{}, c.handles);
    const SolveReport one_call = whole.solve(o);
    ASSERT_TRUE(one_call.converged);
    ASSERT_GT(one_call.path_steps, 1);

    Deformer batched(c.mesh, PrismParameters{}, c.handles);
    SolveOptions single = o;
    single.max_iterations = 1;
    single.path.max_iterations = 1;
    int calls = 0, sub_steps = 0, path_iterations = 0, iterations = 0;
    SolveReport r;
    do {
      r = batched.solve(single);
      sub_steps += r.path_steps;
      path_iterations += r.path_iterations;
      iterations += r.iterations;
      ++calls;
    } while (!r.converged && calls < 1000);
    ASSERT_TRUE(r.converged);
    EXPECT_EQ(sub_steps, one_call.path_steps);
    EXPECT_EQ(path_iterations, one_call.path_iterations) << "sub-steps cut short";
    std::cout << "one call: " << one_call.path_iterations << " + " << one_call.iterations
              << " iterations; single ones: " << path_iterations << " + " << iterations << "\n";
    EXPECT_NEAR(r.energy, one_call.energy, 1e-6 * one_call.energy);
    EXPECT_LT(largest_point_distance(batched.vertex_positions(), whole.vertex_positions()),
              1e-4 * c.diagonal);
  }
}

TEST(DeformerPath, ARedoAfterAnUndoTakesNoMoreThanTheFirstSolve) {
  // Undo and redo are jumps: the hierarchy's coarse factor from before the jump must not
  // carry over into the new path's first cycles (a koala redo took 192 iterations instead of
  // 20 with it).
  const BentCylinder c = bent_cylinder(24, 48, 150.0);
  SolveOptions o = converging(true);
  o.method = SolveMethod::Hierarchical;
  Deformer d(c.mesh, PrismParameters{}, c.handles);
  const SolveReport first = d.solve(o);
  ASSERT_TRUE(first.converged);
  const RigidTransform pose = c.handles[1].transform;
  d.set_handle_transform(1, RigidTransform::identity());
  ASSERT_TRUE(d.solve(o).converged);  // the undo
  d.set_handle_transform(1, pose);
  const SolveReport redo = d.solve(o);
  ASSERT_TRUE(redo.converged);
  std::cout << "first solve " << first.path_iterations << " + " << first.iterations
            << " iterations, redo " << redo.path_iterations << " + " << redo.iterations << "\n";
  EXPECT_LE(redo.path_iterations + redo.iterations, first.path_iterations + first.iterations + 2);
  EXPECT_NEAR(redo.energy, first.energy, 1e-6 * first.energy);
}

TEST(DeformerPath, DefaultMaterialPosesASubdividedModelAlike) {
  // A bent tube and the same tube Loop-subdivided once (4x the faces): with the default,
  // resolution-independent thickness both take the same shape; with the format's height in
  // mean edge lengths the finer tube is a thinner, softer layer and sags differently.
  const BentCylinder coarse = bent_cylinder(16, 24, 90.0, 0.0, Fix::All, FaceShape::Triangles);
  const Mesh fine_mesh = loop_subdivide(coarse.mesh, 1, "cylinder");
  const double band = 2.0 / 24;
  std::vector<Handle> fine_handles = coarse.handles;
  fine_handles[0].faces = faces_where(fine_mesh, [&](const Vec3& p) { return p.y() < band; });
  fine_handles[1].faces = faces_where(fine_mesh, [&](const Vec3& p) { return p.y() > 2.0 - band; });

  auto pose = [&](const Mesh& mesh, const std::vector<Handle>& handles, const PrismParameters& p) {
    Deformer d(mesh, p, handles);
    EXPECT_TRUE(d.solve(converging(true)).converged);
    std::vector<Vec3> x = d.vertex_positions();
    x.resize(coarse.mesh.n_vertices());  // Loop keeps the original vertices first
    return x;
  };
  const PrismParameters product = PrismParameters::product_default();
  const double apart = largest_point_distance(pose(coarse.mesh, coarse.handles, product),
                                              pose(fine_mesh, fine_handles, product)) /
                       coarse.diagonal;
  const double legacy_apart =
      largest_point_distance(pose(coarse.mesh, coarse.handles, PrismParameters{}),
                             pose(fine_mesh, fine_handles, PrismParameters{})) /
      coarse.diagonal;
  std::cout << "[ metric   ] tube and its Loop subdivision, largest vertex distance: "
            << 100 * apart << "% of the diagonal with the default half_thickness, "
            << 100 * legacy_apart << "% with height 1 (mean edge lengths)\n";
  EXPECT_LT(apart, 0.005);
  EXPECT_GT(legacy_apart, 0.005);
}
