#include "primo/solve/rigid_multigrid.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "prefetch.h"
#include "primo/solve/body_partition.h"
#include "primo/solve/cluster_hierarchy.h"
#include "primo/util/parallel.h"
#include "rigid_blocks.h"

namespace primo {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// A sweep's rows depend on each other, so the processor cannot run far enough ahead to load
// the next rows' blocks while it computes; it is told to, a few rows ahead (at 240k faces a
// cycle took 44 instead of 53 ms, in alternating runs).
constexpr size_t kPrefetchRows = 3;
void prefetch_row(const BlockMatrix& a, const std::vector<RigidInverse>& diag_inverse, int row) {
  prefetch_bytes(
      a.row_block.data() + a.row_begin[size_t(row)],
      size_t(a.row_begin[size_t(row) + 1] - a.row_begin[size_t(row)]) * sizeof(PairBlock));
  prefetch_bytes(&diag_inverse[size_t(row)], sizeof(RigidInverse));
}

// The Galerkin projection gathers each coarse block from finer pair blocks scattered through
// the finer matrix: it fetches them this many ahead (the set-up at 240k faces: 52-56 ms
// instead of 62-64).
constexpr int kGatherAhead = 4;

// Rows a smoothing part has on the coarse levels. A row of a sweep costs about 100 ns where a
// body's match costs 300 (kBodiesPerPart is for those), and with 2,000 rows a part the 240k
// mesh's third level (2,792 clusters) was one part, swept on one thread 8 times a cycle. With
// 500: MultigridCycle/4800 42-50 ms (least, median of 15) against 48-52, the 240k full solve's
// steps 2557, 2702 ms against 2955, 2864 (the same 10 steps, 34 CG iterations), the koala's
// 1682, 1617 against 1614, 1497 (noise at its size); and more cores get more parts to share.
constexpr size_t kCoarseRowsPerPart = 500;

}  // namespace

struct RigidMultigrid::Level {
  const BlockMatrix* matrix = nullptr;  // the caller's on the fine level, else `own`
  BlockMatrix own;
  BodyPartition partition;
  std::vector<RigidInverse> diag_inverse;
  std::vector<Vec3> position;  // of the bodies, at set_matrix
  // Towards the next coarser level (empty on the coarsest):
  std::vector<int> parent;  // body -> cluster
  std::vector<Vec3> arm;    // body position - its cluster's
  // Galerkin sources of this level's blocks in the next finer level (empty on the fine one):
  Groups children;  // cluster -> finer bodies
  Groups internal;  // cluster -> finer pairs inside it
  Groups sources;   // pair -> finer pairs joining its two clusters
  // Positions as the means of the children's.
  void take_mean_positions(const Level& finer) {
    parallel_chunks(position.size(), kParallelGrain, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; ++c) {
        Vec3 sum = Vec3::Zero();
        for (int k = children.begin[c]; k < children.begin[c + 1]; ++k)
          sum += finer.position[size_t(children.items[size_t(k)])];
        position[c] = sum / double(children.begin[c + 1] - children.begin[c]);
      }
    });
  }
  std::vector<Eigen::Vector3f> arm_f;  // `arm` for the cycle's transfers
  // Each row's block slots, those of rows its forward sweep reaches before it first
  // (`slots_before` of them). A cycle's first sweep starts from zero: a row's product then
  // only needs the rows swept before it (the others are still zero), and the residual after
  // it only the rows swept after it (what they changed since the row was solved). Each reads
  // half of every row's blocks instead of all of them twice.
  std::vector<int> slots, slots_before;
  // sum of row b's blocks times x over its slots [first, last) (counted from the row's first).
  Vec6f slots_product(int b, int first, int last, const BlockVectorF& x) const {
    const BlockMatrix& a = *matrix;
    Vec6f sum = Vec6f::Zero();
    for (int k = a.row_begin[size_t(b)] + first; k < a.row_begin[size_t(b)] + last; ++k) {
      const size_t slot = size_t(slots[size_t(k)]);
      a.row_block[slot].add_product(x[size_t(a.row_column[slot])], sum);
    }
    return sum;
  }
  // For the level's matrix (every fine matrix has the pairs the multigrid was made for, and
  // so the same slots).
  void order_slots() {
    if (!slots_before.empty() && slots.size() == matrix->row_column.size()) return;
    const BlockMatrix& a = *matrix;
    const size_t n = a.diag.size();
    std::vector<int> rank(n, -1);
    int next = 0;
    for (const std::vector<int>& colour : partition.colours)
      for (const int part : colour)
        for (const int row : partition.parts[size_t(part)]) rank[size_t(row)] = next++;
    slots.resize(a.row_column.size());
    slots_before.assign(n, 0);
    for (size_t b = 0; b < n; ++b) {
      int front = a.row_begin[b];
      for (int k = a.row_begin[b]; k < a.row_begin[b + 1]; ++k)
        if (rank[size_t(a.row_column[size_t(k)])] < rank[b]) slots[size_t(front++)] = k;
      slots_before[b] = front - a.row_begin[b];
      for (int k = a.row_begin[b]; k < a.row_begin[b + 1]; ++k)
        if (!(rank[size_t(a.row_column[size_t(k)])] < rank[b])) slots[size_t(front++)] = k;
    }
  }
  BlockVectorF rhs, x, residual;
  BlockVectorF krylov[5];  // work vectors of the K-cycle's coarse correction
};

