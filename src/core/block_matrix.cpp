#include "primo/block_matrix.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

#include "primo/parallel.h"

namespace primo {

void BlockMatrix::set_structure(int n, std::vector<std::pair<int, int>> coupled_pairs) {
  pairs = std::move(coupled_pairs);
  diag.assign(size_t(n), Mat6f::Zero());
  row_begin.assign(size_t(n) + 1, 0);
  for (const auto& [a, b] : pairs) {
    ++row_begin[size_t(a) + 1];
    ++row_begin[size_t(b) + 1];
  }
  for (int b = 0; b < n; ++b) row_begin[size_t(b) + 1] += row_begin[size_t(b)];
  row_column.resize(size_t(row_begin[size_t(n)]));
  row_block.assign(row_column.size(), Mat6f::Zero());
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

void BlockMatrix::multiply(const BlockVector& x, BlockVector& y) const {
  y.resize(diag.size());
  parallel_chunks(diag.size(), kParallelGrain / 4, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b)
      y[b] = diag[b].cast<double>() * x[b] + off_product(int(b), x);
  });
}

PairNumbering number_pairs(const std::vector<std::pair<int, int>>& edges) {
  PairNumbering numbering;
  numbering.pair_of.assign(edges.size(), -1);
  std::unordered_map<std::uint64_t, int> index;
  for (size_t k = 0; k < edges.size(); ++k) {
    const auto [a, b] = edges[k];
    if (a < 0 || b < 0 || a == b) continue;
    const int hi = std::max(a, b), lo = std::min(a, b);
    const std::uint64_t key = (std::uint64_t(std::uint32_t(hi)) << 32) | std::uint32_t(lo);
    const auto [it, inserted] = index.emplace(key, int(numbering.pairs.size()));
    if (inserted) numbering.pairs.emplace_back(hi, lo);
    numbering.pair_of[k] = it->second;
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

double dot(const BlockVector& a, const BlockVector& b) {
  return parallel_sum(a.size(), kParallelGrain, 0.0, [&](size_t begin, size_t end) {
    double sum = 0.0;
    for (size_t i = begin; i < end; ++i) sum += a[i].dot(b[i]);
    return sum;
  });
}

}  // namespace primo
