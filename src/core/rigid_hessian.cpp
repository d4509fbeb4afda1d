#include "primo/rigid_hessian.h"

#include <algorithm>

#include "primo/global_solver.h"
#include "primo/parallel.h"
#include "rigid_blocks.h"

namespace primo {
namespace {

constexpr size_t kBodyGrain = kParallelGrain / 8;  // a body's blocks cost a few thousand flops

}  // namespace

RigidHessian::RigidHessian(const RigidSystem& system, std::vector<int> order)
    : system_(system), order_(std::move(order)) {
  const int n = system.n_bodies();
  if (order_.empty()) {
    order_.resize(size_t(n));
    for (int b = 0; b < n; ++b) order_[size_t(b)] = b;
  }
  row_of_.assign(size_t(n), -1);
  for (int r = 0; r < n; ++r) row_of_[size_t(order_[size_t(r)])] = r;
  mask_.resize(size_t(n));
  for (int r = 0; r < n; ++r)
    mask_[size_t(r)] = active_mask(system.bodies[size_t(order_[size_t(r)])].kind);
  // One block per pair of coupled bodies that both move, numbered in coupling order.
  std::vector<std::pair<int, int>> edges = moving_coupling_edges(system);
  for (auto& [a, b] : edges)
    if (a >= 0) {
      a = row_of_[size_t(a)];
      b = row_of_[size_t(b)];
    }
  PairNumbering numbering = number_pairs(edges);
  coupling_pair_ = std::move(numbering.pair_of);
  matrix_.set_structure(n, std::move(numbering.pairs));
  gradient_.assign(size_t(n), Vec6::Zero());
}

void RigidHessian::assemble(const std::vector<BodyState>& state, bool second_order) {
  const RigidSystem& sys = system_;
  // One pass, row by row: a row's couplings give its diagonal block and gradient, and, for
  // the pairs whose first row it is, their off-diagonal blocks from the same residuals (the
  // modes turned into world orientation once per coupling side, not once more per pair).
  parallel_chunks(size_t(sys.n_bodies()), kBodyGrain, [&](size_t begin, size_t end) {
    std::vector<std::pair<int, Mat6>> crosses;  // this row's pairs' blocks
    for (size_t row = begin; row < end; ++row) {
      const size_t b = size_t(order_[row]);
      Mat6 h = Mat6::Zero();
      Vec6 g = Vec6::Zero();
      Mat3 s = Mat3::Zero();
      crosses.clear();
      const int mask = mask_[row];
      if (mask != 0) {
        for (int k = sys.coupling_begin[b]; k < sys.coupling_begin[b + 1]; ++k) {
          const auto [ci, side] = sys.body_couplings[size_t(k)];
          const RigidSystem::Coupling& c = sys.couplings[size_t(ci)];
          const int pair = coupling_pair_[size_t(ci)];
          const bool first = pair >= 0 && matrix_.pairs[size_t(pair)].first == int(row);
          Mat6 cross = Mat6::Zero();  // rows: side 0's dofs
          for_each_residual(c, state[size_t(c.body[0])], state[size_t(c.body[1])],
                            [&, side = side](const Vec3& y0, const Vec3& y1, const Vec3& r,
                                             double w, bool point) {
                              if (side == 0)
                                FeatureBlocks::add_own(h, g, s, y0, r, w, point);
                              else
                                FeatureBlocks::add_own(h, g, s, y1, -r, w, point);
                              if (first) FeatureBlocks::add_cross(cross, y0, y1, w, point);
                            });
          if (!first) continue;
          if (side != 0) cross.transposeInPlace();  // rows: this row's dofs
          auto known = std::find_if(crosses.begin(), crosses.end(),
                                    [&](const auto& e) { return e.first == pair; });
          if (known == crosses.end())
            crosses.emplace_back(pair, cross);
          else
            known->second += cross;
        }
        for (int k = sys.spring_begin[b]; k < sys.spring_begin[b + 1]; ++k) {
          const RigidSystem::Spring& spring = sys.springs[size_t(sys.body_springs[size_t(k)])];
          const Vec3 y = state[b].rotation * spring.local;
          FeatureBlocks::add_own(h, g, s, y, y + state[b].position - spring.target, spring.weight,
                                 true);
        }
      }
      for (int d = 0; d < 6; ++d)
        if (!(mask & (1 << d))) {
          h.row(d).setZero();
          h.col(d).setZero();
          h(d, d) = 1.0;
          g[d] = 0.0;
        }
      if (second_order && (mask & 0x38)) h.block<3, 3>(3, 3) += s;
      matrix_.diag[row] = h.cast<BlockScalar>();
      gradient_[row] = g;
      for (auto& [pair, h01] : crosses) {
        const int m1 = mask_[size_t(matrix_.pairs[size_t(pair)].second)];
        for (int d = 0; d < 6; ++d) {
          if (!(mask & (1 << d))) h01.row(d).setZero();
          if (!(m1 & (1 << d))) h01.col(d).setZero();
        }
        matrix_.set_off(size_t(pair), h01.cast<BlockScalar>());
      }
    }
  });
}

std::vector<BodyState> RigidHessian::moved(const std::vector<BodyState>& state,
                                           const BlockVector& step, double lambda) const {
  std::vector<BodyState> next = state;
  parallel_chunks(state.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t row = begin; row < end; ++row) {
      const size_t b = size_t(order_[row]);
      const Vec6 d = lambda * step[row];
      if (mask_[row] & 0x38)
        next[b].rotation = rotation_from_vector(d.tail<3>()) * state[b].rotation;
      if (mask_[row] & 0x07) next[b].position = state[b].position + d.head<3>();
    }
  });
  return next;
}

}  // namespace primo
