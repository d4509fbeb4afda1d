// Anderson acceleration of rigid-state iterations.

#include "primo/anderson_acceleration.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "primo/global_solver.h"

using namespace primo;

namespace {

// A linear contraction towards `fixed` in the embedding, slow along one direction:
// plain iteration needs hundreds of steps, Anderson a handful.
std::vector<BodyState> contract(const std::vector<BodyState>& x, const std::vector<BodyState>& fixed) {
  std::vector<BodyState> y = x;
  for (size_t b = 0; b < x.size(); ++b) {
    const Vec3 d = x[b].position - fixed[b].position;
    y[b].position = fixed[b].position + Vec3(0.99 * d.x(), 0.5 * d.y(), 0.2 * d.z());
  }
  return y;
}

}  // namespace

TEST(AndersonAcceleration, SolvesASlowLinearIterationInAFewSteps) {
  std::vector<BodyState> fixed(4), x(4);
  for (int b = 0; b < 4; ++b) {
    fixed[b].position = Vec3(b, 2.0 * b, -b);
    x[b].position = fixed[b].position + Vec3(1.0, -1.0, 0.5);
  }
  AndersonAcceleration aa(5);
  int steps = 0;
  double error = 1.0;
  for (; steps < 50 && error > 1e-10; ++steps) {
    const std::vector<BodyState> image = contract(x, fixed);
    x = aa.propose(x, image);
    error = 0.0;
    for (int b = 0; b < 4; ++b) error = std::max(error, (x[b].position - fixed[b].position).norm());
  }
  EXPECT_LE(steps, 8);  // plain iteration: 0.99^n < 1e-10 needs n > 2,290
  EXPECT_LT(error, 1e-10);
}

TEST(AndersonAcceleration, KeepsRotationsProperAndUnchangedBodiesExact) {
  // Body 0 never moves (a fixed handle), body 1 turns a little every step.
  std::vector<BodyState> x(2);
  x[0].rotation = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  x[0].position = Vec3(0.1, 0.2, 0.3);
  AndersonAcceleration aa(3);
  for (int step = 0; step < 6; ++step) {
    std::vector<BodyState> image = x;
    image[1].rotation = rotation_from_vector(Vec3(0.05, 0.02 * step, 0.01)) * x[1].rotation;
    image[1].position += Vec3(0.01, 0.0, -0.02);
    const std::vector<BodyState> next = aa.propose(x, image);
    EXPECT_EQ(next[0].rotation, x[0].rotation);
    EXPECT_EQ(next[0].position, x[0].position);
    const Mat3& r = next[1].rotation;
    EXPECT_LT((r.transpose() * r - Mat3::Identity()).norm(), 1e-12);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    x = next;
  }
  EXPECT_EQ(aa.stored(), 3);
  aa.reset();
  EXPECT_EQ(aa.stored(), 0);
}

// A slow, oscillating contraction of a turn about z towards just over 180 degrees, while a
// second body contracts the same way in position: every image crosses the half turn, where the
// quaternions cross w = 0 and a fixed sign convention would jump. The embedding keeps each
// body's sign on the side of its last one, so one combination serves both bodies and the
// iteration converges in a few steps.
TEST(AndersonAcceleration, ConvergesThroughAHalfTurn) {
  const double target = M_PI + 0.01;
  const Vec3 rest(1.0, 2.0, 3.0);
  auto turn = [](double angle) {
    return Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
  };
  auto angle_of = [](const Mat3& r) {
    const double a = std::atan2(r(1, 0), r(0, 0));
    return a < 0 ? a + 2 * M_PI : a;
  };
  std::vector<BodyState> x(2);
  x[0].rotation = turn(M_PI - 0.3);
  x[1].position = rest + Vec3(0.3, -0.2, 0.1);
  AndersonAcceleration aa(5);
  int steps = 0;
  double error = 1.0;
  for (; steps < 40 && error > 1e-9; ++steps) {
    std::vector<BodyState> image = x;
    image[0].rotation = turn(target - 0.95 * (angle_of(x[0].rotation) - target));
    image[1].position = rest - 0.95 * (x[1].position - rest);
    x = aa.propose(x, image);
    error = std::max(std::abs(angle_of(x[0].rotation) - target), (x[1].position - rest).norm());
  }
  EXPECT_LT(error, 1e-9);
  EXPECT_LE(steps, 8);  // plain iteration: 0.95^n < 1e-9 needs n > 400; without the sign
                        // alignment: no convergence in 40
}
