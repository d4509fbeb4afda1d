#include "primo/model/bilinear_inner_product.h"

#include <cstdlib>

namespace primo {
namespace {

// Corner k = (i, j) with k = i + 2 j, matching the f00, f10, f01, f11 order.
double gram(int k, int l) {
  const int di = std::abs((k & 1) - (l & 1));
  const int dj = std::abs((k >> 1) - (l >> 1));
  return (1.0 / 9.0) / double(1 << (di + dj));
}

}  // namespace

double bilinear_inner_product(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  double sum = 0.0;
  for (int k = 0; k < 4; ++k)
    for (int l = 0; l < 4; ++l) sum += a[k] * b[l] * gram(k, l);
  return sum;
}

double bilinear_inner_product(const PatchCorners& a, const PatchCorners& b) {
  double sum = 0.0;
  for (int k = 0; k < 4; ++k)
    for (int l = 0; l < 4; ++l) sum += a[k].dot(b[l]) * gram(k, l);
  return sum;
}

PatchModes patch_modes(const PatchCorners& f) {
  return {0.25 * (f[0] + f[1] + f[2] + f[3]), 0.5 * (-f[0] + f[1] - f[2] + f[3]),
          0.5 * (-f[0] - f[1] + f[2] + f[3]), 0.5 * (f[0] - f[1] - f[2] + f[3])};
}

double modes_inner_product(const PatchModes& a, const PatchModes& b) {
  return a.mean.dot(b.mean) + kModeWeightDu * a.du.dot(b.du) + kModeWeightDv * a.dv.dot(b.dv) +
         kModeWeightDuv * a.duv.dot(b.duv);
}

}  // namespace primo
