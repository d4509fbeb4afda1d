#pragma once
// A symmetric matrix of 6x6 blocks with one row of blocks per body: the Hessian of the joint
// and spring energy in the bodies' motions (v, omega), or its projection onto clusters of
// bodies (rigid_multigrid.h). Only the diagonal blocks and the blocks of coupled pairs are
// stored, the latter in the 16 numbers that determine them (PairBlock); a vector is one Vec6
// per body.

#include <Eigen/Geometry>
#include <array>
#include <utility>
#include <vector>

#include "primo/util/types.h"

namespace primo {

using BlockVector = std::vector<Vec6>;
// The multigrid preconditioner's vectors (rigid_multigrid.h): it only needs a few digits.
using Vec6f = Eigen::Matrix<float, 6, 1>;
using BlockVectorF = std::vector<Vec6f>;
// Blocks are stored in single precision: products with them are bound by memory traffic, and
// conjugate gradients only solve to a few digits (vectors and sums stay double).
using BlockScalar = float;

// The block of two bodies whose energy is a sum of squared differences of points, each moved
// rigidly by one of them (a joint: the residuals X_row - X_column; a cluster pair of the
// multigrid: a sum of its bodies' joints), rows the first body's motion (v, omega), columns
// the second's:
//   [[weight I, -[column_arm]x], [[row_arm]x, turn]]
// with weight = -sum w, the arms -sum w y over each side's arms y from its body's point, and
// turn = sum w y_column y_row^T - (sum w y_row . y_column) I. Sixteen numbers instead of 36: a
// product or a Gauss-Seidel sweep with the Hessian streams every block, and at 192,000 bodies
// a product took 7.3 ms with them against 8.3 ms, a multigrid cycle 63 against 67 ms, the
// Hessian's assembly 61-80 against 85-99 ms (docs/performance.md). The form is kept by sums,
// by moving either body's point (a cluster's Galerkin projection) and by zeroing the rows or
// columns of a body's shifts or turns (a handle's fixed dofs), so every level of the
// multigrid stores its pairs this way.
template <class Scalar>
struct alignas(16 * sizeof(Scalar)) PairBlockOf {  // one cache line in single precision
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  using M3 = Eigen::Matrix<Scalar, 3, 3>;
  Scalar weight;
  V3 row_arm, column_arm;
  M3 turn;

  // Uninitialized, as Eigen's fixed-size matrices are: a matrix's blocks are first written
  // in parallel (BlockMatrix::set_structure), which places their pages near the threads.
  PairBlockOf() {}
  static PairBlockOf Zero() {
    PairBlockOf z;
    z.weight = Scalar(0);
    z.row_arm.setZero();
    z.column_arm.setZero();
    z.turn.setZero();
    return z;
  }

