// Global Newton matching's reuse of factorizations: how long a factor serves, refreshing it
// on a background thread, turning a reused factor with the bodies, and a reused step's
// gradient.

#include "primo/solve/global_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "primo/solve/deformer.h"
#include "primo/util/parallel.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::max_difference;

namespace {

// A quad cylinder (16 x 24 unless given) bent 90 degrees between its fixed bottom and top
// bands.
Deformer bent_cylinder(int segments = 16, int bands = 24) {
  const test::BentCylinder c = test::bent_cylinder(segments, bands, 90.0);
  return Deformer(c.mesh, PrismParameters{}, c.handles);
}

// Runs `steps` reusing iterations; returns the final state.
std::vector<BodyState> reusing_run(const RigidSystem& system, std::vector<BodyState> state, int steps,
                                   int max_reuse, int lag, GlobalSolverTimings* timings) {
  GlobalSolver solver(system, GlobalSolver::Factorization::SupernodalOneThread);
  solver.set_factor_reuse(max_reuse, lag);
  double energy = system.energy(state);
  for (int k = 0; k < steps; ++k) {
    const GlobalStep step = solver.iterate(state, false, true);
    EXPECT_TRUE(step.decreased) << "step " << k;
    EXPECT_LT(step.energy_after, energy) << "step " << k;
    energy = step.energy_after;
  }
  *timings = solver.timings();
  return state;
}

}  // namespace

TEST(GlobalSolver, AFactorServesAtMostItsStepsAndThenAFreshOneIsMade) {
  Deformer d = bent_cylinder();
  GlobalSolverTimings t;
  reusing_run(d.system(), d.body_states(), 12, 3, 0, &t);
  EXPECT_EQ(t.factorizations, 3);  // steps 1, 5 and 9 make one; the others reuse it
  EXPECT_EQ(t.background_factorizations, 0);
}

TEST(GlobalSolver, BackgroundRefreshesDescendAndDoNotDependOnTiming) {
  Deformer d = bent_cylinder();
  Deformer reference = bent_cylinder();
  SolveOptions exact;
  exact.tolerance = 1e-12;
  exact.max_iterations = 200;
  const double minimum = reference.solve(exact).energy;

  GlobalSolverTimings first, second;
  const std::vector<BodyState> a = reusing_run(d.system(), d.body_states(), 30, 3, 2, &first);
  const std::vector<BodyState> b = reusing_run(d.system(), d.body_states(), 30, 3, 2, &second);
  EXPECT_EQ(first.factorizations, 1);  // only the first one is made in the foreground
  EXPECT_EQ(first.background_factorizations, 4);  // one started every 6 steps; the fifth still runs
  EXPECT_EQ(first.background_factorizations, second.background_factorizations);
  // The threads finish at different times in the two runs; the factors take over at the same
  // steps, so the iterates are the same to the last bit.
  EXPECT_EQ(max_difference(a, b), 0.0);
  EXPECT_LT(d.system().energy(a), minimum * (1 + 1e-6));
}

TEST(GlobalSolver, AReusedFactorTurnsWithTheBodies) {
  // A state part way to the minimum, and the same state turned as a whole: the problem is the
  // same up to the turn, so a factor made before the turn, turned with the bodies, must give
  // the fresh Newton step of the turned state.
  Deformer d = bent_cylinder();
  const RigidSystem& system = d.system();
  std::vector<BodyState> before = d.body_states();
  {
    GlobalSolver warm(system);
    for (int k = 0; k < 3; ++k) warm.iterate(before, false);
  }
  const Mat3 turn = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<BodyState> turned = before;
  for (BodyState& s : turned) s = {turn * s.rotation, turn * s.position};
  ASSERT_NEAR(system.energy(turned), system.energy(before), 1e-12 * system.energy(before));

  std::vector<Mat3> frames(system.n_bodies(), Mat3::Identity());
  GlobalSolver reused(system, GlobalSolver::Factorization::SupernodalOneThread);
  reused.set_body_frames(&frames);
  std::vector<BodyState> scratch = before;
  reused.iterate(scratch, false);  // the factor of `before`
  for (Mat3& f : frames) f = turn;
  std::vector<BodyState> from_reused = turned;
  const GlobalStep step = reused.iterate(from_reused, false, true);
  ASSERT_TRUE(step.reused_factorization);

  GlobalSolver fresh(system, GlobalSolver::Factorization::SupernodalOneThread);
  std::vector<BodyState> from_fresh = turned;
  fresh.iterate(from_fresh, false);
  EXPECT_LT(max_difference(from_reused, from_fresh), 1e-9);

  // Without the frames the old factor is applied unturned: a different, worse step.
  GlobalSolver unturned(system, GlobalSolver::Factorization::SupernodalOneThread);
  scratch = before;
  unturned.iterate(scratch, false);
  std::vector<BodyState> from_unturned = turned;
  unturned.iterate(from_unturned, false, true);
  EXPECT_GT(max_difference(from_unturned, from_fresh), 1e-4);
  EXPECT_GT(system.energy(from_unturned), system.energy(from_fresh));
}

