// block_matrix.h: pair numbering, grouping, a pair's block in its 16 numbers, a body's own
// block in its form, and the 6x6-block matrix's product, against plain references (a map of
// pairs in order of first appearance; blocks from their points; a dense matrix).

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <map>
#include <random>

#include "primo/solve/block_matrix.h"

using namespace primo;

namespace {

// What number_pairs promises, written the obvious way: a map from (higher, lower) to the
// pair's number, numbers given in order of first appearance.
PairNumbering reference_numbering(const std::vector<std::pair<int, int>>& edges) {
  PairNumbering out;
  std::map<std::pair<int, int>, int> index;
  for (const auto& [a, b] : edges) {
    if (a < 0 || b < 0 || a == b) {
      out.pair_of.push_back(-1);
      continue;
    }
    const std::pair<int, int> key{std::max(a, b), std::min(a, b)};
    const auto [it, inserted] = index.emplace(key, int(out.pairs.size()));
    if (inserted) out.pairs.push_back(key);
    out.pair_of.push_back(it->second);
  }
  return out;
}

Mat3 cross(const Vec3& a) {
  Mat3 m;
  m << 0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0;
  return m;
}

// How a motion (v, omega) moves a point at arm y from the body's point: v + omega x y.
Eigen::Matrix<double, 3, 6> point_jacobian(const Vec3& y) {
  Eigen::Matrix<double, 3, 6> j;
  j << Mat3::Identity(), -cross(y);
  return j;
}

// T = [[I, -[d]x], [0, I]]: a body's motion as seen from a point d away.
Mat6 rigid_transfer(const Vec3& d) {
  Mat6 t = Mat6::Identity();
  t.block<3, 3>(0, 3) = -cross(d);
  return t;
}

PairBlock random_pair_block(std::mt19937& rng) {
  std::normal_distribution<float> normal;
  PairBlock b;
  b.weight = normal(rng);
  for (int k = 0; k < 3; ++k) {
    b.row_arm[k] = normal(rng);
    b.column_arm[k] = normal(rng);
  }
  for (int k = 0; k < 9; ++k) b.turn(k / 3, k % 3) = normal(rng);
  return b;
}

}  // namespace

TEST(PairNumbering, NumbersPairsInOrderOfFirstAppearanceAsTheReference) {
  std::mt19937 rng(5);
  for (const int bodies : {1, 2, 7, 300}) {
    for (const int n_edges : {0, 1, 10, 2000}) {
      std::uniform_int_distribution<int> body(-1, bodies - 1);
      std::vector<std::pair<int, int>> edges;
      for (int k = 0; k < n_edges; ++k) edges.emplace_back(body(rng), body(rng));
      // Both orientations of one pair and a repeat: one pair.
      if (bodies > 1) edges.insert(edges.end(), {{1, 0}, {0, 1}, {1, 0}});
      const PairNumbering got = number_pairs(edges), want = reference_numbering(edges);
      EXPECT_EQ(got.pairs, want.pairs) << bodies << " bodies, " << n_edges << " edges";
      EXPECT_EQ(got.pair_of, want.pair_of) << bodies << " bodies, " << n_edges << " edges";
    }
  }
  // Self-edges and negative ends are left out.
  const PairNumbering none = number_pairs({{3, 3}, {-1, 2}, {2, -1}, {-1, -1}});
  EXPECT_TRUE(none.pairs.empty());
  EXPECT_EQ(none.pair_of, (std::vector<int>{-1, -1, -1, -1}));
}

TEST(Groups, GroupItemsByKeyInOrderAndSkipNegativeKeys) {
  const Groups g = group_by({2, 0, -1, 2, 1, 0}, 4);
  EXPECT_EQ(g.begin, (std::vector<int>{0, 2, 3, 5, 5}));
  EXPECT_EQ(g.items, (std::vector<int>{1, 5, 4, 0, 3}));
}