  // y += B x, in the vectors' precision.
  template <class V>
  void add_product(const V& x, V& y) const {
    using T = typename V::Scalar;
    const T v0 = x[0], v1 = x[1], v2 = x[2], w0 = x[3], w1 = x[4], w2 = x[5];
    const T m = T(weight);
    const T r0 = T(row_arm[0]), r1 = T(row_arm[1]), r2 = T(row_arm[2]);
    const T c0 = T(column_arm[0]), c1 = T(column_arm[1]), c2 = T(column_arm[2]);
    y[0] += m * v0 + (w1 * c2 - w2 * c1);  // weight v + omega x column_arm
    y[1] += m * v1 + (w2 * c0 - w0 * c2);
    y[2] += m * v2 + (w0 * c1 - w1 * c0);
    y[3] += (r1 * v2 - r2 * v1) + T(turn(0, 0)) * w0 + T(turn(0, 1)) * w1 +
            T(turn(0, 2)) * w2;  // row_arm x v + turn omega
    y[4] += (r2 * v0 - r0 * v2) + T(turn(1, 0)) * w0 + T(turn(1, 1)) * w1 + T(turn(1, 2)) * w2;
    y[5] += (r0 * v1 - r1 * v0) + T(turn(2, 0)) * w0 + T(turn(2, 1)) * w1 + T(turn(2, 2)) * w2;
  }
  // B^T: the same pair seen from its second body.
  PairBlockOf transposed() const {
    PairBlockOf t;
    t.weight = weight;
    t.row_arm = column_arm;
    t.column_arm = row_arm;
    t.turn = turn.transpose();
    return t;
  }
  // T_row^T B T_column for the rigid transfers T = [[I, -[d]x], [0, I]] that move a body's
  // point by -d (a cluster's motion seen by a body whose point is d from the cluster's).
  // turn - [row_arm]x [d_column]x - [d_row]x [column_arm']x, by [u]x [v]x = v u^T - (u.v) I.
  PairBlockOf shifted(const V3& d_row, const V3& d_column) const {
    PairBlockOf s;
    s.weight = weight;
    s.row_arm = row_arm + weight * d_row;
    s.column_arm = column_arm + weight * d_column;
    s.turn = turn - d_column * row_arm.transpose() - s.column_arm * d_row.transpose();
    s.turn.diagonal().array() += row_arm.dot(d_column) + d_row.dot(s.column_arm);
    return s;
  }
  // Zeroes the rows or columns of shifts (v) or turns (omega) that are not to move.
  void mask(bool row_shifts, bool row_turns, bool column_shifts, bool column_turns) {
    if (!row_shifts || !column_shifts) weight = Scalar(0);
    if (!row_shifts || !column_turns) column_arm.setZero();
    if (!row_turns || !column_shifts) row_arm.setZero();
    if (!row_turns || !column_turns) turn.setZero();
  }
  PairBlockOf& operator+=(const PairBlockOf& b) {
    weight += b.weight;
    row_arm += b.row_arm;
    column_arm += b.column_arm;
    turn += b.turn;
    return *this;
  }
  template <class Other>
  PairBlockOf<Other> cast() const {
    PairBlockOf<Other> c;
    c.weight = Other(weight);
    c.row_arm = row_arm.template cast<Other>();
    c.column_arm = column_arm.template cast<Other>();
    c.turn = turn.template cast<Other>();
    return c;
  }
  Mat6 dense() const {
    Mat6 b;
    b.template block<3, 3>(0, 0) = double(weight) * Mat3::Identity();
    b.template block<3, 3>(0, 3) = -cross(column_arm).template cast<double>();
    b.template block<3, 3>(3, 0) = cross(row_arm).template cast<double>();
    b.template block<3, 3>(3, 3) = turn.template cast<double>();
    return b;
  }

 private:
  static M3 cross(const V3& a) {  // [a]x
    M3 m;
    m << Scalar(0), -a[2], a[1], a[2], Scalar(0), -a[0], -a[1], a[0], Scalar(0);
    return m;
  }
};
using PairBlock = PairBlockOf<BlockScalar>;
using PairBlockSum = PairBlockOf<double>;  // to add many in

// A body's own (diagonal) block of the same energy: [[weight I, -[arm]x], [[arm]x, turn]] with
// weight = sum w, arm = sum w y and turn = sum w (|y|^2 I - y y^T) over its points' arms y
// (plus, in an exact Hessian, a symmetric second-order term in `turn`). Zeroing a handle's
// fixed rows and columns with 1 on the diagonal keeps the form (weight 1 or arm 0 or turn I),
// and so do sums, moving the body's point and adding a pair inside a cluster: every diagonal
// block of the multigrid's levels has it. Projections and inverses in this form instead of
// dense 6x6 products: the multigrid's set-up at 192,000 bodies took 48-52 ms (least and
// median of 12 runs) instead of 55-62 ms on two threads, 76-83 instead of 97-111 on one.
struct RigidDiagonalBlock {
  double weight = 0.0;
  Vec3 arm = Vec3::Zero();
  Mat3 turn = Mat3::Zero();

