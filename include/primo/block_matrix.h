#pragma once
// A symmetric matrix of 6x6 blocks with one row of blocks per body: the Hessian of the joint
// and spring energy in the bodies' motions (v, omega), or its projection onto clusters of
// bodies (rigid_multigrid.h). Only the diagonal blocks and the blocks of coupled pairs are
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
  // The coupled pairs (row body, column body), row > column, each once.
  std::vector<std::pair<int, int>> pairs;
  // Each body's off-diagonal blocks, contiguous by row (CSR over bodies, in pair order): the
  // block of the row body against `row_column`. Every pair's block is stored twice, as
  // itself in its first body's row and transposed in its second's, so that a product
  // streams each row without gathering or transposing (it is bound by memory traffic).
  std::vector<int> row_begin;
  std::vector<int> row_column;
  std::vector<Mat6f> row_block;
  std::vector<int> pair_slot, pair_slot_transposed;  // where pair p's two copies are

  int size() const { return int(diag.size()); }
  // Sizes diag and the rows (zero) for `n` bodies and the given pairs.
  void set_structure(int n, std::vector<std::pair<int, int>> coupled_pairs);
  // The block of pair p (rows of its first body, columns of its second), and setting it.
  const Mat6f& off(size_t p) const { return row_block[size_t(pair_slot[p])]; }
  void set_off(size_t p, const Mat6f& block) {
    row_block[size_t(pair_slot[p])] = block;
    row_block[size_t(pair_slot_transposed[p])] = block.transpose();
  }
  // sum over the body's off-diagonal blocks of block * x[column], in row order.
  Vec6 off_product(int body, const BlockVector& x) const {
    Vec6 sum = Vec6::Zero();
    const int end = row_begin[size_t(body) + 1];
    for (int k = row_begin[size_t(body)]; k < end; ++k)
      sum.noalias() += row_block[size_t(k)].cast<double>() * x[size_t(row_column[size_t(k)])];
    return sum;
  }
  // The same sum in reverse row order. A backward Gauss-Seidel sweep walks the rows from the
  // end, and the processor's prefetchers follow it only when every read in it descends: at
  // 192,000 bodies the multigrid's backward sweep took 14 ms instead of 27 so.
  Vec6 off_product_descending(int body, const BlockVector& x) const {
    Vec6 sum = Vec6::Zero();
    const int begin = row_begin[size_t(body)];
    for (int k = row_begin[size_t(body) + 1] - 1; k >= begin; --k)
      sum.noalias() += row_block[size_t(k)].cast<double>() * x[size_t(row_column[size_t(k)])];
    return sum;
  }
  // y = A x, in parallel by rows (the same bits on any number of threads).
  void multiply(const BlockVector& x, BlockVector& y) const;
};

// The distinct unordered pairs among `edges` (pairs of bodies), numbered in order of first
// appearance, each as (higher, lower); `pair_of[k]` is edge k's pair. Edges joining a body to
// itself, or with a negative end, are left out (-1). The Hessian's pairs come from the
// couplings, a coarse level's from the finer level's pairs mapped to their clusters.
struct PairNumbering {
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> pair_of;
};
PairNumbering number_pairs(const std::vector<std::pair<int, int>>& edges);

// Items 0..key.size()-1 grouped by their key in [0, n_keys) (CSR: group g holds
// items[begin[g]..begin[g + 1]), in ascending order); items with a negative key are left out.
struct Groups {
  std::vector<int> begin;
  std::vector<int> items;
};
Groups group_by(const std::vector<int>& key, int n_keys);

// sum of a_i . b_i, in a fixed order (parallel_sum's chunks).
double dot(const BlockVector& a, const BlockVector& b);

}  // namespace primo
