// A drag's preview (Deformer::preview, HierarchicalSolver::begin_preview): the coarse levels'
// solve carried to every vertex while the hand moves, and the full resolution from it after.

#include <gtest/gtest.h>

#include <iostream>

#include "primo/solve/deformer.h"
#include "primo/mesh/geometry.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/mesh_order.h"
#include "primo/util/parallel.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::faces_where;

namespace {

// Spot with every kind of target: feet fixed, the head turned by an orientation-only handle,
// the back pulled by a position-only handle, the tail by a spring.
struct PosedSpot {
  Mesh mesh = load_mesh(test::source_path("assets/meshes/spot_quadrangulated.obj"));
  std::vector<Handle> handles;
  std::vector<Force> forces;
  PosedSpot() {
    handles.push_back({"feet", faces_where(mesh, [](const Vec3& p) { return p.y() < -0.6; }),
                       Fix::All, {}});
    handles.push_back({"head",
                       faces_where(mesh, [](const Vec3& p) { return (p - Vec3(0, 0.2, 0.95)).norm() < 0.2; }),
                       Fix::Orientation, {}});
    handles.push_back({"back",
                       faces_where(mesh, [](const Vec3& p) { return (p - Vec3(0, 0.67, -0.02)).norm() < 0.12; }),
                       Fix::Position, {}});
    forces.push_back({"tail",
                      faces_where(mesh, [](const Vec3& p) { return p.z() < -0.55 && p.y() > 0.0; }),
                      Vec3::Zero(), 50.0});
  }
  // The targets at a fraction t of the pose.
  void place(Deformer& d, double t) const {
    d.set_handle_transform(1, make_rigid_transform(Vec3::Zero(), Vec3::UnitY(), 40.0 * t,
                                                   Vec3(0, 0.2, 0.95)));
    RigidTransform back = RigidTransform::identity();
    back.translation = t * Vec3(0.0, 0.2, 0.1);
    d.set_handle_transform(2, back);
    d.set_force_offset(0, t * Vec3(0.25, 0.1, 0.0));
  }
};

SolveOptions hierarchical(int iterations, double tolerance) {
  SolveOptions o;
  o.method = SolveMethod::Hierarchical;
  o.max_iterations = iterations;
  o.tolerance = tolerance;
  o.drag_frame = true;
  o.hierarchical.hierarchy.coarsest_max_bodies = 150;  // several levels on a small mesh
  return o;
}

// The solver's body states as face_motions() shows them (a body's faces move as one).
std::vector<BodyState> shown_states(const Deformer& d) {
  const std::vector<RigidTransform> motions = d.order().faces_to_solver(d.face_motions());
  std::vector<BodyState> states;
  for (const RigidSystem::Body& body : d.system().bodies) {
    const RigidTransform& m = motions[size_t(body.faces.front())];
    states.push_back({m.rotation, m.apply(body.rest_center)});
  }
  return states;
}

}  // namespace

TEST(DragPreview, ItsEnergyIsTheFineEnergyOfThePictureAndFallsFromTheStart) {
  // On an intermediate level (swept) and on the coarsest (Newton steps).
  const PosedSpot spot;
  ASSERT_FALSE(spot.forces[0].faces.empty());
  for (const int max_couplings : {1 << 30, 0}) {
    Deformer d(spot.mesh, PrismParameters{}, spot.handles, spot.forces);
    SolveOptions frame = hierarchical(1, 0.0);
    frame.hierarchical.preview_max_couplings = max_couplings;
    d.prepare(frame);
    const HierarchicalSolver& h = *d.hierarchical_solver();
    ASSERT_GE(h.levels(), 3);
    for (int k = 1; k <= 10; ++k) {
      spot.place(d, k / 10.0);
      const double moved = d.previewing() ? 0.0 : d.system().energy(d.body_states());
      const SolveReport r = d.preview(frame);
      ASSERT_TRUE(d.previewing());
      EXPECT_EQ(h.preview_level(), max_couplings == 0 ? h.levels() - 1 : 1);
      EXPECT_EQ(r.stop_reason, "preview");
      const double picture = d.system().energy(shown_states(d));
      EXPECT_NEAR(r.energy, picture, 1e-9 * picture) << "frame " << k;
      EXPECT_EQ(d.energy(), r.energy);
      if (k == 1) {
        EXPECT_LT(r.energy, moved) << "the clusters followed the targets";
      }
    }
  }
}

