// block_matrix.h: pair numbering, grouping, and the 6x6-block matrix's product, against
// plain references (a map of pairs in order of first appearance; a dense matrix).

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "primo/block_matrix.h"

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

TEST(BlockMatrix, ProductMatchesTheDenseMatrixWithEveryPairStoredInBothRows) {
  std::mt19937 rng(9);
  std::normal_distribution<float> normal;
  const int n = 9;
  const std::vector<std::pair<int, int>> pairs = {{1, 0}, {4, 2}, {8, 0}, {5, 3}, {8, 7}, {6, 1}};
  BlockMatrix a;
  a.set_structure(n, pairs);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (int b = 0; b < n; ++b) {
    Mat6f block;
    for (int k = 0; k < 36; ++k) block(k / 6, k % 6) = normal(rng);
    a.diag[size_t(b)] = block;
    dense.block<6, 6>(6 * b, 6 * b) = block.cast<double>();
  }
  for (size_t p = 0; p < pairs.size(); ++p) {
    Mat6f block;
    for (int k = 0; k < 36; ++k) block(k / 6, k % 6) = normal(rng);
    a.set_off(p, block);
    EXPECT_EQ(a.off(p), block);
    const auto [i, j] = pairs[p];
    dense.block<6, 6>(6 * i, 6 * j) = block.cast<double>();
    dense.block<6, 6>(6 * j, 6 * i) = block.transpose().cast<double>();
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