  // += T^T b T for the rigid transfer T = [[I, -[d]x], [0, I]] (b seen from a point -d away).
  void add_shifted(const RigidDiagonalBlock& b, const Vec3& d);
  // += p + p^T: a pair of bodies that one cluster holds both of.
  void add_pair(const PairBlockSum& p);
  Mat6 dense() const;
};

// A symmetric 3x3 matrix in single precision by its six numbers (xx, xy, xz, yy, yz, zz): a
// diagonal block's turn and the inverse of its Schur complement.
struct Symmetric3f : std::array<float, 6> {
  // `m` with each pair of off-diagonal entries averaged.
  static Symmetric3f of(const Mat3& m);
  Mat3 widened() const;
  // The product in the vector's precision.
  template <class T>
  Eigen::Matrix<T, 3, 1> times(const Eigen::Matrix<T, 3, 1>& w) const {
    const Symmetric3f& s = *this;
    return {T(s[0]) * w[0] + T(s[1]) * w[1] + T(s[2]) * w[2],
            T(s[1]) * w[0] + T(s[3]) * w[1] + T(s[4]) * w[2],
            T(s[2]) * w[0] + T(s[4]) * w[1] + T(s[5]) * w[2]};
  }
};

// The inverse of a RigidDiagonalBlock [[w I, -[a]x], [[a]x, T]] kept as the numbers it is made
// of: 1/w, a and the inverse of the Schur complement S = T + [a]x[a]x / w (symmetric, six
// numbers), 40 bytes where the dense 6x6 inverse in single precision takes 144. The
// multigrid's sweeps read one for every row they solve and are bound by memory traffic: at
// 192,000 bodies a cycle took 45-53 ms (median 47.6 of six alternating runs) instead of
// 50-53 (52.1), the set-up that writes them 36-42 ms instead of 47-52.
// Applied as v = S^-1 (t - a x f / w), u = (f + a x v) / w for the right side (f, t).
struct RigidInverse {  // uninitialized until `of` writes it, as DiagonalBlock
  float inverse_weight;
  Eigen::Vector3f arm;
  Symmetric3f schur_inverse;

  // The smoothers' inverse of `block`; false when the block is not positive definite.
  static bool of(const RigidDiagonalBlock& block, RigidInverse& out);
  Vec6f times(const Vec6f& rhs) const {
    const Eigen::Vector3f f = rhs.head<3>();
    const Eigen::Vector3f t = rhs.tail<3>() - inverse_weight * arm.cross(f);
    const Eigen::Vector3f v = schur_inverse.times(t);
    Vec6f out;
    out.head<3>() = inverse_weight * (f + arm.cross(v));
    out.tail<3>() = v;
    return out;
  }
};

// A diagonal block as a BlockMatrix stores it: a RigidDiagonalBlock's numbers in single
// precision, its turn (symmetric: the energy's second derivative) in six, 40 bytes where a
// dense 6x6 block takes 144. The Hessian's assembly writes every row's block and the
// multigrid's set-up reads it: at 192,000 bodies they took 35-44 ms (median 38.1 of five
// alternating runs) instead of 35-50 (42.9), and 31-32 ms instead of 34-43 (40.1); products
// with the Hessian the same (its double arithmetic costs what the smaller reads save).
// Uninitialized when default-constructed, as Eigen's matrices are, so that a matrix's blocks
// are zeroed on every core (set_structure) instead of one by one as a vector constructs them.
struct DiagonalBlock {
  float weight;
  Eigen::Vector3f arm;
  Symmetric3f turn;

  static DiagonalBlock Zero() { return {0.0f, Eigen::Vector3f::Zero(), {}}; }

