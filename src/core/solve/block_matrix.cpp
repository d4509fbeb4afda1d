#include "primo/solve/block_matrix.h"

#include <algorithm>

#include "primo/util/parallel.h"
#include "rigid_blocks.h"

namespace primo {

void BlockMatrix::set_structure(int n, std::vector<std::pair<int, int>> coupled_pairs) {
  pairs = std::move(coupled_pairs);
  // Zeroed in parallel (at 240k faces the blocks were 110 MB, and filling them on one thread
  // took 70-100 ms).
  parallel_assign(diag, size_t(n), DiagonalBlock::Zero());
  row_begin.assign(size_t(n) + 1, 0);
  for (const auto& [a, b] : pairs) {
    ++row_begin[size_t(a) + 1];
    ++row_begin[size_t(b) + 1];
  }
  for (int b = 0; b < n; ++b) row_begin[size_t(b) + 1] += row_begin[size_t(b)];
  row_column.resize(size_t(row_begin[size_t(n)]));
  parallel_assign(row_block, row_column.size(), PairBlock::Zero());
  pair_slot.resize(pairs.size());
  pair_slot_transposed.resize(pairs.size());
  std::vector<int> next(row_begin.begin(), row_begin.end() - 1);
  for (size_t p = 0; p < pairs.size(); ++p) {
    const auto [a, b] = pairs[p];
    pair_slot[p] = next[size_t(a)]++;
    row_column[size_t(pair_slot[p])] = b;
    pair_slot_transposed[p] = next[size_t(b)]++;
    row_column[size_t(pair_slot_transposed[p])] = a;
  }
}

namespace {
template <class V>
void multiply_rows(const BlockMatrix& a, const std::vector<V>& x, std::vector<V>& y) {
  y.resize(a.diag.size());
  parallel_chunks(a.diag.size(), kBlockRowGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) y[b] = a.row_product(int(b), x);
  });
}
}  // namespace

void BlockMatrix::multiply(const BlockVector& x, BlockVector& y) const {
  multiply_rows(*this, x, y);
}
void BlockMatrix::multiply(const BlockVectorF& x, BlockVectorF& y) const {
  multiply_rows(*this, x, y);
}

PairNumbering number_pairs(const std::vector<std::pair<int, int>>& edges) {
  // Linear time with arrays, not a hash map (which took 120 ms for the 240k mesh's 358,000
  // couplings): the edges bucketed by their higher end in edge order, each bucket's repeats
  // found by marking the lower ends seen, then the pairs numbered in edge order.
  PairNumbering numbering;
  numbering.pair_of.assign(edges.size(), -1);
  auto valid = [](const std::pair<int, int>& e) {
    return e.first >= 0 && e.second >= 0 && e.first != e.second;
  };
  int n = 0;
  std::vector<int> higher(edges.size(), -1);  // each valid edge's higher end
  for (size_t k = 0; k < edges.size(); ++k)
    if (valid(edges[k])) {
      higher[k] = std::max(edges[k].first, edges[k].second);
      n = std::max(n, higher[k] + 1);
    }
  const Groups by_higher = group_by(higher, n);  // each bucket in edge order
  // first[k]: the first edge with edge k's ends (k itself for a pair's first edge).
  std::vector<int> first(edges.size(), -1), seen_in(size_t(n), -1), seen_first(size_t(n), -1);
  for (int hi = 0; hi < n; ++hi)
    for (int i = by_higher.begin[size_t(hi)]; i < by_higher.begin[size_t(hi) + 1]; ++i) {
      const int k = by_higher.items[size_t(i)];
      const int lo = std::min(edges[size_t(k)].first, edges[size_t(k)].second);
      if (seen_in[size_t(lo)] != hi) {
        seen_in[size_t(lo)] = hi;
        seen_first[size_t(lo)] = k;
      }
      first[size_t(k)] = seen_first[size_t(lo)];
    }
  for (size_t k = 0; k < edges.size(); ++k) {
    if (first[k] < 0) continue;
    if (first[k] == int(k)) {
      numbering.pair_of[k] = int(numbering.pairs.size());
      numbering.pairs.emplace_back(std::max(edges[k].first, edges[k].second),
                                   std::min(edges[k].first, edges[k].second));
    } else {
      numbering.pair_of[k] = numbering.pair_of[size_t(first[k])];  // numbered before: first < k
    }
  }
  return numbering;
}

Groups group_by(const std::vector<int>& key, int n_keys) {
  Groups groups;
  groups.begin.assign(size_t(n_keys) + 1, 0);
  for (int k : key)
    if (k >= 0) ++groups.begin[size_t(k) + 1];
  for (int g = 0; g < n_keys; ++g) groups.begin[size_t(g) + 1] += groups.begin[size_t(g)];
  groups.items.resize(size_t(groups.begin[size_t(n_keys)]));
  std::vector<int> next(groups.begin.begin(), groups.begin.end() - 1);
  for (size_t i = 0; i < key.size(); ++i)
    if (key[i] >= 0) groups.items[size_t(next[size_t(key[i])]++)] = int(i);
  return groups;
}

