// One coupling standing for all the couplings between two bodies (the hierarchy's coarsest
// level).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "primo/solve/coupling_moments.h"
#include "primo/solve/global_solver.h"

using namespace primo;

namespace {

Vec3 random_vector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

PatchModes random_modes(std::mt19937& rng) {
  return {random_vector(rng, 2.0), random_vector(rng, 0.5), random_vector(rng, 0.3),
          random_vector(rng, 0.1)};
}

BodyState random_state(std::mt19937& rng) {
  return {rotation_from_vector(random_vector(rng, 1.5)), random_vector(rng, 1.0)};
}

// Two bodies coupled by `couplings` (bodies 0 and 1), and the system of their merged coupling.
RigidSystem two_bodies(const std::vector<RigidSystem::Coupling>& couplings) {
  RigidSystem sys;
  sys.bodies.resize(2);
  sys.couplings = couplings;
  index_couplings(sys);
  return sys;
}

RigidSystem::Coupling coupling(const PatchModes& a, const PatchModes& b, double w) {
  RigidSystem::Coupling c;
  c.body[0] = 0;
  c.body[1] = 1;
  c.weight = w;
  c.local[0] = a;
  c.local[1] = b;
  c.update_cross();
  return c;
}

}  // namespace

TEST(CouplingMoments, OneCouplingHasTheEnergyOfManyUpToTheConstantItReturns) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<RigidSystem::Coupling> couplings;
    CouplingMoments moments;
    const int count = 1 + trial % 6;
    for (int k = 0; k < count; ++k) {
      const PatchModes a = random_modes(rng), b = random_modes(rng);
      const double w = 0.1 + double(k);
      couplings.push_back(coupling(a, b, w));
      moments.add(a, b, w);
    }
    RigidSystem::Coupling merged = coupling({}, {}, 0.0);
    const double shortfall = moments.write(merged);
    const RigidSystem many = two_bodies(couplings), one = two_bodies({merged});
    for (int s = 0; s < 10; ++s) {
      const std::vector<BodyState> state = {random_state(rng), random_state(rng)};
      const double e_many = many.energy(state);
      EXPECT_NEAR(one.energy(state) + shortfall, e_many, 1e-11 * (1.0 + e_many));
    }
    // The cross moments follow the modes.
    const Mat3 cross = merged.cross;
    merged.update_cross();
    EXPECT_LT((merged.cross - cross).norm(), 1e-12 * (1.0 + cross.norm()));
  }
}

// Where the joints are closed (each coupling's two sides the same points where the bodies
// are), the merged coupling's are closed too: its residuals, hence its Gauss-Newton Hessian's
// departure from the exact one, are those of the joints. The bodies' frames are turned alike,
// as a coarse level's clusters' are when it is restricted (their corrections start unturned).
TEST(CouplingMoments, ClosedJointsMakeAClosedCoupling) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 turn = rotation_from_vector(random_vector(rng, 1.5));
    const std::vector<BodyState> placed = {{turn, random_vector(rng, 1.0)},
                                           {turn, random_vector(rng, 1.0)}};
    CouplingMoments moments;
    std::vector<RigidSystem::Coupling> couplings;
    const int count = 1 + trial % 5;
    for (int k = 0; k < count; ++k) {
      // World modes, seen from each body.
      const PatchModes world = random_modes(rng);
      auto seen_from = [&](const BodyState& s) {
        const Mat3 back = s.rotation.transpose();
        return PatchModes{back * (world.mean - s.position), back * world.du, back * world.dv,
                          back * world.duv};
      };
      const PatchModes a = seen_from(placed[0]), b = seen_from(placed[1]);
      couplings.push_back(coupling(a, b, 1.0 + k));
      moments.add(a, b, 1.0 + k);
    }
    RigidSystem::Coupling merged = coupling({}, {}, 0.0);
    const double shortfall = moments.write(merged);
    const RigidSystem one = two_bodies({merged});
    EXPECT_NEAR(two_bodies(couplings).energy(placed), 0.0, 1e-12);
    EXPECT_NEAR(one.energy(placed), 0.0, 1e-10) << count << " couplings";
    EXPECT_NEAR(shortfall, 0.0, 1e-10);
  }
}

TEST(CouplingMoments, NoCouplingsWriteAWeightlessOne) {
  RigidSystem::Coupling merged =
      coupling(PatchModes{Vec3::Ones(), Vec3::Ones(), Vec3::Ones(), Vec3::Ones()},
               PatchModes{Vec3::Ones(), Vec3::Ones(), Vec3::Ones(), Vec3::Ones()}, 1.0);
  EXPECT_EQ(CouplingMoments().write(merged), 0.0);
  EXPECT_EQ(merged.weight, 0.0);
  EXPECT_EQ(two_bodies({merged}).energy({BodyState{}, BodyState{}}), 0.0);
}

TEST(CouplingMoments, AddingAMovedCouplingIsAddingItsMovedModes) {
  std::mt19937 rng(5);
  auto moved = [](const PatchModes& m, const BodyState& s) {
    return PatchModes{s.rotation * m.mean + s.position, s.rotation * m.du, s.rotation * m.dv,
                      s.rotation * m.duv};
  };
  for (int trial = 0; trial < 10; ++trial) {
    CouplingMoments by_modes, by_cross;
    for (int k = 0; k < 3; ++k) {
      const RigidSystem::Coupling c = coupling(random_modes(rng), random_modes(rng), 0.5 + k);
      const BodyState s0 = random_state(rng), s1 = random_state(rng);
      const bool turned = (trial + k) % 2 == 1;
      by_cross.add_moved(OrientedCoupling::of(c, turned), s0.rotation, s0.position, s1.rotation,
                         s1.position);
      by_cross.trace += vector_mode_trace(c);
      by_modes.add(moved(c.local[turned ? 1 : 0], s0), moved(c.local[turned ? 0 : 1], s1),
                   c.weight);
    }
    EXPECT_NEAR(by_cross.weight, by_modes.weight, 1e-12);
    EXPECT_NEAR(by_cross.trace, by_modes.trace, 1e-10 * by_modes.trace);
    EXPECT_LT((by_cross.sum0 - by_modes.sum0).norm(), 1e-10);
    EXPECT_LT((by_cross.sum1 - by_modes.sum1).norm(), 1e-10);
    EXPECT_LT((by_cross.cross - by_modes.cross).norm(), 1e-10 * by_modes.cross.norm());
  }
}
