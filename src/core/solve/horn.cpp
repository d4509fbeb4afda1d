#include "primo/solve/horn.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace primo {
namespace {

// The rotation of the quaternion (w, x, y, z), which need not be normalized (nonzero).
Mat3 quaternion_rotation(double w, double x, double y, double z) {
  const double s = 2.0 / (w * w + x * x + y * y + z * z);
  const double xs = x * s, ys = y * s, zs = z * s;
  const double wx = w * xs, wy = w * ys, wz = w * zs;
  const double xx = x * xs, xy = x * ys, xz = x * zs;
  const double yy = y * ys, yz = y * zs, zz = z * zs;
  Mat3 R;
  R << 1.0 - (yy + zz), xy - wz, xz + wy,  //
      xy + wz, 1.0 - (xx + zz), yz - wx,   //
      xz - wy, yz + wx, 1.0 - (xx + yy);
  return R;
}

// Column c of adj(M) up to sign: the generalized cross product of the three rows of M other
// than row c (orthogonal to them, its entries the signed 3x3 minors).
void adjugate_column(const double M[4][4], int c, double v[4]) {
  const double* a = M[c == 0 ? 1 : 0];
  const double* b = M[c <= 1 ? 2 : 1];
  const double* d = M[c <= 2 ? 3 : 2];
  const double m01 = b[0] * d[1] - b[1] * d[0], m02 = b[0] * d[2] - b[2] * d[0];
  const double m03 = b[0] * d[3] - b[3] * d[0], m12 = b[1] * d[2] - b[2] * d[1];
  const double m13 = b[1] * d[3] - b[3] * d[1], m23 = b[2] * d[3] - b[3] * d[2];
  v[0] = a[1] * m23 - a[2] * m13 + a[3] * m12;
  v[1] = -(a[0] * m23 - a[2] * m03 + a[3] * m02);
  v[2] = a[0] * m13 - a[1] * m03 + a[3] * m01;
  v[3] = -(a[0] * m12 - a[1] * m02 + a[2] * m01);
}

// horn_rotation for a nonzero S whose squared norm `frobenius2` is far from over- and
// underflow (the quartic below has terms of order |S|^4, the adjugate of order |S|^3).
Mat3 rotation_of(const Mat3& S, const Mat3& prior, double frobenius2) {
  const double sxx = S(0, 0), sxy = S(0, 1), sxz = S(0, 2);
  const double syx = S(1, 0), syy = S(1, 1), syz = S(1, 2);
  const double szx = S(2, 0), szy = S(2, 1), szz = S(2, 2);
  // Horn's symmetric N: q^T N q = trace(R(q) S) for a unit quaternion q = (w, x, y, z).
  double N[4][4] = {{sxx + syy + szz, syz - szy, szx - sxz, sxy - syx},
                    {syz - szy, sxx - syy - szz, sxy + syx, szx + sxz},
                    {szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy},
                    {sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz}};

  // The largest eigenvalue of N is the largest root of its characteristic polynomial. With
  // the singular values s1 >= s2 >= s3 of S and s3' = sign(det S) s3, the eigenvalues are
  // s1+s2+s3', s1-s2-s3', -s1+s2-s3', -s1-s2+s3', whose product works out to
  //   p(x) = x^4 - 2 F x^2 - 8 d x + F^2 - 4 C = (x^2 - F)^2 - 8 d x - 4 C
  // with F = |S|_F^2 = sum s_i^2, d = det S and C = s1^2 s2^2 + s2^2 s3^2 + s3^2 s1^2, the
  // squared norm of the cofactor matrix of S (Cauchy-Binet). The second form is evaluated:
  // it has no cancellation between terms of order F^2 (e.g. for nearly rank-1 S).
  const double k00 = syy * szz - syz * szy, k01 = syz * szx - syx * szz;
  const double k02 = syx * szy - syy * szx, k10 = sxz * szy - sxy * szz;
  const double k11 = sxx * szz - sxz * szx, k12 = sxy * szx - sxx * szy;
  const double k20 = sxy * syz - sxz * syy, k21 = sxz * syx - sxx * syz;
  const double k22 = sxx * syy - sxy * syx;
  const double d8 = 8.0 * (sxx * k00 + sxy * k01 + sxz * k02);
  const double C4 = 4.0 * (k00 * k00 + k01 * k01 + k02 * k02 + k10 * k10 + k11 * k11 +
                           k12 * k12 + k20 * k20 + k21 * k21 + k22 * k22);

  // Newton's method on p. The largest root is at most s1+s2+s3 <= sqrt(3 F) = upper and at
  // least s1 >= sqrt(F/3), where p'' = 12 x^2 - 4 F >= 0: p is convex on [sqrt(F/3), inf).
  // Any start x0 >= sqrt(F/3) with p'(x0) > 0 converges to the largest root: p is convex and
  // increasing from x0 on, so if p(x0) <= 0 exactly one root is above x0, the largest, and
  // the first Newton step lands at or above it (the tangent is below the convex p); if
  // p(x0) > 0 no root is above x0. From above the largest root Newton decreases monotonically.
  // p'(x0) must be well above its rounding noise though: p' at the root is the product of the
  // gaps to the other eigenvalues, and a tiny one (a nearly repeated top eigenvalue) makes
  // the first step noise. Otherwise start from upper, as the plain method does.
  // Starts, best first: x0 = trace(R_prior S) = q_prior^T N q_prior, a lower bound exact at
  // convergence of a sweep (the prior is the answer: one step); else the upper bound
  // z = sqrt(F + sqrt(4 C + 8 |d| upper)) >= s1+s2+s3 (from (s1+s2+s3)^2 = F + 2 e with
  // e = s1 s2 + s2 s3 + s3 s1 and e^2 = C + 2 s1 s2 s3 (s1+s2+s3)), nearly exact for flat
  // point sets (d ~ 0); else upper.
  const double upper = std::sqrt(3.0 * frobenius2);
  double x = upper;
  const double x0 = prior(0, 0) * sxx + prior(0, 1) * syx + prior(0, 2) * szx +
                    prior(1, 0) * sxy + prior(1, 1) * syy + prior(1, 2) * szy +
                    prior(2, 0) * sxz + prior(2, 1) * syz + prior(2, 2) * szz;
  const double min_slope = 1e-4 * frobenius2 * upper;
  if (x0 > 0.0 && x0 < upper && 3.0 * x0 * x0 >= frobenius2 &&
      4.0 * x0 * (x0 * x0 - frobenius2) - d8 > min_slope) {
    x = x0;
  } else {
    const double z = std::sqrt(frobenius2 + std::sqrt(C4 + std::abs(d8) * upper));
    if (z < upper && 4.0 * z * (z * z - frobenius2) - d8 > min_slope) x = z;
  }
  for (int it = 0; it < 60; ++it) {
    const double y = x * x - frobenius2;
    const double p = y * y - d8 * x - C4;
    const double dp = 4.0 * x * y - d8;
    if (!(dp > 0.0)) break;
    const double step = p / dp;
    const double previous = x;
    x -= step;
    if (x > upper) x = upper;  // the root is below (only a first step from below gets here)
    // Taylor: the new error (x - root >= 0) is p''(xi) (x_previous - root)^2 / (2 p'(x_previous))
    // with xi between them, and p'' is increasing: stop when that is below rounding. (Only
    // while x is in the convex range: near a multiple root the steps are rounding noise.)
    const double xm = std::max(x, previous);
    if (std::abs(step) <= 1e-14 * x ||
        (3.0 * x * x >= frobenius2 &&
         step * step * (12.0 * xm * xm - 4.0 * frobenius2) <= 1e-16 * x * dp))
      break;
  }

  // The eigenvector q spans the adjugate of M = N - x I (rank 3): adj(M) = K q q^T, so column
  // c is K q_c q and its entry c is K q_c^2. Columns with a large |q_c| are the accurate ones.
  const double diagonal[4] = {N[0][0], N[1][1], N[2][2], N[3][3]};
  for (int i = 0; i < 4; ++i) N[i][i] -= x;
  // When the top eigenvalue is (nearly) repeated the adjugate vanishes and its columns are
  // noise: those below this bound go to the symmetric eigensolver (entries of N are O(|S|),
  // the adjugate is O(|S|^3)). K = p'(x) is the product of the gaps to the other eigenvalues;
  // rounding errors of order eps |S|^4 in p(x) put x off by eps |S|^4 / K, which mixes the
  // next eigenvector in by (x error / gap) and loses about (x error)^2 / gap of the maximum:
  // below 1e-12 |S| with |column| >= 1e-5 |S|^3, the eigensolver takes the rest.
  const double floor2 = 1e-10 * frobenius2 * frobenius2 * frobenius2;
  // First try the column of the prior's largest quaternion component (Shepperd's choice:
  // the largest of trace, R00, R11, R22); near convergence it is the answer's. Accepted when
  // the column itself confirms q_c^2 = v_c^2 / |v|^2 >= 1/8 (the largest is >= 1/4).
  int c = 0;
  double largest = prior(0, 0) + prior(1, 1) + prior(2, 2);
  for (int i = 0; i < 3; ++i)
    if (prior(i, i) > largest) largest = prior(i, i), c = i + 1;
  double v[4];
  adjugate_column(N, c, v);
  double norm2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3];
  if (norm2 > floor2 && 8.0 * v[c] * v[c] >= norm2)
    return quaternion_rotation(v[0], v[1], v[2], v[3]);
  if (norm2 > floor2) {
    // A far prior: this column is still proportional to q; take q's largest component.
    int k = 0;
    for (int i = 1; i < 4; ++i)
      if (std::abs(v[i]) > std::abs(v[k])) k = i;
    adjugate_column(N, k, v);
    norm2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3];
    if (norm2 > floor2 && 8.0 * v[k] * v[k] >= norm2)
      return quaternion_rotation(v[0], v[1], v[2], v[3]);
  }

  // Otherwise (a nearly repeated top eigenvalue, or a far prior's column vanished) the largest
  // of the four columns.
  double best[4] = {0.0, 0.0, 0.0, 0.0};
  double best_norm2 = 0.0;
  for (int k = 0; k < 4; ++k) {
    adjugate_column(N, k, v);
    norm2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3];
    if (norm2 > best_norm2) {
      best_norm2 = norm2;
      for (int i = 0; i < 4; ++i) best[i] = v[i];
    }
  }
  if (best_norm2 > floor2) return quaternion_rotation(best[0], best[1], best[2], best[3]);

  Eigen::Matrix4d H;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) H(i, j) = i == j ? diagonal[i] : N[i][j];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(H);
  const Eigen::Vector4d q = eig.eigenvectors().col(3);
  return quaternion_rotation(q[0], q[1], q[2], q[3]);
}

}  // namespace

Mat3 horn_rotation(const Mat3& S, const Mat3& prior) {
  const double frobenius2 = S.squaredNorm();
  if (frobenius2 > 1e-60 && frobenius2 < 1e60) return rotation_of(S, prior, frobenius2);
  // Huge or tiny S (or zero, or not finite): scaling by a power of two is exact and leaves the
  // maximizer unchanged; bring the largest entry to [1, 2).
  const double largest = S.cwiseAbs().maxCoeff();
  if (largest == 0.0) return prior;
  if (!(largest <= std::numeric_limits<double>::max())) return rotation_of(S, prior, frobenius2);
  const int e = std::ilogb(largest);
  const Mat3 scaled = S.unaryExpr([e](double s) { return std::ldexp(s, -e); });
  return rotation_of(scaled, prior, scaled.squaredNorm());
}

}  // namespace primo
