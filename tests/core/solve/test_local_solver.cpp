// Local shape matching: single matches, the plain sweep, and the planned (packed) sweep.

#include "primo/solve/local_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "primo/mesh/mesh_generators.h"
#include "primo/model/prism_layer.h"

using namespace primo;

namespace {

// A quad cylinder whose faces are grouped into bodies of 3 x 3 faces, as on a coarse level:
// neighbouring bodies share several joints. The bottom ring of bodies is fixed.
struct GroupedCylinder {
  Mesh mesh;
  PrismLayer layer;
  RigidSystem system;
};

GroupedCylinder grouped_cylinder() {
  GroupedCylinder g;
  const int around = 12, rings = 15;
  g.mesh = make_cylinder(0.3, 1.5, around, rings, FaceShape::Quads);
  g.layer = build_prism_layer(g.mesh, PrismParameters{});
  // make_cylinder numbers faces ring by ring.
  std::vector<int> face_body(g.mesh.n_faces());
  for (int f = 0; f < int(face_body.size()); ++f)
    face_body[f] = (f / around / 3) * (around / 3) + (f % around) / 3;
  const int n_bodies = (rings / 3) * (around / 3);
  std::vector<BodyKind> kinds(n_bodies, BodyKind::Free);
  for (int b = 0; b < around / 3; ++b) kinds[b] = BodyKind::Fixed;
  g.system = build_rigid_system(g.layer, face_body, kinds, {});
  return g;
}

// A random pose near rest: every body turned by up to 0.3 rad and moved by up to 0.1.
std::vector<BodyState> random_pose(const RigidSystem& system, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<BodyState> state(system.n_bodies());
  for (int b = 0; b < system.n_bodies(); ++b) {
    state[b].position = system.bodies[b].rest_center;
    if (system.bodies[b].kind == BodyKind::Fixed) continue;
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    state[b].rotation = Eigen::AngleAxisd(0.3 * u(rng), axis).toRotationMatrix();
    state[b].position += 0.1 * Vec3(u(rng), u(rng), u(rng));
  }
  return state;
}

}  // namespace

TEST(LocalSolver, EachMatchLowersTheEnergy) {
  const GroupedCylinder g = grouped_cylinder();
  std::vector<BodyState> state = random_pose(g.system, 1);
  double energy = g.system.energy(state);
  for (int b = 0; b < g.system.n_bodies(); ++b) {
    state[b] = local_match(g.system, state, b);
    const double after = g.system.energy(state);
    EXPECT_LE(after, energy * (1 + 1e-12)) << "body " << b;
    energy = after;
  }
}

TEST(SweepPlan, JointsBetweenTheSameBodiesArePackedIntoOne) {
  const GroupedCylinder g = grouped_cylinder();
  const SweepPlan plan = plan_sweep(g.system);
  // Bodies of 3 x 3 quads touch a neighbour across 3 joints: at least a third fewer entries.
  EXPECT_LE(3 * plan.joints.size(), g.system.body_couplings.size() + 0u);
  for (int b = 0; b < g.system.n_bodies(); ++b)
    for (int k = plan.joint_begin[b]; k < plan.joint_begin[b + 1]; ++k)
      for (int m = k + 1; m < plan.joint_begin[b + 1]; ++m)
        EXPECT_NE(plan.joints[k].other, plan.joints[m].other) << "body " << b;
  // Each coupling side's slot is its body's entry for the coupling's other body, and a body's
  // entries follow the order in which its couplings first reach each neighbour.
  for (int b = 0; b < g.system.n_bodies(); ++b) {
    int next = plan.joint_begin[b];
    for (int k = g.system.coupling_begin[b]; k < g.system.coupling_begin[b + 1]; ++k) {
      const auto [ci, side] = g.system.body_couplings[k];
      const int slot = plan.joint_slot[k];
      ASSERT_GE(slot, plan.joint_begin[b]);
      ASSERT_LT(slot, plan.joint_begin[b + 1]);
      EXPECT_EQ(plan.joints[slot].other, g.system.couplings[ci].body[1 - side]) << "body " << b;
      EXPECT_LE(slot, next) << "body " << b;  // a new neighbour takes the next entry
      if (slot == next) ++next;
    }
    EXPECT_EQ(next, plan.joint_begin[b + 1]) << "body " << b << ": an entry no coupling uses";
  }
}

TEST(SweepPlan, PlannedSweepMatchesThePlainSweep) {
  const GroupedCylinder g = grouped_cylinder();
  std::vector<BodyState> plain = random_pose(g.system, 2), planned = plain;
  SweepPlan plan = plan_sweep(g.system);
  for (int sweep = 0; sweep < 3; ++sweep) {
    local_sweep(g.system, plain);
    planned_sweep(g.system, plan, planned);
  }
  for (int b = 0; b < g.system.n_bodies(); ++b) {
    EXPECT_LT((plain[b].rotation - planned[b].rotation).norm(), 1e-10) << "body " << b;
    EXPECT_LT((plain[b].position - planned[b].position).norm(), 1e-10) << "body " << b;
  }
}

// One free body among fixed ones, turned off its rest pose: its plain match is the rest pose.
// Over-relaxed by r, it turns r times as far, past the rest pose, when that still lowers its
// energy, and stops at the match when it would not.
TEST(SweepPlan, OverRelaxedMatchTurnsFurtherAlongTheSameGeodesic) {
  GroupedCylinder g = grouped_cylinder();
  const int free_body = 5;
  std::vector<BodyKind> kinds(g.system.n_bodies(), BodyKind::Fixed);
  kinds[free_body] = BodyKind::Free;
  std::vector<int> face_body(g.mesh.n_faces());
  for (int b = 0; b < g.system.n_bodies(); ++b)
    for (int f : g.system.bodies[b].faces) face_body[f] = b;
  const RigidSystem system = build_rigid_system(g.layer, face_body, kinds, {});
  const Vec3 axis = Vec3(1.0, 2.0, -0.5).normalized();
  const double angle = 0.1;
  auto turned = [&] {
    std::vector<BodyState> state(system.n_bodies());
    for (int b = 0; b < system.n_bodies(); ++b) state[b].position = system.bodies[b].rest_center;
    state[free_body].rotation = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    return state;
  };
  const SweepPlan plan = plan_sweep(system);
  const double start = system.energy(turned());
  ASSERT_GT(start, 0.0);

  std::vector<BodyState> plain = turned();
  planned_sweep(system, plan, plain, 1.0);
  EXPECT_LT((plain[free_body].rotation - Mat3::Identity()).norm(), 1e-9);
  EXPECT_LT(system.energy(plain), 1e-12 * start);

  std::vector<BodyState> over = turned();
  planned_sweep(system, plan, over, 1.8);
  const Eigen::AngleAxisd result(over[free_body].rotation);
  // 0.8 of the turn on the other side of the rest pose (to third order in the angle).
  EXPECT_NEAR(result.angle(), 0.8 * angle, 1e-3);
  EXPECT_GT(result.axis().dot(-axis), 1.0 - 1e-9);
  EXPECT_LT(system.energy(over), start);

  std::vector<BodyState> too_far = turned();
  planned_sweep(system, plan, too_far, 2.5);  // 1.5 turns past rest: more energy than at start
  EXPECT_LT((too_far[free_body].rotation - Mat3::Identity()).norm(), 1e-9);
}