namespace {
template <class V>
double dot_rows(const std::vector<V>& a, const std::vector<V>& b) {
  return parallel_sum(a.size(), kParallelGrain, 0.0, [&](size_t begin, size_t end) {
    double sum = 0.0;
    for (size_t i = begin; i < end; ++i) sum += double(a[i].dot(b[i]));
    return sum;
  });
}
}  // namespace

double dot(const BlockVector& a, const BlockVector& b) { return dot_rows(a, b); }
double dot(const BlockVectorF& a, const BlockVectorF& b) { return dot_rows(a, b); }

namespace {

// The inverse of a symmetric positive definite 3x3 matrix by its cofactors; false when it is
// not positive definite (a leading minor is not positive: Sylvester's criterion).
bool spd_inverse3(const Mat3& m, Mat3& inverse) {
  const double c00 = m(1, 1) * m(2, 2) - m(1, 2) * m(1, 2);
  const double c01 = m(0, 2) * m(1, 2) - m(0, 1) * m(2, 2);
  const double c02 = m(0, 1) * m(1, 2) - m(0, 2) * m(1, 1);
  const double minor2 = m(0, 0) * m(1, 1) - m(0, 1) * m(0, 1);
  const double det = m(0, 0) * c00 + m(0, 1) * c01 + m(0, 2) * c02;
  if (!(m(0, 0) > 0.0) || !(minor2 > 0.0) || !(det > 0.0)) return false;
  const double r = 1.0 / det;
  inverse(0, 0) = r * c00;
  inverse(0, 1) = inverse(1, 0) = r * c01;
  inverse(0, 2) = inverse(2, 0) = r * c02;
  inverse(1, 1) = r * (m(0, 0) * m(2, 2) - m(0, 2) * m(0, 2));
  inverse(1, 2) = inverse(2, 1) = r * (m(0, 1) * m(0, 2) - m(0, 0) * m(1, 2));
  inverse(2, 2) = r * minor2;
  return true;
}

}  // namespace

void RigidDiagonalBlock::add_shifted(const RigidDiagonalBlock& b, const Vec3& d) {
  // T^T b T = [[w I, -[a + w d]x], [[a + w d]x, turn - w [d]x[d]x - [d]x[a]x - [a]x[d]x]]
  // with [u]x[v]x = v u^T - (u . v) I.
  weight += b.weight;
  arm += b.arm + b.weight * d;
  const Mat3 ad = b.arm * d.transpose();
  turn += b.turn - b.weight * (d * d.transpose()) - ad - ad.transpose();
  turn.diagonal().array() += b.weight * d.squaredNorm() + 2.0 * b.arm.dot(d);
}

void RigidDiagonalBlock::add_pair(const PairBlockSum& p) {
  // p + p^T = [[2 w I, -[r + c]x], [[r + c]x, turn + turn^T]] for p's arms r (rows), c.
  weight += 2.0 * p.weight;
  arm += p.row_arm + p.column_arm;
  turn += p.turn + p.turn.transpose();
}

bool RigidInverse::of(const RigidDiagonalBlock& block, RigidInverse& out) {
  if (!(block.weight > 0.0)) return false;
  const double iw = 1.0 / block.weight;
  Mat3 schur =
      0.5 * (block.turn + block.turn.transpose()) + iw * (block.arm * block.arm.transpose());
  schur.diagonal().array() -= iw * block.arm.squaredNorm();
  Mat3 s_inverse;
  if (!spd_inverse3(schur, s_inverse)) return false;
  out.inverse_weight = float(iw);
  out.arm = block.arm.cast<float>();
  out.schur_inverse = Symmetric3f::of(s_inverse);
  return true;
}

Symmetric3f Symmetric3f::of(const Mat3& m) {
  Symmetric3f s;
  s[0] = float(m(0, 0));
  s[1] = float(0.5 * (m(0, 1) + m(1, 0)));
  s[2] = float(0.5 * (m(0, 2) + m(2, 0)));
  s[3] = float(m(1, 1));
  s[4] = float(0.5 * (m(1, 2) + m(2, 1)));
  s[5] = float(m(2, 2));
  return s;
}

Mat3 Symmetric3f::widened() const {
  const Symmetric3f& s = *this;
  Mat3 m;
  m << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
  return m;
}

DiagonalBlock DiagonalBlock::of(const RigidDiagonalBlock& block) {
  DiagonalBlock out;
  out.weight = float(block.weight);
  out.arm = block.arm.cast<float>();
  out.turn = Symmetric3f::of(block.turn);
  return out;
}

RigidDiagonalBlock DiagonalBlock::widened() const {
  RigidDiagonalBlock out;
  out.weight = double(weight);
  out.arm = arm.cast<double>();
  out.turn = turn.widened();
  return out;
}

Mat6 RigidDiagonalBlock::dense() const {
  Mat6 b;
  const Mat3 ax = cross_matrix(arm);
  b.topLeftCorner<3, 3>() = weight * Mat3::Identity();
  b.topRightCorner<3, 3>() = -ax;
  b.bottomLeftCorner<3, 3>() = ax;
  b.bottomRightCorner<3, 3>() = turn;
  return b;
}

}  // namespace primo
