#pragma once
// Local shape matching (paper Sect. 4.1, Appendix A): one body at a time is moved to the
// rigid motion that minimizes its joint and spring energy with every other body held fixed,
// in closed form by Horn's method. Each match can only lower the energy.

#include <vector>

#include "primo/model/rigid_system.h"

namespace primo {

// The optimal state of `body` given the others. Free bodies get rotation and translation;
// PinnedPosition bodies rotate about their prescribed rest_center; FixedRotation bodies only
// translate; Fixed bodies (and bodies with nothing acting on them) keep their state.
BodyState local_match(const RigidSystem& system, const std::vector<BodyState>& state, int body);

// One Gauss-Seidel sweep over all bodies in index order.
void local_sweep(const RigidSystem& system, std::vector<BodyState>& state);

// A Gauss-Seidel sweep over every core, with the same result on any number of threads. The
// movable bodies are cut into parts by recursive bisection of their rest centres along the
// longest axis; how many parts depends on the number of bodies alone (about 2,000 bodies a
// part, at most 128). Parts are coloured so that no two parts of a colour have coupled bodies:
// the parts of one colour are matched in parallel (none reads what another writes), colour
// after colour. It is a Gauss-Seidel ordering, so its fixed points are those of `local_sweep`;
// a sweep needs one wait per colour (four to six on a surface) and no spinning.
//
// The plan also holds each body's joints packed for matching: the state-independent parts of
// Horn's sums, contiguous so that a sweep streams them instead of gathering whole couplings.
// Those parts are linear in the joint's data, so all joints between the same two bodies are
// summed into one: on a coarse level, where a cluster border is crossed by several fine
// joints, a match then costs what the number of neighbouring clusters requires.
struct SweepPlan {
  std::vector<std::vector<int>> parts;    // each part's bodies, in index order
  std::vector<std::vector<int>> colours;  // each colour's parts, in index order
  struct PackedJoint {
    // Not initialized (as Eigen's fixed-size members are not): the plan writes its entries
    // in parallel, which faults their pages in on every core.
    PackedJoint() {}
    int other;         // the body on the other side
    double weight;     // sums over the joints between the two bodies:
    Vec3 own_mean;     // weight * own side's mean (body coordinates)
    Vec3 other_mean;   // weight * other side's mean (the other body's coordinates)
    Mat3 cross;        // Coupling::cross_of the own side
  };
  std::vector<PackedJoint> joints;   // body b's neighbours: joint_begin[b] .. joint_begin[b + 1]
  std::vector<int> joint_begin;
  std::vector<int> joint_slot;       // system.body_couplings[k] -> its entry in `joints`
  std::vector<double> joint_weight;  // per body: sum of its joints' weights
  std::vector<Vec3> joint_source;    // per body: sum of own_mean
  // Per body: its kind, read here rather than from its Body (232 bytes: a cache line a body
  // for one byte; PlannedSweep/4800 took 36.6 ms instead of 33.8, medians alternating).
  std::vector<BodyKind> kind;
};
SweepPlan plan_sweep(const RigidSystem& system, bool parallel = true);
// Re-reads the couplings' values after they changed (same couplings, same bodies); springs
// are always read from the system.
void refresh_sweep_plan(SweepPlan& plan, const RigidSystem& system);
// With `relaxation` > 1 (successive over-relaxation) each body moves about that many times as
// far as its match along the geodesic, when that lowers its energy, and to its match otherwise:
// still a descent method, faster on smooth errors.
void planned_sweep(const RigidSystem& system, const SweepPlan& plan,
                   std::vector<BodyState>& state, double relaxation = 1.0);

}  // namespace primo
