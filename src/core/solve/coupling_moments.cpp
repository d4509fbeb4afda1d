#include "primo/solve/coupling_moments.h"

#include <Eigen/Cholesky>
#include <cmath>

namespace primo {
namespace {

constexpr double kVectorModeWeight[3] = {kModeWeightDu, kModeWeightDv, kModeWeightDuv};

// c_k |a_k|^2 + c_k |b_k|^2 over the vector modes of one coupling, without its weight.
double vector_trace(const PatchModes& a, const PatchModes& b) {
  return kModeWeightDu * (a.du.squaredNorm() + b.du.squaredNorm()) +
         kModeWeightDv * (a.dv.squaredNorm() + b.dv.squaredNorm()) +
         kModeWeightDuv * (a.duv.squaredNorm() + b.duv.squaredNorm());
}

// The same over all modes, the means too.
double mode_trace(const PatchModes& a, const PatchModes& b) {
  return a.mean.squaredNorm() + b.mean.squaredNorm() + vector_trace(a, b);
}

Vec3& vector_mode(PatchModes& m, int k) { return k == 0 ? m.du : k == 1 ? m.dv : m.duv; }

}  // namespace

void CouplingMoments::add(const PatchModes& a, const PatchModes& b, double w) {
  weight += w;
  sum0 += w * a.mean;
  sum1 += w * b.mean;
  Mat3 c = a.mean * b.mean.transpose();
  c.noalias() += kModeWeightDu * a.du * b.du.transpose();
  c.noalias() += kModeWeightDv * a.dv * b.dv.transpose();
  c.noalias() += kModeWeightDuv * a.duv * b.duv.transpose();
  cross += w * c;
  trace += w * mode_trace(a, b);
}

void CouplingMoments::add_moved(const OrientedCoupling& c, const Mat3& rotation0,
                                const Vec3& offset0, const Mat3& rotation1, const Vec3& offset1) {
  const double w = c.weight;
  const Vec3 a_turned = rotation0 * c.own_mean, b_moved = rotation1 * c.other_mean + offset1;
  const Vec3 a_moved = a_turned + offset0;
  weight += w;
  sum0 += w * a_moved;
  sum1 += w * b_moved;
  // (R0 a + t0)(R1 b + t1)^T = R0 a b^T R1^T + (R0 a) t1^T + t0 (R1 b + t1)^T on the means,
  // R0 a b^T R1^T on the vector modes.
  cross.noalias() += rotation0 * c.cross * rotation1.transpose();
  cross.noalias() += w * (a_turned * offset1.transpose() + offset0 * b_moved.transpose());
  trace += w * (a_moved.squaredNorm() + b_moved.squaredNorm());
}

OrientedCoupling OrientedCoupling::of(const RigidSystem::Coupling& c, bool turned) {
  const int own = turned ? 1 : 0;
  return {c.body[own],       c.body[1 - own],       c.weight,
          c.local[own].mean, c.local[1 - own].mean, c.cross_of(own)};
}

double vector_mode_trace(const RigidSystem::Coupling& c) {
  return c.weight * vector_trace(c.local[0], c.local[1]);
}

double CouplingMoments::write(RigidSystem::Coupling& out) const {
  out.weight = weight;
  PatchModes& a = out.local[0];
  PatchModes& b = out.local[1];
  a = b = PatchModes{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  if (!(weight > 0.0)) {
    out.cross.setZero();
    return trace;
  }
  a.mean = sum0 / weight;
  b.mean = sum1 / weight;
  // What the means leave of C, to be factored as L Q^T: the vector modes are then L's and Q's
  // columns, k-th modes a_k = L e_k / s_k and b_k = Q e_k / s_k with s_k^2 = W c_k. Any
  // invertible L is exact; the Cholesky factor of the symmetric part makes Q = L where the
  // joints are closed (the rest of C is then the sides' common second moment), so that the
  // residuals a_k - b_k are as small as the joints' and the Gauss-Newton Hessian is theirs.
  const Mat3 rest = cross - sum0 * b.mean.transpose();
  const double scale = rest.norm();
  if (scale > 0.0) {
    const Mat3 symmetric = 0.5 * (rest + rest.transpose());
    Eigen::LLT<Mat3> llt(symmetric + 1e-9 * scale * Mat3::Identity());
    // Not positive definite (joints far apart): shifted by |rest| >= -(least eigenvalue).
    if (llt.info() != Eigen::Success) llt.compute(symmetric + scale * Mat3::Identity());
    const Mat3 L = llt.matrixL();
    const Mat3 Qt = llt.matrixL().solve(rest);  // L Qt = rest
    for (int k = 0; k < 3; ++k) {
      const double s = std::sqrt(weight * kVectorModeWeight[k]);
      Vec3 ak = L.col(k) / s;
      Vec3 bk = Qt.row(k).transpose() / s;
      // Equal lengths on both sides, the product unchanged: a nearly singular symmetric part
      // would otherwise leave a short mode on one side against a long one on the other.
      const double la = ak.norm(), lb = bk.norm();
      if (la > 0.0 && lb > 0.0) {
        const double balance = std::sqrt(lb / la);
        ak *= balance;
        bk /= balance;
      } else {
        ak.setZero();
        bk.setZero();
      }
      vector_mode(a, k) = ak;
      vector_mode(b, k) = bk;
    }
  }
  out.update_cross();
  return trace - weight * mode_trace(a, b);
}

}  // namespace primo
