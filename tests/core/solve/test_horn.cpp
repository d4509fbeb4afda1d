#include "primo/solve/horn.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

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

namespace {

// The largest eigenvalue of Horn's N, i.e. max over rotations of trace(R S), by the
// symmetric eigensolver.
double max_trace(const Mat3& s) {
  Eigen::Matrix4d N;
  N << s(0, 0) + s(1, 1) + s(2, 2), s(1, 2) - s(2, 1), s(2, 0) - s(0, 2), s(0, 1) - s(1, 0),
      s(1, 2) - s(2, 1), s(0, 0) - s(1, 1) - s(2, 2), s(0, 1) + s(1, 0), s(2, 0) + s(0, 2),
      s(2, 0) - s(0, 2), s(0, 1) + s(1, 0), -s(0, 0) + s(1, 1) - s(2, 2), s(1, 2) + s(2, 1),
      s(0, 1) - s(1, 0), s(2, 0) + s(0, 2), s(1, 2) + s(2, 1), -s(0, 0) - s(1, 1) + s(2, 2);
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(N, Eigen::EigenvaluesOnly).eigenvalues()[3];
}

// R is a proper rotation attaining the maximum of trace(R S) (to `relative` of |S|).
void expect_maximizer(const Mat3& S, const Mat3& R, double relative = 1e-12) {
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12) << S;
  EXPECT_LT((R * R.transpose() - Mat3::Identity()).norm(), 1e-12) << S;
  EXPECT_NEAR((R * S).trace(), max_trace(S), relative * S.norm()) << S;
}

// A local shape-matching covariance: 3..12 weighted point pairs on the sides of a thin prism
// (spread in a plane, small height), centred, with targets a rotated and slightly deformed copy.
Mat3 prism_covariance(std::mt19937& rng, const Mat3& R, int points) {
  std::uniform_real_distribution<double> u(-1, 1), w(0.2, 2.0);
  std::normal_distribution<double> n;
  std::vector<Vec3> source;
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < points; ++k) {
    source.emplace_back(u(rng), u(rng), k % 2 ? 0.05 : -0.05);
    mean += source.back();
  }
  mean /= points;
  Mat3 S = Mat3::Zero();
  for (const Vec3& s : source) {
    const Vec3 c = s - mean;
    S += w(rng) * c * (R * c + 0.02 * Vec3(n(rng), n(rng), n(rng))).transpose();
  }
  return S;
}

Mat3 rotation_by(std::mt19937& rng, double max_degrees) {
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> angle(0.0, max_degrees * M_PI / 180.0);
  return Eigen::AngleAxisd(angle(rng), Vec3(n(rng), n(rng), n(rng)).normalized()).toRotationMatrix();
}

}  // namespace

TEST(Horn, WarmStartAtTheAnswerReturnsTheAnswer) {
  // At convergence of a sweep the prior is the maximizer itself.
  std::mt19937 rng(31);
  for (int trial = 0; trial < 500; ++trial) {
    const Mat3 S = prism_covariance(rng, random_rotation(rng), 3 + trial % 10);
    const Mat3 answer = horn_by_eigensolver(S);
    const Mat3 R = horn_rotation(S, answer);
    expect_maximizer(S, R);
    EXPECT_LT((R - answer).norm(), 1e-10) << S;
    // And again from its own result (a converged sweep calls it with the same S).
    EXPECT_LT((horn_rotation(S, R) - R).norm(), 1e-12) << S;
  }
}

TEST(Horn, PriorsNearAndFarFromTheAnswerGiveTheSameMaximizer) {
  std::mt19937 rng(32);
  for (int trial = 0; trial < 500; ++trial) {
    const Mat3 S = prism_covariance(rng, random_rotation(rng), 3 + trial % 10);
    const Mat3 answer = horn_by_eigensolver(S);
    const Mat3 half_turn = Eigen::AngleAxisd(M_PI, answer.col(trial % 3)).toRotationMatrix();
    for (const Mat3& prior :
         {Mat3(rotation_by(rng, 5.0) * answer), Mat3(rotation_by(rng, 45.0) * answer),
          Mat3(half_turn * answer), random_rotation(rng), Mat3(Mat3::Identity())}) {
      const Mat3 R = horn_rotation(S, prior);
      expect_maximizer(S, R);
      EXPECT_LT((R - answer).norm(), 1e-9) << S << "\nprior\n" << prior;
    }
  }
}

TEST(Horn, PriorIsOnlyAHint) {
  // Not even a rotation: the result is still the maximizer.
  std::mt19937 rng(33);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 300; ++trial) {
    const Mat3 S = prism_covariance(rng, random_rotation(rng), 6);
    Mat3 garbage;
    for (int i = 0; i < 9; ++i) garbage.data()[i] = 10.0 * n(rng);
    for (const Mat3& prior : {garbage, Mat3(Mat3::Zero()), Mat3(-Mat3::Identity()),
                              Mat3(3.0 * horn_by_eigensolver(S))}) {
      const Mat3 R = horn_rotation(S, prior);
      expect_maximizer(S, R);
      EXPECT_LT((R - horn_by_eigensolver(S)).norm(), 1e-9) << S;
    }
  }
}

