#pragma once
// The blocks of the joint and spring energy's derivatives in the rigid motions of the bodies,
// shared by global Newton matching (global_solver.cpp) and the Newton-Krylov steps
// (newton_krylov.cpp). A body's motion is linearized as dX = v + omega x y, y = R * local:
// local dof order v (0..2), omega (3..5).

#include <utility>
#include <vector>

#include "primo/model/bilinear_inner_product.h"
#include "primo/model/rigid_system.h"

namespace primo {

// Bit k set when local dof k moves.
inline int active_mask(BodyKind kind) {
  switch (kind) {
    case BodyKind::Free:
      return 0x3F;
    case BodyKind::PinnedPosition:
      return 0x38;
    case BodyKind::FixedRotation:
      return 0x07;
    case BodyKind::Fixed:
      return 0;
  }
  return 0;
}

// The couplings as edges between bodies, (-1, -1) where a side cannot move (a fixed handle):
// such a coupling adds to the other side's diagonal block only, never to a pair's.
inline std::vector<std::pair<int, int>> moving_coupling_edges(const RigidSystem& system) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(system.couplings.size());
  for (const RigidSystem::Coupling& c : system.couplings) {
    const bool moving = active_mask(system.bodies[size_t(c.body[0])].kind) != 0 &&
                        active_mask(system.bodies[size_t(c.body[1])].kind) != 0;
    edges.emplace_back(moving ? c.body[0] : -1, moving ? c.body[1] : -1);
  }
  return edges;
}

inline Mat3 cross_matrix(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// w (|y|^2 I - y y^T) = w [y]x^T [y]x
inline void add_rotational_inertia(Eigen::Ref<Mat3> m, const Vec3& y, double w) {
  m.noalias() -= w * y * y.transpose();
  m.diagonal().array() += w * y.squaredNorm();
}

// Calls residual(y0, y1, r, w, point) for the four modes of a coupling in the given states
// (y_s the side's mode turned into world orientation, r = X_0 - X_1): the mean as a point,
// the derivatives as vectors.
template <class Residual>
void for_each_residual(const RigidSystem::Coupling& c, const BodyState& s0, const BodyState& s1,
                       Residual&& residual) {
  const Vec3 p0 = s0.rotation * c.local[0].mean, p1 = s1.rotation * c.local[1].mean;
  residual(p0, p1, (p0 + s0.position) - (p1 + s1.position), c.weight, true);
  const Vec3 u0 = s0.rotation * c.local[0].du, u1 = s1.rotation * c.local[1].du;
  residual(u0, u1, u0 - u1, c.weight * kModeWeightDu, false);
  const Vec3 v0 = s0.rotation * c.local[0].dv, v1 = s1.rotation * c.local[1].dv;
  residual(v0, v1, v0 - v1, c.weight * kModeWeightDv, false);
  const Vec3 t0 = s0.rotation * c.local[0].duv, t1 = s1.rotation * c.local[1].duv;
  residual(t0, t1, t0 - t1, c.weight * kModeWeightDuv, false);
}

// Gauss-Newton blocks of one residual r = X_0 - X_1 with X_s = position_s + y_s (a point) or
// X_s = y_s (a vector, no translation), linearized as dX = v + omega x y.
struct FeatureBlocks {
  Mat6 h00 = Mat6::Zero(), h11 = Mat6::Zero(), h01 = Mat6::Zero();
  Vec6 g0 = Vec6::Zero(), g1 = Vec6::Zero();
  Mat3 s0 = Mat3::Zero(), s1 = Mat3::Zero();  // second-order rotation terms

  // One side's own blocks: its diagonal block h, gradient g and second-order term s, for the
  // residual r as seen from that side (X_own - X_other).
  static void add_own(Mat6& h, Vec6& g, Mat3& s, const Vec3& y, const Vec3& r, double w,
                      bool point) {
    if (point) {
      h.block<3, 3>(0, 0).diagonal().array() += w;
      const Mat3 c = w * cross_matrix(y);
      h.block<3, 3>(0, 3) -= c;
      h.block<3, 3>(3, 0) += c;
      g.head<3>() += w * r;
    }
    add_rotational_inertia(h.block<3, 3>(3, 3), y, w);
    g.tail<3>() += w * y.cross(r);
    // d^2/domega^2 of r . (1/2) omega x (omega x y) = (r y^T + y r^T) / 2 - (r . y) I
    const Mat3 ry = r * y.transpose();
    s += w * 0.5 * (ry + ry.transpose());
    s.diagonal().array() -= w * r.dot(y);
  }
  // The block coupling side 0's dofs (rows) to side 1's (columns).
  static void add_cross(Mat6& h01, const Vec3& y0, const Vec3& y1, double w, bool point) {
    if (point) {
      h01.block<3, 3>(0, 0).diagonal().array() -= w;
      h01.block<3, 3>(0, 3) += w * cross_matrix(y1);
      h01.block<3, 3>(3, 0) -= w * cross_matrix(y0);
    }
    h01.block<3, 3>(3, 3).noalias() += w * y1 * y0.transpose();
    h01.block<3, 3>(3, 3).diagonal().array() -= w * y0.dot(y1);
  }

  void add(const Vec3& y0, const Vec3& y1, const Vec3& r, double w, bool point) {
    add_own(h00, g0, s0, y0, r, w, point);
    add_own(h11, g1, s1, y1, -r, w, point);
    add_cross(h01, y0, y1, w, point);
  }
};

// A step's line search: lambda = 1, 1/2, ... (at most `max_halvings` halvings) until the state
// move_into(lambda, trial) writes into `trial` has an energy below `energy_before`; that state
// is swapped into `state` (and `trial` keeps the old one's memory for the next search).
// Returns the accepted lambda and its energy, or lambda 0 when none was lower.
struct HalvedStep {
  double lambda = 0.0;
  double energy = 0.0;
  int evaluations = 0;
};
template <class MoveInto>
HalvedStep halve_until_lower(const RigidSystem& system, std::vector<BodyState>& state,
                             double energy_before, int max_halvings, std::vector<BodyState>& trial,
                             MoveInto&& move_into) {
  HalvedStep result;
  double lambda = 1.0;
  for (int halving = 0; halving <= max_halvings; ++halving, lambda *= 0.5) {
    move_into(lambda, trial);
    const double e = system.energy(trial);
    ++result.evaluations;
    if (e < energy_before) {
      state.swap(trial);
      result.lambda = lambda;
      result.energy = e;
      return result;
    }
  }
  return result;
}

}  // namespace primo
