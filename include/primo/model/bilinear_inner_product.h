#pragma once
// The L2 inner product of two bilinear patches over [0,1]^2 (paper, Appendix A):
//   <a, b>_2 = 1/9 sum_{i,j,k,l in {0,1}} a_ij . b_kl . 2^(-|i-k|-|j-l|).
// Corners are ordered f00, f10, f01, f11 (first index along the edge, second across the
// layer).
//
// The 4x4 Gram matrix of the bilinear basis is the tensor square of [[1/3, 1/6], [1/6, 1/3]],
// whose eigenvectors are (1, 1) and (1, -1). In that orthogonal basis the inner product is
// diagonal, so one patch reduces to four "modes": its corner mean (a point) and three
// difference vectors. Energies, shape matching and Newton systems all work on modes, which
// is exact and four times cheaper than the 16-term sum.

#include <array>

#include "primo/util/types.h"

namespace primo {

using PatchCorners = std::array<Vec3, 4>;  // f00, f10, f01, f11

double bilinear_inner_product(const std::array<double, 4>& a, const std::array<double, 4>& b);
double bilinear_inner_product(const PatchCorners& a, const PatchCorners& b);

struct PatchModes {
  Vec3 mean;  // (f00 + f10 + f01 + f11) / 4: moves as a point
  Vec3 du;    // (-f00 + f10 - f01 + f11) / 2: along the edge, moves as a vector
  Vec3 dv;    // (-f00 - f10 + f01 + f11) / 2: across the layer
  Vec3 duv;   // ( f00 - f10 - f01 + f11) / 2: twist
};

// Weights of the modes: <a, b>_2 = a.mean.b.mean + (a.du.b.du + a.dv.b.dv) / 12 + a.duv.b.duv / 36.
inline constexpr double kModeWeightDu = 1.0 / 12.0;
inline constexpr double kModeWeightDv = 1.0 / 12.0;
inline constexpr double kModeWeightDuv = 1.0 / 36.0;

PatchModes patch_modes(const PatchCorners& corners);
double modes_inner_product(const PatchModes& a, const PatchModes& b);

}  // namespace primo