struct RigidMultigrid::Coarsest {
  SparseMatrix matrix;  // lower triangle, all 36 entries of every block
  std::vector<std::array<int, 36>> diag_slots, off_slots;
  Eigen::CholmodSimplicialLLT<SparseMatrix, Eigen::Lower> factor;
  bool analyzed = false;
};

MultigridRows multigrid_rows(const RigidSystem& fine) {
  const int n = fine.n_bodies();
  std::vector<int> all(static_cast<size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  std::vector<Vec3> position(static_cast<size_t>(n));
  for (int b = 0; b < n; ++b) position[size_t(b)] = fine.bodies[size_t(b)].rest_center;
  MultigridRows rows;
  rows.partition = partition_bodies(std::move(all), position, moving_coupling_edges(fine));
  // Partitioning the rows (the same positions and pairs, renumbered) would give these parts
  // as runs of rows: each bisection splits the same set, and ties at a median go by index,
  // which the rows order as the bodies' split ordered them. The colours stay.
  rows.order.reserve(size_t(n));
  for (std::vector<int>& part : rows.partition.parts)
    for (int& body : part) {
      rows.order.push_back(body);
      body = int(rows.order.size()) - 1;
    }
  return rows;
}

RigidMultigrid::RigidMultigrid(const RigidSystem& fine,
                               const std::vector<std::pair<int, int>>& fine_pairs,
                               const MultigridOptions& options, const std::vector<int>& fine_order,
                               BodyPartition fine_partition)
    : options_(options) {
  HierarchyOptions hierarchy_options;
  hierarchy_options.cluster_size = options.cluster_size;
  hierarchy_options.coarsest_max_bodies = options.coarsest_max_bodies;
  hierarchy_options.max_levels = 12;
  const ClusterHierarchy hierarchy = build_cluster_hierarchy(fine, hierarchy_options);

  const int n_fine = fine.n_bodies();
  // Each body's row on the level being built (its cluster's on coarse levels).
  std::vector<int> row_of_body(static_cast<size_t>(n_fine));
  for (int r = 0; r < n_fine; ++r)
    row_of_body[size_t(fine_order.empty() ? r : fine_order[size_t(r)])] = r;
  auto fine_level = std::make_unique<Level>();
  fine_level->own.set_structure(0, {});
  fine_level->position.resize(size_t(n_fine));
  for (int b = 0; b < n_fine; ++b)
    fine_level->position[size_t(row_of_body[size_t(b)])] = fine.bodies[size_t(b)].rest_center;
  if (hierarchy.coarse_levels() > 0 && !fine_partition.parts.empty()) {
    fine_level->partition = std::move(fine_partition);
  } else if (hierarchy.coarse_levels() > 0) {
    std::vector<int> all(static_cast<size_t>(n_fine));
    std::iota(all.begin(), all.end(), 0);
    fine_level->partition = partition_bodies(std::move(all), fine_level->position, fine_pairs);
  }
  std::vector<std::pair<int, int>> pairs = fine_pairs;
  int n = n_fine;
  levels_.push_back(std::move(fine_level));
  for (int l = 0; l < hierarchy.coarse_levels(); ++l) {
    Level& finer = *levels_.back();
    const int n_coarse = hierarchy.cluster_count[size_t(l)];
    std::vector<int> parent(size_t(n), -1);
    for (int b = 0; b < n_fine; ++b)
      parent[size_t(row_of_body[size_t(b)])] = hierarchy.cluster_of[size_t(l)][size_t(b)];
    auto level = std::make_unique<Level>();
    Level& coarse = *level;
    // The clusters' children and rest positions, and the finer pairs as pairs of clusters.
    std::vector<std::pair<int, int>> edges(pairs.size());
    auto take_parents = [&] {
      coarse.children = group_by(parent, n_coarse);
      coarse.position.resize(size_t(n_coarse));
      coarse.take_mean_positions(finer);
      for (size_t p = 0; p < pairs.size(); ++p)
        edges[p] = {parent[size_t(pairs[p].first)], parent[size_t(pairs[p].second)]};
    };
    take_parents();
    if (l + 1 < hierarchy.coarse_levels()) {
      // A level that is swept (all but the coarsest) gets its smoothing partition by its
      // clusters' rest positions, and its clusters are numbered part after part, so that each
      // part's rows are contiguous.
      std::vector<int> all(static_cast<size_t>(n_coarse));
      std::iota(all.begin(), all.end(), 0);
      coarse.partition =
          partition_bodies(std::move(all), coarse.position, edges, kCoarseRowsPerPart);
      std::vector<int> renumbered(size_t(n_coarse), -1);
      int next = 0;
      for (std::vector<int>& part : coarse.partition.parts)
        for (int& c : part) c = renumbered[size_t(c)] = next++;  // stays ascending
      for (int& c : parent) c = renumbered[size_t(c)];
      take_parents();
    }
    finer.parent = std::move(parent);
    // Finer pairs inside a cluster add to its diagonal block, the others to the block of
    // their clusters' pair.
    std::vector<int> inside(pairs.size(), -1);
    for (size_t p = 0; p < pairs.size(); ++p)
      if (edges[p].first == edges[p].second) inside[p] = edges[p].first;
    PairNumbering numbering = number_pairs(edges);
    coarse.internal = group_by(inside, n_coarse);
    coarse.sources = group_by(numbering.pair_of, int(numbering.pairs.size()));
    std::vector<std::pair<int, int>> coarse_pairs = std::move(numbering.pairs);
    coarse.own.set_structure(n_coarse, coarse_pairs);
    coarse.matrix = &coarse.own;
    pairs = std::move(coarse_pairs);
    n = n_coarse;
    for (int& row : row_of_body) row = levels_.back()->parent[size_t(row)];
    levels_.push_back(std::move(level));
  }
  // The work vectors of set_matrix and the cycles, made now on every core: made by the first
  // step instead, their first touch was a step's page faults (about 35 MB at 240k faces).
  for (size_t l = 0; l < levels_.size(); ++l) {
    Level& level = *levels_[l];
    const size_t rows = level.position.size();
    parallel_assign(level.x, rows, Vec6f::Zero().eval());
    parallel_assign(level.rhs, rows, Vec6f::Zero().eval());
    if (l + 1 == levels_.size()) continue;
    parallel_assign(level.residual, rows, Vec6f::Zero().eval());
    parallel_assign(level.arm, rows, Vec3::Zero().eval());
    parallel_assign(level.arm_f, rows, Eigen::Vector3f::Zero().eval());
    parallel_assign(level.diag_inverse, rows, RigidInverse{0.0f, Eigen::Vector3f::Zero(), {}});
    if (l > 0 && options_.coarse_visits > 1)  // the levels krylov_correction solves on
      for (BlockVectorF& v : level.krylov) parallel_assign(v, rows, Vec6f::Zero().eval());
  }
  // The coarsest matrix's pattern, analysed once.
  coarsest_ = std::make_unique<Coarsest>();
  const Level& last = *levels_.back();
  const BlockMatrix& structure = last.own;
  const int nc = levels_.size() == 1 ? n_fine : structure.size();
  const std::vector<std::pair<int, int>>& last_pairs =
      levels_.size() == 1 ? fine_pairs : structure.pairs;
  std::vector<Eigen::Triplet<double>> triplets;
  auto add_block = [&](int rb, int cb) {
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c)
        if (6 * rb + r >= 6 * cb + c) triplets.emplace_back(6 * rb + r, 6 * cb + c, 0.0);
  };
  for (int b = 0; b < nc; ++b) add_block(b, b);
  for (const auto& [hi, lo] : last_pairs) add_block(hi, lo);
  Coarsest& co = *coarsest_;
  co.matrix.resize(6 * nc, 6 * nc);
  co.matrix.setFromTriplets(triplets.begin(), triplets.end());
  co.matrix.makeCompressed();
  auto block_slots = [&](int rb, int cb) {
    std::array<int, 36> s;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) {
        const int gr = 6 * rb + r, gc = 6 * cb + c;
        if (gr < gc) {
          s[size_t(r * 6 + c)] = -1;
          continue;
        }
        const int* rows = co.matrix.innerIndexPtr();
        const int begin = co.matrix.outerIndexPtr()[gc], end = co.matrix.outerIndexPtr()[gc + 1];
        s[size_t(r * 6 + c)] = int(std::lower_bound(rows + begin, rows + end, gr) - rows);
      }
    return s;
  };
  co.diag_slots.resize(size_t(nc));
  for (int b = 0; b < nc; ++b) co.diag_slots[size_t(b)] = block_slots(b, b);
  co.off_slots.resize(last_pairs.size());
  for (size_t p = 0; p < last_pairs.size(); ++p)
    co.off_slots[p] = block_slots(last_pairs[p].first, last_pairs[p].second);
  co.factor.cholmod().print = 0;
}