  // `block` in single precision, its turn symmetrized.
  static DiagonalBlock of(const RigidDiagonalBlock& block);
  RigidDiagonalBlock widened() const;
  Mat6 dense() const { return widened().dense(); }
  // [[w I, -[a]x], [[a]x, turn]] x in the vector's precision.
  template <class T>
  Eigen::Matrix<T, 6, 1> times(const Eigen::Matrix<T, 6, 1>& x) const {
    using V3 = Eigen::Matrix<T, 3, 1>;
    const V3 v = x.template head<3>(), w = x.template tail<3>();
    const V3 a = arm.cast<T>();
    Eigen::Matrix<T, 6, 1> y;
    y.template head<3>() = T(weight) * v - a.cross(w);
    y.template tail<3>() = a.cross(v) + turn.times(w);
    return y;
  }
};

struct BlockMatrix {
  std::vector<DiagonalBlock> diag;
  // The coupled pairs (row body, column body), row > column, each once.
  std::vector<std::pair<int, int>> pairs;
  // Each body's off-diagonal blocks, contiguous by row (CSR over bodies, in pair order): the
  // block of the row body against `row_column`. Every pair's block is stored twice, as
  // itself in its first body's row and transposed in its second's, so that a product
  // streams each row without gathering or transposing (it is bound by memory traffic).
  std::vector<int> row_begin;
  std::vector<int> row_column;
  std::vector<PairBlock> row_block;
  std::vector<int> pair_slot, pair_slot_transposed;  // where pair p's two copies are

  int size() const { return int(diag.size()); }
  // Sizes diag and the rows (zero) for `n` bodies and the given pairs.
  void set_structure(int n, std::vector<std::pair<int, int>> coupled_pairs);
  // The block of pair p (rows of its first body, columns of its second), and setting it.
  const PairBlock& off(size_t p) const { return row_block[size_t(pair_slot[p])]; }
  void set_off(size_t p, const PairBlock& block) {
    row_block[size_t(pair_slot[p])] = block;
    row_block[size_t(pair_slot_transposed[p])] = block.transposed();
  }
  // sum over the body's off-diagonal blocks of block * x[column], in row order.
  template <class V>
  V off_product(int body, const std::vector<V>& x) const {
    V sum = V::Zero();
    const int end = row_begin[size_t(body) + 1];
    for (int k = row_begin[size_t(body)]; k < end; ++k)
      row_block[size_t(k)].add_product(x[size_t(row_column[size_t(k)])], sum);
    return sum;
  }
  // The same sum in reverse row order. A backward Gauss-Seidel sweep walks the rows from the
  // end, and the processor's prefetchers follow it only when every read in it descends: at
  // 192,000 bodies the multigrid's backward sweep took 14 ms instead of 27 so.
  template <class V>
  V off_product_descending(int body, const std::vector<V>& x) const {
    V sum = V::Zero();
    const int begin = row_begin[size_t(body)];
    for (int k = row_begin[size_t(body) + 1] - 1; k >= begin; --k)
      row_block[size_t(k)].add_product(x[size_t(row_column[size_t(k)])], sum);
    return sum;
  }
  // Row `body` of A x.
  template <class V>
  V row_product(int body, const std::vector<V>& x) const {
    return diag[size_t(body)].times(x[size_t(body)]) + off_product(body, x);
  }
  // y = A x, in parallel by rows (the same bits on any number of threads).
  void multiply(const BlockVector& x, BlockVector& y) const;
  void multiply(const BlockVectorF& x, BlockVectorF& y) const;
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

// Rows a chunk of a row-by-row loop over a block matrix has (products, residuals,
// prolongations): a row takes about 100 ns, so 512 pay for a task, and the multigrid's coarse
// levels (2,800 rows at 240k faces, visited 8 times an application) are split too, where
// 2,048 left them on one thread. Only for loops whose rows are independent: a sum's chunks
// would change its rounding.
inline constexpr size_t kBlockRowGrain = 512;

// sum of a_i . b_i, in a fixed order (parallel_sum's chunks).
double dot(const BlockVector& a, const BlockVector& b);
double dot(const BlockVectorF& a, const BlockVectorF& b);  // summed in double

}  // namespace primo
