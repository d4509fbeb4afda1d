#include "primo/model/bilinear_inner_product.h"

#include <gtest/gtest.h>

#include <random>

using namespace primo;

namespace {

Vec3 bilinear(const PatchCorners& f, double u, double v) {
  return (1 - u) * (1 - v) * f[0] + u * (1 - v) * f[1] + (1 - u) * v * f[2] + u * v * f[3];
}

PatchCorners random_patch(std::mt19937& rng) {
  std::uniform_real_distribution<double> d(-2.0, 2.0);
  PatchCorners p;
  for (Vec3& c : p) c = Vec3(d(rng), d(rng), d(rng));
  return p;
}

// Dense tensor midpoint quadrature of the integral of a(u).b(u) over [0,1]^2.
double dense_quadrature(const PatchCorners& a, const PatchCorners& b, int n) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = (i + 0.5) / n, v = (j + 0.5) / n;
      sum += bilinear(a, u, v).dot(bilinear(b, u, v));
    }
  return sum / (double(n) * n);
}

}  // namespace

TEST(BilinearInnerProduct, ClosedFormEqualsDenseQuadrature) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const PatchCorners a = random_patch(rng), b = random_patch(rng);
    const double closed = bilinear_inner_product(a, b);
    // Midpoint rule error is O(h^2) with a small constant: 1000^2 samples give ~1e-7.
    EXPECT_NEAR(closed, dense_quadrature(a, b, 1000), 1e-6 * (1 + std::abs(closed)));
  }
}

TEST(BilinearInnerProduct, ModesAreTheSameInnerProduct) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 100; ++trial) {
    const PatchCorners a = random_patch(rng), b = random_patch(rng);
    EXPECT_NEAR(modes_inner_product(patch_modes(a), patch_modes(b)), bilinear_inner_product(a, b),
                1e-12);
  }
}

TEST(BilinearInnerProduct, ScalarFormMatchesPaperFormula) {
  // A constant function 1 has squared norm 1; u has integral of u^2 = 1/3.
  EXPECT_NEAR(bilinear_inner_product(std::array<double, 4>{1, 1, 1, 1}, {1, 1, 1, 1}), 1.0, 1e-15);
  EXPECT_NEAR(bilinear_inner_product(std::array<double, 4>{0, 1, 0, 1}, {0, 1, 0, 1}), 1.0 / 3.0,
              1e-15);
  // u v: integral of u^2 v^2 = 1/9.
  EXPECT_NEAR(bilinear_inner_product(std::array<double, 4>{0, 0, 0, 1}, {0, 0, 0, 1}), 1.0 / 9.0,
              1e-15);
}
