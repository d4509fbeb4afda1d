#include "primo/solve/rigid_hessian.h"

#include <algorithm>
#include <numeric>

#include "primo/solve/global_solver.h"
#include "prefetch.h"
#include "primo/util/parallel.h"
#include "rigid_blocks.h"

namespace primo {
namespace {

constexpr size_t kBodyGrain = kParallelGrain / 8;  // a body's blocks cost a few thousand flops
constexpr size_t kAssemblyAhead = 2;

// A body's own blocks (FeatureBlocks::add_own summed over its residuals) from sums that each
// residual adds to: every term of them is linear in w, w y, w r, w y y^T or w r y^T. A 6x6
// block per residual cost more than the residuals' rotations.
struct OwnSums {
  double point_weight = 0.0;
  Vec3 point_arm = Vec3::Zero();   // sum of w y over the points
  Vec3 point_pull = Vec3::Zero();  // sum of w r over the points
  Vec3 torque = Vec3::Zero();      // sum of w y x r
  Mat3 yy = Mat3::Zero();          // sum of w y y^T
  Mat3 ry = Mat3::Zero();          // sum of w r y^T
  // The couplings' parts of point_arm and yy in the body's own frame: sum of w l and of
  // w l l^T over their modes l (turned into the world once per body, in blocks()).
  Vec3 local_arm = Vec3::Zero();
  Mat3 local_yy = Mat3::Zero();

  void add(const Vec3& y, const Vec3& r, double w, bool point) {
    if (point) {
      point_weight += w;
      point_arm += w * y;
      point_pull += w * r;
    }
    const Vec3 wy = w * y;
    torque += wy.cross(r);
    yy.noalias() += wy * y.transpose();
    ry.noalias() += r * wy.transpose();
  }

  // All four residuals of a coupling as seen from its side `own` (r = X_own - X_other), from
  // its moments: with K = sum of w y_own y_other^T = R_own cross R_other^T and the point mode's
  // arms p and d = x_own - x_other, sum w y_own x r = w p_own x d - sum w y_own x y_other and
  // sum w r y_own^T = sum w y_own y_own^T - K^T + w d p_own^T. Two 3x3 products a coupling
  // instead of eight rotated modes and four outer products each (twice as many as before, as
  // every coupling is visited from both its bodies' rows). The parts that do not depend on the
  // state (w, w l, w l l^T) start the sums (RowConstants).
  void add_coupling(const Mat3& k, const Vec3& p_own, const Vec3& p_other, const Vec3& d,
                    double w) {
    point_pull += w * (p_own - p_other + d);
    torque += w * p_own.cross(d) -
              Vec3(k(1, 2) - k(2, 1), k(2, 0) - k(0, 2), k(0, 1) - k(1, 0));  // axial(K^T - K)
    ry.noalias() += (w * d) * p_own.transpose();
    ry -= k.transpose();
  }

