// Anderson acceleration of rigid-state iterations.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "primo/solve/anderson_acceleration.h"
#include "primo/util/error.h"
#include "primo/solve/global_solver.h"

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

// The hierarchical solver hands the input over only on the first accelerated cycle and then
// lets the acceleration remember the state it left (its proposal, or the image after a
// refusal): the proposals are those of passing every input, to rounding.
TEST(AndersonAcceleration, RemembersTheStateItLeft) {
  std::vector<BodyState> fixed(3), x(3);
  for (int b = 0; b < 3; ++b) {
    fixed[b].rotation =
        Eigen::AngleAxisd(0.4 * b + 0.2, Vec3(1, b, 2).normalized()).toRotationMatrix();
    fixed[b].position = Vec3(b, 1.0, -b);
    x[b].position = fixed[b].position + Vec3(0.5, -0.3, 0.2);
  }
  auto image_of = [&](const std::vector<BodyState>& s) {
    std::vector<BodyState> y = contract(s, fixed);
    for (size_t b = 0; b < s.size(); ++b)  // a slow turn towards the fixed rotation
    {
      const Eigen::AngleAxisd rest(Mat3(fixed[b].rotation * s[b].rotation.transpose()));
      y[b].rotation = rotation_from_vector(0.3 * rest.angle() * rest.axis()) * s[b].rotation;
    }
    return y;
  };
  AndersonAcceleration told(4), remembering(4);
  EXPECT_FALSE(remembering.knows_input());
  std::vector<BodyState> proposal_told, proposal_remembered, y = x;
  for (int step = 0; step < 10; ++step) {
    const std::vector<BodyState> image = image_of(y);
    const bool a = told.propose(&y, image, proposal_told);
    const bool b = remembering.propose(step == 0 ? &y : nullptr, image, proposal_remembered);
    ASSERT_EQ(a, b);
    EXPECT_TRUE(remembering.knows_input());
    // Every third proposal is refused: the caller goes on from the image.
    const bool refuse = step % 3 == 2;
    if (a && refuse) {
      told.refuse();
      remembering.refuse();
    }
    for (size_t k = 0; k < y.size(); ++k) {
      if (!a) continue;
      EXPECT_LT((proposal_told[k].rotation - proposal_remembered[k].rotation).norm(), 1e-12);
      EXPECT_LT((proposal_told[k].position - proposal_remembered[k].position).norm(), 1e-12);
    }
    y = a && !refuse ? proposal_told : image;
  }
  remembering.reset();
  EXPECT_FALSE(remembering.knows_input());
  EXPECT_THROW(remembering.propose(nullptr, y, proposal_remembered), Error);
}
