#include "primo/solve/local_solver.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <thread>

#include "prefetch.h"
#include "primo/solve/body_partition.h"
#include "primo/solve/horn.h"
#include "primo/util/parallel.h"

namespace primo {

namespace {

// The optimal state of a body from the weighted moments of its point pairs (source in body
// coordinates, target in world; direction pairs enter `cross` only): cross = sum w s t^T over
// both kinds, the sums over point pairs only.
BodyState match_from_moments(BodyKind kind, const BodyState& current, double point_weight,
                             const Vec3& source_sum, const Vec3& target_sum, const Mat3& cross) {
  if (point_weight <= 0.0) return current;
  BodyState next = current;
  const Vec3 source_mean = source_sum / point_weight;
  const Vec3 target_mean = target_sum / point_weight;
  switch (kind) {
    case BodyKind::Free: {
      // Centred cross-covariance: sum w (s - s̄)(t - t̄)^T = sum w s t^T - W s̄ t̄^T.
      const Mat3 S = cross - point_weight * source_mean * target_mean.transpose();
      next.rotation = horn_rotation(S, current.rotation);
      next.position = target_mean - next.rotation * source_mean;
      break;
    }
    case BodyKind::PinnedPosition: {
      // Rotation about the pinned rest_center, which stays at `position`.
      const Mat3 S = cross - source_sum * current.position.transpose();
      next.rotation = horn_rotation(S, current.rotation);
      break;
    }
    case BodyKind::FixedRotation:
      next.position = target_mean - current.rotation * source_mean;
      break;
    case BodyKind::Fixed:
      break;
  }
  return next;
}

// One joint's state-dependent terms, given its weight-scaled own and other means in body
// coordinates: the targets t = R_o other + p_o give sum w t = R_o (w other) + w p_o and
// sum w own t^T = cross R_o^T + (w own) p_o^T.
void add_joint(double weight, const Vec3& own_mean, const Vec3& other_mean, const Mat3& joint_cross,
               const BodyState& other, Vec3& target_sum, Mat3& cross) {
  target_sum.noalias() += other.rotation * other_mean;
  target_sum += weight * other.position;
  cross.noalias() += joint_cross * other.rotation.transpose();
  cross.noalias() += own_mean * other.position.transpose();
}

void add_springs(const RigidSystem& system, int body, double& point_weight, Vec3& source_sum,
                 Vec3& target_sum, Mat3& cross) {
  for (int k = system.spring_begin[body]; k < system.spring_begin[body + 1]; ++k) {
    const RigidSystem::Spring& s = system.springs[system.body_springs[k]];
    point_weight += s.weight;
    source_sum += s.weight * s.local;
    target_sum += s.weight * s.target;
    cross.noalias() += s.weight * s.local * s.target.transpose();
  }
}

// The change of a body's joint and spring energy from `from` to `to`, from the moments of
// its point pairs: E(R, p) = const + W |p|^2 + 2 p.(R source_sum) - 2 p.target_sum
// - 2 trace(R cross).
double energy_change(const BodyState& from, const BodyState& to, double point_weight,
                     const Vec3& source_sum, const Vec3& target_sum, const Mat3& cross) {
  auto variable = [&](const BodyState& s) {
    return point_weight * s.position.squaredNorm() +
           2.0 * s.position.dot(s.rotation * source_sum - target_sum) -
           2.0 * (s.rotation.cwiseProduct(cross.transpose())).sum();
  };
  return variable(to) - variable(from);
}

// `current` moved about `relaxation` times as far as towards `matched`, along the geodesic
// between their rotations. The turn is extended as a unit quaternion q along its great
// circle, normalize((1 - r) + r q): r times the angle for small turns, a little less for
// large ones. Without trigonometric functions it costs 80 ns a call instead of 125 for the
// exact geodesic (angle-axis both ways), about 4 ms of a 240k-face drag frame, with the same
// drag lags and cycle counts within two. The caller keeps it only where it lowers the energy.
BodyState relaxed(const BodyState& current, const BodyState& matched, double relaxation) {
  Eigen::Quaterniond turn(Mat3(matched.rotation * current.rotation.transpose()));
  if (turn.w() < 0.0) turn.coeffs() = -turn.coeffs();  // the short way round
  const double w = 1.0 - relaxation + relaxation * turn.w();
  if (!(w > 0.0)) return matched;  // a turn this large is not extended past a half turn
  const Eigen::Quaterniond extended =
      Eigen::Quaterniond(w, relaxation * turn.x(), relaxation * turn.y(), relaxation * turn.z())
          .normalized();
  BodyState next;
  next.rotation = extended.toRotationMatrix() * current.rotation;
  next.position = current.position + relaxation * (matched.position - current.position);
  return next;
}

// local_match through the plan's packed joints, over-relaxed when `relaxation` > 1 and that
// still lowers the body's energy.
BodyState planned_match(const RigidSystem& system, const SweepPlan& plan,
                        const std::vector<BodyState>& state, int body, double relaxation) {
  const BodyKind kind = plan.kind[size_t(body)];
  const BodyState& current = state[body];
  if (kind == BodyKind::Fixed) return current;
  double point_weight = plan.joint_weight[body];
  Vec3 source_sum = plan.joint_source[body];
  Vec3 target_sum = Vec3::Zero();
  Mat3 cross = Mat3::Zero();
  const int end = plan.joint_begin[body + 1];
  for (int k = plan.joint_begin[body]; k < end; ++k) {
    const SweepPlan::PackedJoint& j = plan.joints[k];
    add_joint(j.weight, j.own_mean, j.other_mean, j.cross, state[j.other], target_sum, cross);
  }
  add_springs(system, body, point_weight, source_sum, target_sum, cross);
  const BodyState matched =
      match_from_moments(kind, current, point_weight, source_sum, target_sum, cross);
  if (relaxation == 1.0) return matched;
  const BodyState over = relaxed(current, matched, relaxation);
  return energy_change(current, over, point_weight, source_sum, target_sum, cross) < 0.0 ? over
                                                                                         : matched;
}

}  // namespace

BodyState local_match(const RigidSystem& system, const std::vector<BodyState>& state, int body) {
  const RigidSystem::Body& b = system.bodies[body];
  const BodyState& current = state[body];
  if (b.kind == BodyKind::Fixed) return current;

  double point_weight = 0.0;
  Vec3 source_sum = Vec3::Zero(), target_sum = Vec3::Zero();
  Mat3 cross = Mat3::Zero();
  for (int k = system.coupling_begin[body]; k < system.coupling_begin[body + 1]; ++k) {
    const auto [ci, side] = system.body_couplings[k];
    const RigidSystem::Coupling& c = system.couplings[ci];
    const Vec3 own_mean = c.weight * c.local[side].mean;
    point_weight += c.weight;
    source_sum += own_mean;
    add_joint(c.weight, own_mean, c.weight * c.local[1 - side].mean, c.cross_of(side),
              state[c.body[1 - side]], target_sum, cross);
  }
  add_springs(system, body, point_weight, source_sum, target_sum, cross);
  return match_from_moments(b.kind, current, point_weight, source_sum, target_sum, cross);
}

void local_sweep(const RigidSystem& system, std::vector<BodyState>& state) {
  for (int b = 0; b < system.n_bodies(); ++b) state[b] = local_match(system, state, b);
}

SweepPlan plan_sweep(const RigidSystem& system, bool parallel) {
  SweepPlan plan;
  const int n = system.n_bodies();
  std::vector<int> movable;
  for (int b = 0; b < n; ++b)
    if (system.bodies[b].kind != BodyKind::Fixed) movable.push_back(b);
  refresh_sweep_plan(plan, system);
  std::vector<Vec3> position(static_cast<size_t>(n));
  for (int b = 0; b < n; ++b) position[size_t(b)] = system.bodies[size_t(b)].rest_center;
  std::vector<std::pair<int, int>> edges;
  edges.reserve(system.couplings.size());
  for (const RigidSystem::Coupling& c : system.couplings) edges.emplace_back(c.body[0], c.body[1]);
  BodyPartition partition = partition_bodies(std::move(movable), position, edges, kBodiesPerPart,
                                             parallel ? kMaxPartLevels : 0);
  plan.parts = std::move(partition.parts);
  plan.colours = std::move(partition.colours);
  return plan;
}

namespace {

// One packed entry per pair of coupled bodies: the slots of body b's couplings, in the order
// of their other bodies' first appearance. Two parallel passes (count each body's entries,
// then write them where the counts put them): at 240k faces the fine plan's entries are about
// 70 MB, and most of the 64 ms a serial pass took went to faulting their pages in (48 ms on
// two threads, 87 on one).
void build_joint_slots(SweepPlan& plan, const RigidSystem& system) {
  const int n = system.n_bodies();
  // Body b's couplings' other bodies into `other`, and each one's slot (counted from the
  // body's first) into `slot`; returns the number of distinct other bodies.
  auto slots_of = [&](int b, std::vector<int>& other, std::vector<int>& slot) {
    const int begin = system.coupling_begin[b], count = system.coupling_begin[b + 1] - begin;
    other.resize(size_t(count));
    slot.resize(size_t(count));
    int distinct = 0;
    for (int k = 0; k < count; ++k) {
      const auto [ci, side] = system.body_couplings[size_t(begin + k)];
      other[k] = system.couplings[ci].body[1 - side];
      int m = 0;
      while (m < k && other[m] != other[k]) ++m;
      slot[k] = m < k ? slot[m] : distinct++;
    }
    return distinct;
  };
  plan.kind.resize(size_t(n));  // kinds never change in a system: with the structure
  for (int b = 0; b < n; ++b) plan.kind[size_t(b)] = system.bodies[size_t(b)].kind;
  plan.joint_begin.assign(n + 1, 0);
  parallel_chunks(size_t(n), kParallelGrain, [&](size_t begin, size_t end) {
    std::vector<int> other, slot;
    for (size_t b = begin; b < end; ++b) plan.joint_begin[b + 1] = slots_of(int(b), other, slot);
  });
  for (int b = 0; b < n; ++b) plan.joint_begin[b + 1] += plan.joint_begin[b];
  plan.joint_slot.resize(system.body_couplings.size());
  plan.joints.resize(size_t(plan.joint_begin[n]));  // not initialized: written below, in parallel
  parallel_chunks(size_t(n), kParallelGrain, [&](size_t begin, size_t end) {
    std::vector<int> other, slot;
    for (size_t b = begin; b < end; ++b) {
      slots_of(int(b), other, slot);
      for (size_t k = 0; k < slot.size(); ++k) {
        const int s = plan.joint_begin[b] + slot[k];
        plan.joint_slot[size_t(system.coupling_begin[b]) + k] = s;
        SweepPlan::PackedJoint& j = plan.joints[size_t(s)];
        j.other = other[k];  // the same for a repeat
        j.weight = 0.0;
        j.own_mean = j.other_mean = Vec3::Zero();
        j.cross = Mat3::Zero();
      }
    }
  });
}

}  // namespace

// A coarse level's plan is packed again every cycle from its couplings, which each body
// reaches out of order (by coupling index): they are fetched this many ahead.
constexpr int kPackAhead = 4;

void refresh_sweep_plan(SweepPlan& plan, const RigidSystem& system) {
  const int n = system.n_bodies();
  if (plan.joint_slot.size() != system.body_couplings.size() ||
      int(plan.joint_begin.size()) != n + 1)
    build_joint_slots(plan, system);
  plan.joint_weight.resize(n);
  plan.joint_source.resize(n);
  parallel_chunks(size_t(n), kParallelGrain, [&](size_t begin, size_t end) {
    const int last_coupling = system.coupling_begin[end];
    for (int b = int(begin); b < int(end); ++b) {
      for (int s = plan.joint_begin[b]; s < plan.joint_begin[b + 1]; ++s) {
        SweepPlan::PackedJoint& j = plan.joints[s];  // `other` is set once, with the slots
        j.weight = 0.0;
        j.own_mean = j.other_mean = Vec3::Zero();
        j.cross = Mat3::Zero();
      }
      double weight = 0.0;
      Vec3 source = Vec3::Zero();
      for (int k = system.coupling_begin[b]; k < system.coupling_begin[b + 1]; ++k) {
        if (k + kPackAhead < last_coupling)
          prefetch_bytes(
              &system.couplings[size_t(system.body_couplings[size_t(k + kPackAhead)].first)],
              sizeof(RigidSystem::Coupling));
        const auto [ci, side] = system.body_couplings[k];
        const RigidSystem::Coupling& c = system.couplings[ci];
        SweepPlan::PackedJoint& j = plan.joints[plan.joint_slot[k]];
        const Vec3 own_mean = c.weight * c.local[side].mean;
        j.weight += c.weight;
        j.own_mean += own_mean;
        j.other_mean += c.weight * c.local[1 - side].mean;
        j.cross += c.cross_of(side);
        weight += c.weight;
        source += own_mean;
      }
      plan.joint_weight[b] = weight;
      plan.joint_source[b] = source;
    }
  });
}

void planned_sweep(const RigidSystem& system, const SweepPlan& plan,
                   std::vector<BodyState>& state, double relaxation) {
  for (const std::vector<int>& colour : plan.colours)
    parallel_tasks(colour.size(), [&](size_t k) {
      for (int b : plan.parts[size_t(colour[k])])
        state[size_t(b)] = planned_match(system, plan, state, b, relaxation);
    });
}

}  // namespace primo