  // h = [[W I, -[a]x], [[a]x, tr(YY) I - YY]], g = (sum w r, sum w y x r), and the
  // second-order term s = (RY + RY^T) / 2 - tr(RY) I, for the body turned by `rotation`.
  void blocks(const Mat3& rotation, RigidDiagonalBlock& h, Vec6& g, Mat3& s) const {
    const Mat3 coupled_yy = rotation * local_yy * rotation.transpose();
    const Mat3 all_yy = yy + coupled_yy, all_ry = ry + coupled_yy;
    h.weight = point_weight;
    h.arm = point_arm + rotation * local_arm;
    h.turn = -all_yy;
    h.turn.diagonal().array() += all_yy.trace();
    g << point_pull, torque;
    s = 0.5 * (all_ry + all_ry.transpose());
    s.diagonal().array() -= all_ry.trace();
  }
};

}  // namespace

RigidHessian::RigidHessian(const RigidSystem& system, std::vector<int> order)
    : system_(system), order_(std::move(order)) {
  const int n = system.n_bodies();
  if (order_.empty()) {
    order_.resize(size_t(n));
    std::iota(order_.begin(), order_.end(), 0);
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
  // Each row's couplings, their terms numbered as the rows first meet them: a coupling's first
  // row is the lower of its two, and a row numbers the couplings it meets first in its own
  // order. Built in parallel passes that each read a coupling once (at 240k faces the steps'
  // structure is built beside the first coarse factorization and took longer than it): the
  // rows' entries (the coupling in place of its terms) and constant sums; the terms, by the
  // rows that meet them first; the entries' terms.
  const std::vector<std::pair<int, int>>& sides = system.body_couplings;
  row_coupling_begin_.assign(size_t(n) + 1, 0);
  for (int r = 0; r < n; ++r) {
    const size_t b = size_t(order_[size_t(r)]);
    row_coupling_begin_[size_t(r) + 1] =
        row_coupling_begin_[size_t(r)] + system.coupling_begin[b + 1] - system.coupling_begin[b];
  }
  std::vector<int> terms_begin(size_t(n) + 1, 0);
  row_couplings_.resize(sides.size());
  row_constants_.resize(size_t(n));
  parallel_chunks(size_t(n), kBodyGrain, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      const size_t b = size_t(order_[r]);
      RowConstants& constants = row_constants_[r];
      RowCoupling* entry = &row_couplings_[size_t(row_coupling_begin_[r])];
      for (int k = system.coupling_begin[b]; k < system.coupling_begin[b + 1]; ++k, ++entry) {
        const auto [ci, side] = sides[size_t(k)];
        const RigidSystem::Coupling& c = system.couplings[size_t(ci)];
        const int other = c.body[1 - side];
        const int pair = numbering.pair_of[size_t(ci)];
        const bool writes_pair =
            pair >= 0 && numbering.pairs[size_t(pair)].first == int(r);  // its first row
        *entry = {ci, other, side, writes_pair ? pair : -1};
        if (int(r) < row_of_[size_t(other)]) ++terms_begin[r + 1];
        const PatchModes& l = c.local[side];
        const double w = c.weight;
        constants.weight += w;
        constants.arm += w * l.mean;
        auto add_mode = [&](const Vec3& mode, double weight) {
          constants.yy.noalias() += (weight * mode) * mode.transpose();
        };
        add_mode(l.mean, w);
        add_mode(l.du, w * kModeWeightDu);
        add_mode(l.dv, w * kModeWeightDv);
        add_mode(l.duv, w * kModeWeightDuv);
      }
    }
  });
  for (int r = 0; r < n; ++r) terms_begin[size_t(r) + 1] += terms_begin[size_t(r)];
  std::vector<int> terms_of(system.couplings.size(), -1);
  terms_.resize(size_t(terms_begin[size_t(n)]));
  parallel_chunks(size_t(n), kBodyGrain, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      int next = terms_begin[r];
      for (int k = row_coupling_begin_[r]; k < row_coupling_begin_[r + 1]; ++k) {
        const RowCoupling& e = row_couplings_[size_t(k)];
        if (!(int(r) < row_of_[size_t(e.other)])) continue;
        const RigidSystem::Coupling& c = system.couplings[size_t(e.terms)];
        terms_of[size_t(e.terms)] = next;
        CouplingTerms& t = terms_[size_t(next++)];
        t.cross = c.cross;
        t.mean[0] = c.local[0].mean;
        t.mean[1] = c.local[1].mean;
        t.weight = c.weight;
      }
    }
  });
  parallel_chunks(row_couplings_.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k)
      row_couplings_[k].terms = terms_of[size_t(row_couplings_[k].terms)];
  });
  matrix_.set_structure(n, std::move(numbering.pairs));
  gradient_.assign(size_t(n), Vec6::Zero());
}

