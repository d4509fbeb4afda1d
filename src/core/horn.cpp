#include "primo/horn.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace primo {

Mat3 horn_rotation(const Mat3& S, const Mat3& prior) {
  const double sxx = S(0, 0), sxy = S(0, 1), sxz = S(0, 2);
  const double syx = S(1, 0), syy = S(1, 1), syz = S(1, 2);
  const double szx = S(2, 0), szy = S(2, 1), szz = S(2, 2);
  if (S.cwiseAbs().maxCoeff() == 0.0) return prior;
  Eigen::Matrix4d N;
  N << sxx + syy + szz, syz - szy, szx - sxz, sxy - syx,  //
      syz - szy, sxx - syy - szz, sxy + syx, szx + sxz,   //
      szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy,  //
      sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(N);
  const Eigen::Vector4d q = eig.eigenvectors().col(3);  // eigenvalues ascend
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

}  // namespace primo