RigidMultigrid::~RigidMultigrid() = default;

int RigidMultigrid::levels() const { return int(levels_.size()); }
int RigidMultigrid::bodies(int level) const { return int(levels_[size_t(level)]->position.size()); }

bool RigidMultigrid::set_matrix(const BlockMatrix& fine, const std::vector<Vec3>& position) {
  levels_[0]->matrix = &fine;
  parallel_copy(position, levels_[0]->position);
  for (size_t l = 0; l + 1 < levels_.size(); ++l) {
    Level& finer = *levels_[l];
    Level& coarse = *levels_[l + 1];
    const BlockMatrix& a = *finer.matrix;
    const int nc = coarse.own.size();
    // The clusters' points and the bodies' arms from them.
    coarse.take_mean_positions(finer);
    finer.arm.resize(finer.parent.size());
    finer.arm_f.resize(finer.parent.size());
    parallel_chunks(finer.parent.size(), kParallelGrain, [&](size_t begin, size_t end) {
      for (size_t b = begin; b < end; ++b) {
        finer.arm[b] = finer.position[b] - coarse.position[size_t(finer.parent[b])];
        finer.arm_f[b] = finer.arm[b].cast<float>();
      }
    });
    BlockMatrix& m = coarse.own;
    // Each cluster's block from its bodies', and (every body in one cluster) the bodies'
    // inverse blocks for the finer level's smoother while they are at hand.
    std::vector<char> failed(size_t(nc), 0);
    finer.diag_inverse.resize(a.diag.size());
    parallel_chunks(size_t(nc), kParallelGrain / 8, [&](size_t begin, size_t end) {
      const int internal_end = coarse.internal.begin[end];  // prefetches stay in the chunk
      for (size_t c = begin; c < end; ++c) {
        RigidDiagonalBlock sum;
        for (int k = coarse.children.begin[c]; k < coarse.children.begin[c + 1]; ++k) {
          const size_t b = size_t(coarse.children.items[size_t(k)]);
          const RigidDiagonalBlock child = a.diag[b].widened();
          if (!RigidInverse::of(child, finer.diag_inverse[b])) failed[c] = 1;
          sum.add_shifted(child, finer.arm[b]);
        }
        for (int k = coarse.internal.begin[c]; k < coarse.internal.begin[c + 1]; ++k) {
          if (k + kGatherAhead < internal_end)
            prefetch_bytes(&a.off(size_t(coarse.internal.items[size_t(k + kGatherAhead)])),
                           sizeof(PairBlock));
          const size_t p = size_t(coarse.internal.items[size_t(k)]);
          const auto [i, j] = a.pairs[p];
          sum.add_pair(a.off(p).cast<double>().shifted(finer.arm[size_t(i)], finer.arm[size_t(j)]));
        }
        m.diag[c] = DiagonalBlock::of(sum);
      }
    });
    if (std::find(failed.begin(), failed.end(), 1) != failed.end()) return false;
    finer.order_slots();
    parallel_chunks(m.pairs.size(), kParallelGrain / 8, [&](size_t begin, size_t end) {
      const int sources_end = coarse.sources.begin[end];  // prefetches stay in the chunk
      for (size_t q = begin; q < end; ++q) {
        PairBlockSum sum = PairBlockSum::Zero();
        for (int k = coarse.sources.begin[q]; k < coarse.sources.begin[q + 1]; ++k) {
          if (k + kGatherAhead < sources_end)
            prefetch_bytes(&a.off(size_t(coarse.sources.items[size_t(k + kGatherAhead)])),
                           sizeof(PairBlock));
          const size_t p = size_t(coarse.sources.items[size_t(k)]);
          const auto [i, j] = a.pairs[p];
          const PairBlockSum block = a.off(p).cast<double>();
          // The finer pair's first body lies in the coarse pair's first cluster, or the other way.
          if (finer.parent[size_t(i)] == m.pairs[q].first)
            sum += block.shifted(finer.arm[size_t(i)], finer.arm[size_t(j)]);
          else
            sum += block.transposed().shifted(finer.arm[size_t(j)], finer.arm[size_t(i)]);
        }
        m.set_off(q, sum.cast<BlockScalar>());
      }
    });
  }
  // The coarsest level's factor.
  Coarsest& co = *coarsest_;
  const BlockMatrix& last = *levels_.back()->matrix;
  double* values = co.matrix.valuePtr();
  std::fill(values, values + co.matrix.nonZeros(), 0.0);
  for (size_t b = 0; b < last.diag.size(); ++b) {
    const Mat6 block = last.diag[b].dense();
    for (int k = 0; k < 36; ++k)
      if (co.diag_slots[b][size_t(k)] >= 0)
        values[co.diag_slots[b][size_t(k)]] += block(k / 6, k % 6);
  }
  for (size_t p = 0; p < last.pairs.size(); ++p) {
    const Mat6 block = last.off(p).dense();
    for (int k = 0; k < 36; ++k)
      if (co.off_slots[p][size_t(k)] >= 0)
        values[co.off_slots[p][size_t(k)]] += block(k / 6, k % 6);
  }
  if (!co.analyzed) {
    co.factor.analyzePattern(co.matrix);
    co.analyzed = true;
  }
  co.factor.factorize(co.matrix);
  return co.factor.info() == Eigen::Success;
}