void RigidHessian::assemble(const std::vector<BodyState>& state, bool second_order) {
  const RigidSystem& sys = system_;
  // One pass, row by row: a row's couplings give its diagonal block and gradient, and, for
  // the pairs whose first row it is, their off-diagonal blocks from the same residuals (the
  // modes turned into world orientation once per coupling side, not once more per pair).
  parallel_chunks(size_t(sys.n_bodies()), kBodyGrain, [&](size_t begin, size_t end) {
    std::vector<std::pair<int, PairBlockSum>> crosses;  // this row's pairs' blocks
    for (size_t row = begin; row < end; ++row) {
      const size_t b = size_t(order_[row]);
      if (row + kAssemblyAhead < end)
        for (int k = row_coupling_begin_[row + kAssemblyAhead];
             k < row_coupling_begin_[row + kAssemblyAhead + 1]; ++k)
          prefetch_bytes(&terms_[size_t(row_couplings_[size_t(k)].terms)], sizeof(CouplingTerms));
      OwnSums own;
      crosses.clear();
      const int mask = mask_[row];
      if (mask != 0) {
        const RowConstants& constants = row_constants_[row];
        own.point_weight = constants.weight;
        own.local_arm = constants.arm;
        own.local_yy = constants.yy;
        const BodyState& own_state = state[b];
        for (int k = row_coupling_begin_[row]; k < row_coupling_begin_[row + 1]; ++k) {
          const RowCoupling& e = row_couplings_[size_t(k)];
          const CouplingTerms& c = terms_[size_t(e.terms)];
          const BodyState& other_state = state[size_t(e.other)];
          const Mat3 moment =
              e.side == 0 ? Mat3(own_state.rotation * c.cross * other_state.rotation.transpose())
                          : Mat3(own_state.rotation * c.cross.transpose() *
                                 other_state.rotation.transpose());
          const Vec3 p_own = own_state.rotation * c.mean[e.side],
                     p_other = other_state.rotation * c.mean[1 - e.side],
                     d = own_state.position - other_state.position;
          own.add_coupling(moment, p_own, p_other, d, c.weight);
          if (e.pair < 0) continue;
          const int pair = e.pair;
          // The pair's block (FeatureBlocks::add_cross summed), rows this side's dofs:
          // weight -w, arms -w p, turn K^T - tr(K) I.
          PairBlockSum block;
          block.weight = -c.weight;
          block.row_arm = -c.weight * p_own;
          block.column_arm = -c.weight * p_other;
          block.turn = moment.transpose();
          block.turn.diagonal().array() -= moment.trace();
          auto known = std::find_if(crosses.begin(), crosses.end(),
                                    [&](const auto& e) { return e.first == pair; });
          if (known == crosses.end())
            crosses.emplace_back(pair, block);
          else
            known->second += block;
        }
        for (int k = sys.spring_begin[b]; k < sys.spring_begin[b + 1]; ++k) {
          const RigidSystem::Spring& spring = sys.springs[size_t(sys.body_springs[size_t(k)])];
          const Vec3 y = state[b].rotation * spring.local;
          own.add(y, y + state[b].position - spring.target, spring.weight, true);
        }
      }
      RigidDiagonalBlock h;
      Vec6 g;
      Mat3 s;
      own.blocks(state[b].rotation, h, g, s);
      // A handle's fixed rows and columns zeroed, 1 on the diagonal (active_mask: all shifts,
      // all turns or both), which keeps the block's form.
      if (!(mask & 0x07)) {
        h.weight = 1.0;
        h.arm.setZero();
        g.head<3>().setZero();
      }
      if (!(mask & 0x38)) {
        h.turn.setIdentity();
        h.arm.setZero();
        g.tail<3>().setZero();
      } else if (second_order) {
        h.turn += s;
      }
      matrix_.diag[row] = DiagonalBlock::of(h);
      gradient_[row] = g;
      for (auto& [pair, h01] : crosses) {
        // Handles fix all their shifts, all their turns, or both (active_mask).
        const int m1 = mask_[size_t(matrix_.pairs[size_t(pair)].second)];
        h01.mask(mask & 0x07, mask & 0x38, m1 & 0x07, m1 & 0x38);
        matrix_.set_off(size_t(pair), h01.cast<BlockScalar>());
      }
    }
  });
}

void RigidHessian::move_into(const std::vector<BodyState>& state, const BlockVector& step,
                             double lambda, std::vector<BodyState>& out) const {
  // In body order: the states are read and written in sequence, and only each row's step
  // (half a state's size) is gathered (row order took 8-9 ms of a 240k step's line search).
  out.resize(state.size());
  parallel_chunks(state.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const size_t row = size_t(row_of_[b]);
      const Vec6 d = lambda * step[row];
      out[b] = state[b];
      if (mask_[row] & 0x38)
        out[b].rotation = rotation_from_vector(d.tail<3>()) * state[b].rotation;
      if (mask_[row] & 0x07) out[b].position = state[b].position + d.head<3>();
    }
  });
}

}  // namespace primo