TEST(GlobalSolver, AReusedStepsGradientInChunksIsTheFullAssemblysGradient) {
  // Above two grains of couplings the gradient of a reused step is summed in chunks.
  // Reusing the factor of the very state it starts from, the step must be the fresh one,
  // whose gradient comes from the one-thread full assembly.
  Deformer d = bent_cylinder(100, 104);
  const RigidSystem& system = d.system();
  ASSERT_GE(system.couplings.size(), 2 * kParallelGrain);
  const std::vector<BodyState> start = d.body_states();

  GlobalSolver reused(system, GlobalSolver::Factorization::SupernodalOneThread);
  std::vector<BodyState> scratch = start;
  reused.iterate(scratch, false);  // the factor of `start`
  std::vector<BodyState> from_reused = start;
  ASSERT_TRUE(reused.iterate(from_reused, false, true).reused_factorization);

  GlobalSolver fresh(system, GlobalSolver::Factorization::SupernodalOneThread);
  std::vector<BodyState> from_fresh = start;
  fresh.iterate(from_fresh, false);
  EXPECT_GT(max_difference(from_fresh, start), 1e-3);
  EXPECT_LT(max_difference(from_reused, from_fresh), 1e-9);
}

TEST(GlobalSolver, AReusedFactorsStepIsHalvedOnlyAsOftenAsAllowed) {
  // From the bent cylinder's start, far from its minimum, a factor kept for every step soon
  // gives steps that overshoot. With the default halvings such a step is cut and the factor
  // kept; allowed none (a drag's frame, HierarchicalSolver), a fresh factor makes it instead.
  Deformer d = bent_cylinder();
  const RigidSystem& system = d.system();
  auto run = [&](int halvings, std::vector<GlobalStep>& steps, std::vector<int>& factorizations) {
    GlobalSolver solver(system, GlobalSolver::Factorization::SupernodalOneThread);
    solver.set_factor_reuse(1000, 0, halvings);
    std::vector<BodyState> state = d.body_states();
    for (int k = 0; k < 12; ++k) {
      steps.push_back(solver.iterate(state, false, true));
      factorizations.push_back(solver.timings().factorizations);
    }
  };
  std::vector<GlobalStep> cut, whole;
  std::vector<int> cut_factorizations, whole_factorizations;
  run(GlobalSolver::kReusedStepHalvings, cut, cut_factorizations);
  run(0, whole, whole_factorizations);

  size_t first_cut = 0;
  while (first_cut < cut.size() &&
         !(cut[first_cut].reused_factorization && cut[first_cut].step_scale < 1.0))
    ++first_cut;
  ASSERT_LT(first_cut, cut.size()) << "no reused step was halved";
  EXPECT_EQ(cut_factorizations[first_cut], 1);  // the first step's factor, still in use
  for (size_t k = 0; k < first_cut; ++k) {
    EXPECT_EQ(whole[k].energy_after, cut[k].energy_after) << "step " << k;
    EXPECT_TRUE(whole[k].reused_factorization || k == 0) << "step " << k;
  }
  const GlobalStep& fresh = whole[first_cut];
  EXPECT_FALSE(fresh.reused_factorization);
  EXPECT_EQ(whole_factorizations[first_cut], 2);
  EXPECT_TRUE(fresh.decreased);
  EXPECT_LT(fresh.energy_after, cut[first_cut].energy_after);
  for (const GlobalStep& s : whole) {
    if (s.reused_factorization) {
      EXPECT_EQ(s.step_scale, 1.0);
    }
  }
}