void RigidMultigrid::sweep(const Level& level, const BlockVectorF& rhs, BlockVectorF& x,
                           Sweep direction) const {
  const bool forward = direction != Sweep::Backward;
  const BlockMatrix& a = *level.matrix;
  const auto& colours = level.partition.colours;
  const auto& parts = level.partition.parts;
  const size_t n_colours = colours.size();
  for (size_t k = 0; k < n_colours; ++k) {
    const std::vector<int>& colour = colours[forward ? k : n_colours - 1 - k];
    parallel_tasks(colour.size(), [&](size_t t) {
      const std::vector<int>& part = parts[size_t(colour[t])];
      const size_t m = part.size();
      for (size_t i = 0; i < m; ++i) {
        const int b = part[forward ? i : m - 1 - i];
        if (i + kPrefetchRows < m)
          prefetch_row(a, level.diag_inverse,
                       part[forward ? i + kPrefetchRows : m - 1 - kPrefetchRows - i]);
        const Vec6f off = direction == Sweep::FromZero
                              ? level.slots_product(b, 0, level.slots_before[size_t(b)], x)
                          : forward ? a.off_product(b, x)
                                    : a.off_product_descending(b, x);
        x[size_t(b)] = level.diag_inverse[size_t(b)].times(Vec6f(rhs[size_t(b)] - off));
      }
    });
  }
}