TEST(PairBlock, IsTheDenseBlockOfAPairOfBodiesJoinedAtPoints) {
  // A pair's block from its points (rows the first body, columns the second): the Gauss-Newton
  // block of sum w |X_0 - X_1|^2 / 2 over points at arms y0, y1 from the bodies' points, i.e.
  // -sum w J(y0)^T J(y1) with J(y) = [I, -[y]x] (a motion (v, omega) moves the point by
  // v + omega x y).
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  auto random3 = [&] { return Vec3(normal(rng), normal(rng), normal(rng)); };
  PairBlockSum block = PairBlockSum::Zero();
  Mat6 want = Mat6::Zero();
  for (int q = 0; q < 4; ++q) {
    const double w = 0.5 + q;
    const Vec3 y0 = random3(), y1 = random3();
    PairBlockSum point;
    point.weight = -w;
    point.row_arm = -w * y0;
    point.column_arm = -w * y1;
    point.turn = w * y1 * y0.transpose() - w * y0.dot(y1) * Mat3::Identity();
    block += point;
    want -= w * point_jacobian(y0).transpose() * point_jacobian(y1);
  }
  EXPECT_LT((block.dense() - want).norm(), 1e-12 * want.norm());
  EXPECT_LT((block.transposed().dense() - want.transpose()).norm(), 1e-12 * want.norm());
  // Moving the bodies' points: T_0^T B T_1 with T = [[I, -[d]x], [0, I]].
  const Vec3 d0 = random3(), d1 = random3();
  const Mat6 moved = rigid_transfer(d0).transpose() * want * rigid_transfer(d1);
  EXPECT_LT((block.shifted(d0, d1).dense() - moved).norm(), 1e-12 * moved.norm());
  // The product is the dense block's.
  Vec6 x, y = Vec6::Zero();
  for (int k = 0; k < 6; ++k) x[k] = normal(rng);
  block.add_product(x, y);
  EXPECT_LT((y - want * x).norm(), 1e-12 * (want * x).norm());
  // A handle's fixed shifts or turns: their rows (the body is the row's) or columns are zero,
  // the rest is the block's.
  for (int fixed_row = 0; fixed_row < 3; ++fixed_row)
    for (int fixed_column = 0; fixed_column < 3; ++fixed_column) {
      PairBlockSum masked = block;  // 0: nothing fixed, 1: shifts fixed, 2: turns fixed
      masked.mask(fixed_row != 1, fixed_row != 2, fixed_column != 1, fixed_column != 2);
      Mat6 expected = block.dense();
      if (fixed_row == 1) expected.topRows<3>().setZero();
      if (fixed_row == 2) expected.bottomRows<3>().setZero();
      if (fixed_column == 1) expected.leftCols<3>().setZero();
      if (fixed_column == 2) expected.rightCols<3>().setZero();
      EXPECT_EQ(masked.dense(), expected) << fixed_row << " " << fixed_column;
    }
}