TEST(DragPreview, HandlesShowTheirTargetsAndTheFullResolutionReachesTheMinimum) {
  const PosedSpot spot;
  const double diagonal = bounding_box_diagonal(spot.mesh);
  Deformer d(spot.mesh, PrismParameters{}, spot.handles, spot.forces);
  const SolveOptions frame = hierarchical(1, 0.0);
  for (int k = 1; k <= 20; ++k) {
    spot.place(d, k / 20.0);
    d.preview(frame);
  }
  ASSERT_TRUE(d.previewing());
  // What each handle prescribes is on screen: the fixed feet, the position-only handle's
  // pinned centre, the orientation-only head's turn.
  const std::vector<RigidTransform> motions = d.face_motions();
  for (int f : spot.handles[0].faces) {
    EXPECT_LT((motions[size_t(f)].rotation - Mat3::Identity()).norm(), 1e-12);
    EXPECT_LT(motions[size_t(f)].translation.norm(), 1e-12);
  }
  const Mat3 head_turn = d.handles()[1].transform.rotation;
  for (int f : spot.handles[1].faces) EXPECT_LT((motions[size_t(f)].rotation - head_turn).norm(), 1e-12);
  // The preview is near the full resolution's minimum for the same targets...
  Deformer reference(spot.mesh, PrismParameters{}, spot.handles, spot.forces);
  spot.place(reference, 1.0);
  SolveOptions exact;
  exact.tolerance = 1e-11;
  ASSERT_TRUE(reference.solve(exact).converged);
  const double lag = largest_point_distance(d.vertex_positions(), reference.vertex_positions()) / diagonal;
  std::cout << "[ metric   ] spot's preview: " << 100 * lag << "% of the diagonal from the minimum, "
            << "energy " << d.energy() << " against " << reference.energy() << "\n";
  // Clusters of 8 of Spot's 2,900 quads: a coarse model (the bench measures big meshes).
  EXPECT_LT(lag, 0.1);
  // ... and solving on from it reaches that minimum.
  const SolveReport on = d.solve(hierarchical(2000, 1e-10));
  EXPECT_FALSE(d.previewing());
  EXPECT_TRUE(on.converged);
  EXPECT_LT(on.energy, reference.energy() * (1 + 1e-6));
  EXPECT_LT(largest_point_distance(d.vertex_positions(), reference.vertex_positions()), 1e-4 * diagonal);
}

TEST(DragPreview, TheSameBitsOnAnyNumberOfThreadsAndAfterAMove) {
  const PosedSpot spot;
  auto drag = [&](int threads) {
    set_thread_count(threads);
    Deformer d(spot.mesh, PrismParameters{}, spot.handles, spot.forces);
    for (int k = 1; k <= 12; ++k) {
      spot.place(d, k / 12.0);
      d.preview(hierarchical(1, 0.0));
    }
    const std::vector<Vec3> shown = d.vertex_positions();
    Deformer moved = std::move(d);  // carries the picture into its state
    EXPECT_FALSE(moved.previewing());
    EXPECT_LT(largest_point_distance(moved.vertex_positions(), shown), 1e-12);
    return shown;
  };
  const std::vector<Vec3> one = drag(1);
  for (int threads : {2, 3, 8}) EXPECT_EQ(largest_point_distance(drag(threads), one), 0.0) << threads;
  set_thread_count(0);
}

TEST(DragPreview, SettingTheStateEndsItAndOtherMethodsSolveInstead) {
  const PosedSpot spot;
  Deformer d(spot.mesh, PrismParameters{}, spot.handles, spot.forces);
  spot.place(d, 0.5);
  d.preview(hierarchical(1, 0.0));
  ASSERT_TRUE(d.previewing());
  const std::vector<RigidTransform> rest(size_t(spot.mesh.n_faces()), RigidTransform::identity());
  d.set_face_motions(rest);
  EXPECT_FALSE(d.previewing());
  const std::vector<RigidTransform> motions = d.face_motions();
  // Free faces at rest; handles keep what they prescribe.
  const int free_face = faces_where(spot.mesh, [](const Vec3& p) { return p.y() > 0.6; }).front();
  EXPECT_EQ(motions[size_t(free_face)].translation.norm(), 0.0);
  d.preview(hierarchical(1, 0.0));
  d.reset();
  EXPECT_FALSE(d.previewing());

  SolveOptions global;
  global.max_iterations = 1;
  const SolveReport r = d.preview(global);
  EXPECT_FALSE(d.previewing());
  EXPECT_NE(r.stop_reason, "preview");
}