void RigidMultigrid::cycle(size_t l, const BlockVectorF& rhs, BlockVectorF& x) {
  Level& level = *levels_[l];
  const BlockMatrix& a = *level.matrix;
  const size_t n = a.diag.size();
  x.resize(n);
  if (l + 1 == levels_.size()) {
    Eigen::VectorXd b(6 * Eigen::Index(n));
    for (size_t i = 0; i < n; ++i) b.segment<6>(6 * Eigen::Index(i)) = rhs[i].cast<double>();
    const Eigen::VectorXd solution = coarsest_->factor.solve(b);
    for (size_t i = 0; i < n; ++i) x[i] = solution.segment<6>(6 * Eigen::Index(i)).cast<float>();
    return;
  }
  parallel_chunks(n, kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) x[b].setZero();
  });
  level.residual.resize(n);
  if (options_.smoothing_sweeps == 1) {
    sweep(level, rhs, x, Sweep::FromZero);
    // Each row was solved with the rows before it as they are now and the rows after it at
    // zero: its residual is what the rows after it add.
    parallel_chunks(n, kBlockRowGrain, [&](size_t begin, size_t end) {
      for (size_t b = begin; b < end; ++b)
        level.residual[b] = -level.slots_product(int(b), level.slots_before[b],
                                                 a.row_begin[b + 1] - a.row_begin[b], x);
    });
  } else {
    for (int s = 0; s < options_.smoothing_sweeps; ++s) sweep(level, rhs, x, Sweep::Forward);
    parallel_chunks(n, kBlockRowGrain, [&](size_t begin, size_t end) {
      for (size_t b = begin; b < end; ++b) level.residual[b] = rhs[b] - a.row_product(int(b), x);
    });
  }
  Level& coarse = *levels_[l + 1];
  const size_t nc = coarse.own.diag.size();
  coarse.rhs.resize(nc);
  parallel_chunks(nc, kParallelGrain / 8, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      Vec6f sum = Vec6f::Zero();
      for (int k = coarse.children.begin[c]; k < coarse.children.begin[c + 1]; ++k) {
        const size_t b = size_t(coarse.children.items[size_t(k)]);
        const Vec6f& r = level.residual[b];
        sum.head<3>() += r.head<3>();
        sum.tail<3>() += level.arm_f[b].cross(Eigen::Vector3f(r.head<3>())) + r.tail<3>();
      }
      coarse.rhs[c] = sum;
    }
  });
  if (options_.coarse_visits > 1 && l + 2 < levels_.size())
    krylov_correction(l + 1);
  else
    cycle(l + 1, coarse.rhs, coarse.x);
  parallel_chunks(n, kBlockRowGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const Vec6f& c = coarse.x[size_t(level.parent[b])];
      x[b].head<3>() += c.head<3>() + Eigen::Vector3f(c.tail<3>()).cross(level.arm_f[b]);
      x[b].tail<3>() += c.tail<3>();
    }
  });
  for (int s = 0; s < options_.smoothing_sweeps; ++s) sweep(level, rhs, x, Sweep::Backward);
}

