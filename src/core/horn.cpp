#include "primo/horn.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

namespace primo {
namespace {

Mat3 quaternion_rotation(const Eigen::Vector4d& q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

// The 3x3 minor of `m` without row r and column c.
double minor3(const Eigen::Matrix4d& m, int r, int c) {
  int rows[3], cols[3];
  for (int i = 0, k = 0; i < 4; ++i)
    if (i != r) rows[k++] = i;
  for (int j = 0, k = 0; j < 4; ++j)
    if (j != c) cols[k++] = j;
  auto e = [&](int i, int j) { return m(rows[i], cols[j]); };
  return e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1)) -
         e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0)) +
         e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0));
}

}  // namespace

Mat3 horn_rotation(const Mat3& S, const Mat3& prior) {
  const double sxx = S(0, 0), sxy = S(0, 1), sxz = S(0, 2);
  const double syx = S(1, 0), syy = S(1, 1), syz = S(1, 2);
  const double szx = S(2, 0), szy = S(2, 1), szz = S(2, 2);
  const double frobenius2 = S.squaredNorm();
  if (frobenius2 == 0.0) return prior;
  Eigen::Matrix4d N;
  N << sxx + syy + szz, syz - szy, szx - sxz, sxy - syx,  //
      syz - szy, sxx - syy - szz, sxy + syx, szx + sxz,   //
      szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy,  //
      sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz;

  // The largest eigenvalue of N is the largest root of its characteristic polynomial
  // x^4 + c2 x^2 + c1 x + c0 (N is traceless), found by Newton's method from an upper bound:
  // the eigenvalues are +-s1 +- s2 +- s3 (singular values of S), all at most
  // sqrt(3 |S|_F^2). From above the largest root, Newton decreases monotonically to it.
  const double c2 = -2.0 * frobenius2;
  const double c1 = -8.0 * S.determinant();
  const double c0 = N.determinant();
  double x = std::sqrt(3.0 * frobenius2);
  for (int it = 0; it < 60; ++it) {
    const double x2 = x * x;
    const double p = (x2 + c2) * x2 + c1 * x + c0;
    const double dp = 4.0 * x2 * x + 2.0 * c2 * x + c1;
    if (!(dp > 0.0)) break;
    const double step = p / dp;
    x -= step;
    if (std::abs(step) <= 1e-14 * std::abs(x)) break;
  }

  // The eigenvector spans the adjugate of N - x I (rank 3): take its largest column.
  Eigen::Matrix4d M = N;
  M.diagonal().array() -= x;
  Eigen::Vector4d best = Eigen::Vector4d::Zero();
  for (int c = 0; c < 4; ++c) {
    Eigen::Vector4d column;
    for (int r = 0; r < 4; ++r) column[r] = ((r + c) % 2 ? -1.0 : 1.0) * minor3(M, c, r);
    if (column.squaredNorm() > best.squaredNorm()) best = column;
  }
  // When the top eigenvalue is (nearly) repeated the adjugate vanishes and its columns are
  // noise: fall back to the symmetric eigensolver.
  const double scale2 = frobenius2;  // entries of N are O(|S|); the adjugate is O(|S|^3)
  if (best.squaredNorm() > 1e-16 * scale2 * scale2 * scale2) return quaternion_rotation(best);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(N);
  return quaternion_rotation(eig.eigenvectors().col(3));
}

}  // namespace primo
