#include "primo/horn.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
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

namespace {

// Reference: Horn's method with a general symmetric eigensolver.
Mat3 horn_by_eigensolver(const Mat3& S) {
  Eigen::Matrix4d N;
  const Mat3& s = S;
  N << s(0, 0) + s(1, 1) + s(2, 2), s(1, 2) - s(2, 1), s(2, 0) - s(0, 2), s(0, 1) - s(1, 0),
      s(1, 2) - s(2, 1), s(0, 0) - s(1, 1) - s(2, 2), s(0, 1) + s(1, 0), s(2, 0) + s(0, 2),
      s(2, 0) - s(0, 2), s(0, 1) + s(1, 0), -s(0, 0) + s(1, 1) - s(2, 2), s(1, 2) + s(2, 1),
      s(0, 1) - s(1, 0), s(2, 0) + s(0, 2), s(1, 2) + s(2, 1), -s(0, 0) - s(1, 1) + s(2, 2);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(N);
  const Eigen::Vector4d q = eig.eigenvectors().col(3);
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

}  // namespace

TEST(Horn, MatchesTheEigensolverOnRandomCovariances) {
  std::mt19937 rng(21);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 2000; ++trial) {
    Mat3 S;
    for (int i = 0; i < 9; ++i) S.data()[i] = n(rng) * std::pow(10.0, trial % 7 - 3);
    const Mat3 fast = horn_rotation(S), reference = horn_by_eigensolver(S);
    // Both maximize trace(R S); compare the attained maxima (robust to ties) and the rotations.
    EXPECT_NEAR((fast * S).trace(), (reference * S).trace(), 1e-10 * S.norm());
    EXPECT_LT((fast - reference).norm(), 1e-6) << S;
  }
}

TEST(Horn, HandlesRankDeficientCovariances) {
  // Points on a line (rank 1) or in a plane (rank 2): the result is still a rotation that
  // attains the maximum of trace(R S).
  std::mt19937 rng(8);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 a(n(rng), n(rng), n(rng)), b(n(rng), n(rng), n(rng));
    const Vec3 c(n(rng), n(rng), n(rng)), d(n(rng), n(rng), n(rng));
    const Mat3 S = trial % 2 ? Mat3(a * b.transpose()) : Mat3(a * b.transpose() + c * d.transpose());
    const Mat3 R = horn_rotation(S);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
    EXPECT_LT((R * R.transpose() - Mat3::Identity()).norm(), 1e-9);
    EXPECT_NEAR((R * S).trace(), (horn_by_eigensolver(S) * S).trace(), 1e-9 * S.norm());
  }
}