namespace {
// K sums over the rows of what row_terms(b, sums) adds to them for row b, each summed as dot()
// sums (the same chunks, rows in order): several dot products in one pass over their vectors
// with the same bits as one dot() each. The K-cycle took seven passes for its five
// coefficients and two norms.
template <size_t K, class RowTerms>
std::array<double, K> row_sums(size_t n, RowTerms&& row_terms) {
  using Sums = std::array<double, K>;
  return parallel_reduce(
      n, kParallelGrain, Sums{},
      [&](size_t begin, size_t end) {
        Sums sums{};
        for (size_t b = begin; b < end; ++b) row_terms(b, sums);
        return sums;
      },
      [](Sums a, const Sums& b) {
        for (size_t k = 0; k < K; ++k) a[k] += b[k];
        return a;
      });
}

// v[0] . v[1], v[2] . v[3], ... in one pass.
template <size_t K>
std::array<double, K> dots(const std::array<const BlockVectorF*, 2 * K>& v) {
  return row_sums<K>(v[0]->size(), [&](size_t b, std::array<double, K>& sums) {
    for (size_t k = 0; k < K; ++k) sums[k] += double((*v[2 * k])[b].dot((*v[2 * k + 1])[b]));
  });
}

void scale_into(double factor, const BlockVectorF& v, BlockVectorF& x) {
  parallel_chunks(v.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) x[b] = factor * v[b];
  });
}
}  // namespace

