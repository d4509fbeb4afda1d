#pragma once
// A symmetric matrix of 6x6 blocks with one row of blocks per body: the Hessian of the joint
// and spring energy in the bodies' motions (v, omega), or its projection onto clusters of
// bodies (rigid_multigrid.h). Only the diagonal blocks and one block per coupled pair are
// stored; a vector is one Vec6 per body.

#include <utility>
#include <vector>

#include "primo/types.h"

namespace primo {

using BlockVector = std::vector<Vec6>;
// Blocks are stored in single precision: products with them are bound by memory traffic, and
// conjugate gradients only solve to a few digits (vectors and sums stay double).
using BlockScalar = float;
using Mat6f = Eigen::Matrix<BlockScalar, 6, 6>;

struct BlockMatrix {
  std::vector<Mat6f> diag;
  // The coupled pairs (row body, column body), row > column, each once, and their blocks.
  std::vector<std::pair<int, int>> pairs;
  std::vector<Mat6f> off;
  // Each body's pairs (CSR over bodies, in pair order), made by index_rows().
  std::vector<int> row_begin;
  std::vector<int> row_pairs;

  int size() const { return int(diag.size()); }
  // Sizes diag and off (zero) and indexes the rows, for `n` bodies and the given pairs.
  void set_structure(int n, std::vector<std::pair<int, int>> coupled_pairs);
  // The block of row `body` and column `other` of pair p (the stored one or its transpose).
  int other_body(int p, int body) const {
    return pairs[size_t(p)].first == body ? pairs[size_t(p)].second : pairs[size_t(p)].first;
  }
  // sum over the body's off-diagonal blocks of block * x[column], in row order.
  Vec6 off_product(int body, const BlockVector& x) const {
    Vec6 sum = Vec6::Zero();
    for (int k = row_begin[size_t(body)]; k < row_begin[size_t(body) + 1]; ++k) {
      const int p = row_pairs[size_t(k)];
      if (pairs[size_t(p)].first == body)
        sum.noalias() += off[size_t(p)].cast<double>() * x[size_t(pairs[size_t(p)].second)];
      else
        sum.noalias() +=
            off[size_t(p)].transpose().cast<double>() * x[size_t(pairs[size_t(p)].first)];
    }
    return sum;
  }
  // y = A x, in parallel by rows (the same bits on any number of threads).
  void multiply(const BlockVector& x, BlockVector& y) const;
};

// sum of a_i . b_i, in a fixed order (parallel_sum's chunks).
double dot(const BlockVector& a, const BlockVector& b);

}  // namespace primo
