#include "primo/horn.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

using namespace primo;

namespace {

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

}  // namespace

TEST(Horn, RecoversAKnownRotationExactly) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const Mat3 R = random_rotation(rng);
    Mat3 S = Mat3::Zero();
    for (int k = 0; k < 6; ++k) {
      const Vec3 s(d(rng), d(rng), d(rng));
      S += (0.5 + k) * s * (R * s).transpose();
    }
    EXPECT_LT((horn_rotation(S) - R).norm(), 1e-12);
  }
}

TEST(Horn, ReturnsAProperRotationForReflectedData) {
  // Targets are a mirror image: the best proper rotation, never a reflection.
  Mat3 S = Mat3::Zero();
  const Mat3 mirror = Vec3(1, 1, -1).asDiagonal();
  for (const Vec3& s : {Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 3), Vec3(1, 1, 1)})
    S += s * (mirror * s).transpose();
  const Mat3 R = horn_rotation(S);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  EXPECT_LT((R * R.transpose() - Mat3::Identity()).norm(), 1e-12);
}

TEST(Horn, ZeroCovarianceKeepsThePrior) {
  std::mt19937 rng(5);
  const Mat3 prior = random_rotation(rng);
  EXPECT_LT((horn_rotation(Mat3::Zero(), prior) - prior).norm(), 1e-15);
}