// Two steps of flexible conjugate gradients on the coarse level's system, preconditioned by
// its own cycle (Notay and Vassilevski's K-cycle): the coarse correction then nearly solves the
// coarse problem, as a two-level method's would, at the cost of two coarse cycles. The
// second step is skipped when the first left less than a quarter of the residual.
void RigidMultigrid::krylov_correction(size_t l) {
  Level& level = *levels_[l];
  const BlockMatrix& a = level.own;
  const size_t n = a.diag.size();
  const BlockVectorF& rhs = level.rhs;
  BlockVectorF& v1 = level.krylov[0];
  BlockVectorF& w1 = level.krylov[1];
  BlockVectorF& r2 = level.krylov[2];
  BlockVectorF& v2 = level.krylov[3];
  BlockVectorF& w2 = level.krylov[4];
  cycle(l, rhs, v1);
  a.multiply(v1, w1);
  const std::array<double, 2> first = dots<2>({&v1, &w1, &v1, &rhs});
  const double rho1 = first[0], alpha1 = first[1];
  BlockVectorF& x = level.x;
  x.resize(n);
  if (!(rho1 > 0.0)) {
    parallel_copy(v1, x);
    return;
  }
  // r2 = rhs - (alpha1 / rho1) w1 and the two norms in one pass.
  r2.resize(n);
  const std::array<double, 2> norms = row_sums<2>(n, [&](size_t b, std::array<double, 2>& sums) {
    r2[b] = rhs[b] - (alpha1 / rho1) * w1[b];
    sums[0] += double(r2[b].dot(r2[b]));
    sums[1] += double(rhs[b].dot(rhs[b]));
  });
  if (norms[0] <= 0.0625 * norms[1]) {
    scale_into(alpha1 / rho1, v1, x);
    return;
  }
  cycle(l, r2, v2);
  a.multiply(v2, w2);
  const std::array<double, 3> second = dots<3>({&v2, &w1, &v2, &w2, &v2, &r2});
  const double gamma = second[0], beta = second[1], alpha2 = second[2];
  const double rho2 = beta - gamma * gamma / rho1;
  if (!(rho2 > 0.0)) {
    scale_into(alpha1 / rho1, v1, x);
    return;
  }
  const double c1 = alpha1 / rho1 - gamma * alpha2 / (rho1 * rho2), c2 = alpha2 / rho2;
  parallel_chunks(n, kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) x[b] = c1 * v1[b] + c2 * v2[b];
  });
}

void RigidMultigrid::apply(const BlockVector& r, BlockVector& z) {
  Level& fine = *levels_[0];
  const size_t n = r.size();
  fine.rhs.resize(n);
  parallel_chunks(n, kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) fine.rhs[b] = r[b].cast<float>();
  });
  cycle(0, fine.rhs, fine.x);
  z.resize(n);
  parallel_chunks(n, kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) z[b] = fine.x[b].cast<double>();
  });
}

}  // namespace primo