TEST(RigidDiagonalBlock, IsTheDenseBlockOfABodysPointsAndKeepsItsFormUnderTransfers) {
  // A body's own Gauss-Newton block of sum w |X - target|^2 / 2 over points at arms y is
  // sum w J(y)^T J(y) with J(y) = [I, -[y]x]: weight sum w, arm sum w y, turn
  // sum w (|y|^2 I - y y^T).
  std::mt19937 rng(6);
  std::normal_distribution<double> normal;
  auto random3 = [&] { return Vec3(normal(rng), normal(rng), normal(rng)); };
  RigidDiagonalBlock block;
  Mat6 want = Mat6::Zero();
  for (int q = 0; q < 5; ++q) {
    const double w = 0.25 + q;
    const Vec3 y = random3();
    block.weight += w;
    block.arm += w * y;
    block.turn += w * (y.squaredNorm() * Mat3::Identity() - y * y.transpose());
    want += w * point_jacobian(y).transpose() * point_jacobian(y);
  }
  EXPECT_LT((block.dense() - want).norm(), 1e-12 * want.norm());
  // Stored in single precision (its turn is symmetric): the same numbers, and its product.
  const DiagonalBlock stored = DiagonalBlock::of(block);
  EXPECT_EQ(stored.dense(), block.dense().cast<float>().cast<double>());
  const Vec6 x = (Vec6() << random3(), random3()).finished();
  EXPECT_LT((stored.times(x) - stored.dense() * x).norm(), 1e-12 * x.norm() * want.norm());
  // Moved to a point d away: T^T B T with T = [[I, -[d]x], [0, I]], added to another block.
  const Vec3 d = random3();
  const Mat6 t = rigid_transfer(d);
  RigidDiagonalBlock sum = block;
  sum.add_shifted(block, d);
  const Mat6 shifted = want + t.transpose() * want * t;
  EXPECT_LT((sum.dense() - shifted).norm(), 1e-12 * shifted.norm());
  // A pair inside one cluster adds p + p^T.
  PairBlockSum pair;
  pair.weight = -1.5;
  pair.row_arm = random3();
  pair.column_arm = random3();
  for (int k = 0; k < 9; ++k) pair.turn(k / 3, k % 3) = normal(rng);
  RigidDiagonalBlock with_pair = block;
  with_pair.add_pair(pair);
  const Mat6 paired = want + pair.dense() + pair.dense().transpose();
  EXPECT_LT((with_pair.dense() - paired).norm(), 1e-12 * paired.norm());
  // The inverse, also of a handle's masked block (fixed shifts: weight 1, arm 0), applied to
  // every unit vector: the dense inverse's columns to single precision.
  auto expect_inverse = [](const RigidDiagonalBlock& b) {
    RigidInverse inverse;
    ASSERT_TRUE(RigidInverse::of(b, inverse));
    const Mat6 want_inverse = b.dense().inverse();
    for (int k = 0; k < 6; ++k) {
      const Vec6 column = inverse.times(Vec6f(Vec6f::Unit(k))).cast<double>();
      EXPECT_LT((column - want_inverse.col(k)).norm(), 1e-5 * want_inverse.norm()) << k;
    }
  };
  expect_inverse(block);
  expect_inverse(with_pair);
  RigidDiagonalBlock pinned = block;
  pinned.weight = 1.0;
  pinned.arm.setZero();
  expect_inverse(pinned);
  // Not positive definite: refused.
  RigidInverse inverse;
  RigidDiagonalBlock negative = block;
  negative.weight = -1.0;
  EXPECT_FALSE(RigidInverse::of(negative, inverse));
  RigidDiagonalBlock flat = block;
  flat.turn = -flat.turn;
  EXPECT_FALSE(RigidInverse::of(flat, inverse));
}

TEST(BlockMatrix, ProductMatchesTheDenseMatrixWithEveryPairStoredInBothRows) {
  std::mt19937 rng(9);
  std::normal_distribution<float> normal;
  const int n = 9;
  const std::vector<std::pair<int, int>> pairs = {{1, 0}, {4, 2}, {8, 0}, {5, 3}, {8, 7}, {6, 1}};
  BlockMatrix a;
  a.set_structure(n, pairs);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (int b = 0; b < n; ++b) {
    DiagonalBlock block;
    block.weight = normal(rng);
    for (int k = 0; k < 3; ++k) block.arm[k] = normal(rng);
    for (float& t : block.turn) t = normal(rng);
    a.diag[size_t(b)] = block;
    dense.block<6, 6>(6 * b, 6 * b) = block.dense();
  }
  for (size_t p = 0; p < pairs.size(); ++p) {
    const PairBlock block = random_pair_block(rng);
    a.set_off(p, block);
    EXPECT_EQ(a.off(p).dense(), block.dense());
    const auto [i, j] = pairs[p];
    dense.block<6, 6>(6 * i, 6 * j) = block.dense();
    dense.block<6, 6>(6 * j, 6 * i) = block.dense().transpose();
  }
  BlockVector x(static_cast<size_t>(n)), y;
  Eigen::VectorXd xd(6 * n);
  for (int b = 0; b < n; ++b) {
    for (int k = 0; k < 6; ++k) x[size_t(b)][k] = normal(rng);
    xd.segment<6>(6 * b) = x[size_t(b)];
  }
  a.multiply(x, y);
  const Eigen::VectorXd want = dense * xd;
  for (int b = 0; b < n; ++b) {
    EXPECT_LT((y[size_t(b)] - want.segment<6>(6 * b)).norm(), 1e-12 * want.norm()) << b;
    // The descending sum is the same sum in the other order.
    EXPECT_LT((a.off_product_descending(b, x) - a.off_product(b, x)).norm(), 1e-12 * want.norm());
  }
}