TEST(Horn, ReflectedDataFromAnyPrior) {
  std::mt19937 rng(34);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 300; ++trial) {
    // A mirrored, rotated copy: det S < 0, the best proper rotation is not a mirror.
    const Mat3 mirror = Vec3(1, 1, -1).asDiagonal();
    const Mat3 Q = random_rotation(rng);
    Mat3 S = Mat3::Zero();
    for (int k = 0; k < 5; ++k) {
      const Vec3 s(n(rng), n(rng), n(rng));
      S += s * (Q * mirror * s).transpose();
    }
    ASSERT_LT(S.determinant(), 0.0);
    const Mat3 answer = horn_by_eigensolver(S);
    for (const Mat3& prior : {Mat3(Mat3::Identity()), answer, Mat3(rotation_by(rng, 5) * answer),
                              Mat3(Q * mirror * -1.0), random_rotation(rng)}) {
      const Mat3 R = horn_rotation(S, prior);
      expect_maximizer(S, R);
      EXPECT_LT((R - answer).norm(), 1e-9) << S;
    }
  }
}

TEST(Horn, RankDeficientCovariancesFromAnyPrior) {
  std::mt19937 rng(35);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 a(n(rng), n(rng), n(rng)), b(n(rng), n(rng), n(rng));
    const Vec3 c(n(rng), n(rng), n(rng)), d(n(rng), n(rng), n(rng));
    const bool rank1 = trial % 2;
    const Mat3 S = rank1 ? Mat3(a * b.transpose()) : Mat3(a * b.transpose() + c * d.transpose());
    const Mat3 answer = horn_by_eigensolver(S);
    for (const Mat3& prior : {Mat3(Mat3::Identity()), answer, random_rotation(rng)}) {
      const Mat3 R = horn_rotation(S, prior);
      expect_maximizer(S, R);
      // Rank 1: the top eigenvalue is double and the maximizer is not unique. Rank 2: unique.
      if (!rank1) {
        EXPECT_LT((R - answer).norm(), 1e-9) << S;
      }
    }
  }
}

TEST(Horn, RepeatedTopEigenvalues) {
  // The top eigenvalue s1 + s2 + sign(det S) s3 of N is repeated when s2 = s3 and det S < 0
  // (double, e.g. diag(3, 1, -1)), when S is a negative multiple of a rotation (triple), and
  // for rank 1 (double). The maximizer is then not unique: check the attained maximum.
  std::mt19937 rng(36);
  const std::vector<Vec3> singular = {Vec3(3, 1, -1),  Vec3(1, 1, -1),   Vec3(-1, -1, -1),
                                      Vec3(2, 0, 0),   Vec3(5, 2, -2),   Vec3(1, 1e-9, -1e-9),
                                      Vec3(3, 1, -(1 - 1e-9)), Vec3(3, 1, -(1 - 1e-6)),
                                      Vec3(1, 1, 1),   Vec3(2, 2, 0),    Vec3(1, 1, 1e-9)};
  for (const Vec3& sigma : singular)
    for (int trial = 0; trial < 40; ++trial) {
      const Mat3 U = trial ? random_rotation(rng) : Mat3(Mat3::Identity());
      const Mat3 V = trial ? random_rotation(rng) : Mat3(Mat3::Identity());
      const Mat3 S = U * sigma.asDiagonal() * V.transpose();
      for (const Mat3& prior : {Mat3(Mat3::Identity()), horn_by_eigensolver(S), random_rotation(rng)})
        expect_maximizer(S, horn_rotation(S, prior));
    }
  // Multiples of the identity.
  for (const double c : {1.0, -1.0, 1e-3, -7.5})
    for (const Mat3& prior : {Mat3(Mat3::Identity()), random_rotation(rng)}) {
      const Mat3 S = c * Mat3::Identity();
      const Mat3 R = horn_rotation(S, prior);
      expect_maximizer(S, R);
      if (c > 0) {
        EXPECT_LT((R - Mat3::Identity()).norm(), 1e-12);
      }
    }
}

TEST(Horn, HugeAndTinyScales) {
  // trace(R S) is homogeneous in S: the maximizer does not depend on the scale, even where
  // |S|^4 (the characteristic polynomial) or |S|^6 would over- or underflow.
  std::mt19937 rng(37);
  for (int trial = 0; trial < 100; ++trial) {
    const Mat3 S = prism_covariance(rng, random_rotation(rng), 3 + trial % 10);
    const Mat3 prior = trial % 2 ? Mat3(Mat3::Identity()) : horn_by_eigensolver(S);
    const Mat3 unit = horn_rotation(S, prior);
    expect_maximizer(S, unit);
    for (const double scale : {1e-310, 1e-300, 1e-200, 1e-150, 1e-80, 1e-40, 1e-20, 1e20, 1e40,
                               1e80, 1e150, 1e200, 1e300}) {
      const Mat3 scaled = S * scale;
      const Mat3 R = horn_rotation(scaled, prior);
      EXPECT_LT((R - unit).norm(), 1e-9) << "scale " << scale;
      EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    }
  }
  // A single nonzero subnormal entry: rank 1, still a rotation.
  Mat3 S = Mat3::Zero();
  S(0, 1) = 4.9e-324;
  const Mat3 R = horn_rotation(S);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  EXPECT_GT(R(1, 0), 1.0 - 1e-12);  // maps x onto y: trace(R S) = R(1,0) S(0,1)
}

TEST(Horn, MatchesTheEigensolverOnRandomCovariancesFromRandomPriors) {
  std::mt19937 rng(38);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 3000; ++trial) {
    Mat3 S;
    for (int i = 0; i < 9; ++i) S.data()[i] = n(rng) * std::pow(10.0, trial % 9 - 4);
    const Mat3 reference = horn_by_eigensolver(S);
    const Mat3 prior = trial % 3 == 0   ? random_rotation(rng)
                       : trial % 3 == 1 ? Mat3(rotation_by(rng, 5.0) * reference)
                                        : reference;
    const Mat3 R = horn_rotation(S, prior);
    expect_maximizer(S, R);
    EXPECT_LT((R - reference).norm(), 1e-6) << S;
  }
}
