#include "primo/solve/hierarchical_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "prefetch.h"
#include "primo/solve/block_matrix.h"
#include "primo/solve/coupling_moments.h"
#include "primo/util/error.h"
#include "primo/solve/horn.h"
#include "primo/util/parallel.h"

namespace primo {
namespace {

using Clock = std::chrono::steady_clock;
// Restricting a level re-expresses every coupling between its clusters from the finer
// coupling it stands for, and the finer couplings and states are read out of order: the loop
// waited on memory (at 240k faces 43% of its time on the first load of each finer coupling),
// so they are fetched this many couplings ahead (the states half as far, from the coupling
// already fetched). At 240k faces the settle's restrictions took 400-490 ms instead of 590-630
// (alternating runs); 16 ahead helped less.
constexpr size_t kRestrictAhead = 4;
constexpr int kMovingCycles = 2;  // cycles since the targets changed that count as a drag
constexpr double kConfirmBelow = 1e-5;
// A settle starts near the minimum when its first cycle at fixed targets lowered the energy by
// at most this fraction (HierarchicalOptions::settle_factor_reuse): after the drag benchmark's
// drags 1.3e-5 to 1e-4, from rest 0.1 to 0.6 (elephant, armadillo, koala).
constexpr double kNearMinimumDecrease = 1e-2;
// Automatic drag_factor_lag: the factorization's flops over this many per fine body give the
// cycles it takes on a background thread, times the coarse steps per cycle, within [2, 16]
// steps. Measured on two cores with the factorization sharing them with the cycles: 8 steps
// (8 cycles) hide a 3e8-flop factorization behind a 29k-face drag. A 240k-face drag makes two
// coarse steps a cycle, and its 4.9e8-flop factorization took 230-300 ms beside cycles of
// about 100 ms: with a lag of 2 steps (one cycle) the frame that needed the factor waited for
// it (frames of 210-370 ms every sixth to tenth frame), with 4 the slowest frames were 180-200
// ms, at the same distance to the minimum at the last frame (0.153% of the diagonal against
// 0.150%; docs/decisions/0002-reused-coarse-factors.md).
constexpr double kFlopsPerFineBodyCycle = 1500.0;
constexpr int kMinAutoLag = 2, kMaxAutoLag = 16;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

struct HierarchicalSolver::Level {
  RigidSystem system;              // couplings/springs rewritten by every restriction
  std::vector<int> parent_of;      // body of the next finer level (or fine body) -> cluster
  std::vector<int> coupling_parent;  // level coupling -> same joint's coupling one level finer
  // The coarsest level has one coupling per pair of neighbouring clusters (coupling_moments.h):
  // coupling k sums the finer couplings merged[merged_begin[k] .. merged_begin[k + 1]), each
  // seen from the finer body on cluster k's side 0 and in the finer bodies' frames, and
  // merged_trace[k] is their vector modes' constant. When the next finer level is the fine
  // one, `merged` is written once (fine couplings never change); otherwise that level's
  // restriction writes it through its merged_slot as it re-expresses its couplings, so that
  // restricting the coarsest level streams one array instead of gathering finer couplings.
  std::vector<int> merged_begin;
  std::vector<OrientedCoupling> merged;
  std::vector<double> merged_trace;
  // On the level next finer than the coarsest: coupling -> 2 x its entry in the coarsest's
  // `merged` (+1 when seen from its side 1), -1 for couplings inside a coarsest cluster.
  std::vector<int> merged_slot;
  std::vector<double> child_weight;  // faces of each body of the next finer level
  Groups children;                   // cluster -> its bodies of the next finer level, ascending
  // A cluster's orientation at restriction: on the coarsest level the mean rotation of its
  // prisms (it turns the rest metric and the reused coarse factors), elsewhere the rotation of
  // a representative fine body (its largest), found through the body of the next finer level
  // that holds it; it also starts Horn's projection for the mean.
  std::vector<int> representative_child;  // cluster -> body of the next finer level
  std::vector<Mat3> orientation;
  std::vector<Vec3> rest_metric_mean;
  std::vector<Mat3> rest_metric_centered, rest_metric_pinned;
  std::vector<BodyState> correction;
  // Each cluster's rest_center as the last restriction set it, read here rather than from its
  // 232-byte Body by the restriction's couplings and the prolongation (a cache line each).
  std::vector<Vec3> center;
  SweepPlan plan;
};

// The coarsest level's couplings: one per pair of clusters that finer couplings join, in the
// order of the pairs' first finer couplings, oriented as that one. `finer_level`: the next
// finer level, null when it is the fine one (`finer_coupling_fine`: each of its couplings'
// fine coupling).
void HierarchicalSolver::merge_coupled_pairs(Level& level, Level* finer_level,
                                             const RigidSystem& fine,
                                             const std::vector<int>& finer_coupling_fine,
                                             const std::vector<int>& cluster_of) {
  // Each finer coupling as a pair of clusters; pairs numbered in order of first appearance.
  std::vector<std::pair<int, int>> edges(finer_coupling_fine.size());
  for (size_t k = 0; k < edges.size(); ++k) {
    const auto& fc = fine.couplings[size_t(finer_coupling_fine[k])];
    edges[k] = {cluster_of[size_t(fc.body[0])], cluster_of[size_t(fc.body[1])]};
  }
  const PairNumbering numbering = number_pairs(edges);
  const Groups members = group_by(numbering.pair_of, int(numbering.pairs.size()));
  RigidSystem& sys = level.system;
  sys.couplings.reserve(numbering.pairs.size());
  level.merged_begin.assign(1, 0);
  level.merged_trace.assign(numbering.pairs.size(), 0.0);
  level.merged.reserve(members.items.size());
  if (finer_level) finer_level->merged_slot.assign(finer_coupling_fine.size(), -1);
  for (size_t p = 0; p < numbering.pairs.size(); ++p) {
    // Oriented as the pair's first finer coupling.
    const size_t first = size_t(members.items[size_t(members.begin[p])]);
    RigidSystem::Coupling c = fine.couplings[size_t(finer_coupling_fine[first])];
    c.body[0] = edges[first].first;
    c.body[1] = edges[first].second;
    sys.couplings.push_back(c);
    for (int i = members.begin[p]; i < members.begin[p + 1]; ++i) {
      const size_t k = size_t(members.items[size_t(i)]);
      const bool turned = edges[k].first != c.body[0];
      // A finer coupling's vector modes are its fine coupling's, turned.
      const RigidSystem::Coupling& fc = fine.couplings[size_t(finer_coupling_fine[k])];
      level.merged_trace[p] += vector_mode_trace(fc);
      if (finer_level)
        finer_level->merged_slot[k] = 2 * int(level.merged.size()) + int(turned);
      level.merged.push_back(finer_level ? OrientedCoupling{} : OrientedCoupling::of(fc, turned));
    }
    level.merged_begin.push_back(int(level.merged.size()));
  }
}

HierarchicalSolver::HierarchicalSolver(const RigidSystem& fine, const HierarchicalOptions& options)
    : fine_(fine), options_(options), acceleration_(options.acceleration_history) {
  // The fine level's sweep plan does not depend on the coarse levels: it is built beside them
  // and the coarse solver's symbolic analysis (their construction is mostly serial passes
  // over the fine bodies and couplings; the analysis, 20-30 ms at 240k faces, took one core
  // after both halves had ended, while the two took about as long).
  parallel_tasks(2, [&](size_t task) {
    if (task == 1) {
      fine_plan_ = plan_sweep(fine);
      return;
    }
    build_levels(fine);
    if (levels_.empty()) return;
    coarse_solver_ = std::make_unique<GlobalSolver>(levels_.back()->system,
                                                    GlobalSolver::Factorization::SupernodalOneThread);
    // Clusters turn with their prisms during a drag; a reused factor follows them.
    coarse_solver_->set_body_frames(&levels_.back()->orientation);
  });
}

void HierarchicalSolver::build_levels(const RigidSystem& fine) {
  const ClusterHierarchy hierarchy = build_cluster_hierarchy(fine, options_.hierarchy);
  const int n_faces = int(fine.face_body.size());

  // Level couplings come from the fine joints crossing cluster borders, in fine order; the
  // borders of a coarser level are a subset of the finer level's, so each level coupling has
  // a parent one level finer, found by walking both lists.
  std::vector<int> finer_coupling_fine(fine.couplings.size());
  for (size_t i = 0; i < finer_coupling_fine.size(); ++i) finer_coupling_fine[i] = int(i);
  const RigidSystem* finer = &fine;
  const std::vector<int>* finer_cluster_of = nullptr;
  for (int l = 0; l < hierarchy.coarse_levels(); ++l) {
    auto level = std::make_unique<Level>();
    const std::vector<int>& cluster_of = hierarchy.cluster_of[l];  // fine body -> cluster
    const int n_clusters = hierarchy.cluster_count[l];
    const int n_finer = finer->n_bodies();
    level->parent_of.assign(n_finer, -1);
    level->child_weight.assign(n_finer, 0.0);
    for (int b = 0; b < fine.n_bodies(); ++b) {
      const int child = finer_cluster_of ? (*finer_cluster_of)[b] : b;
      level->parent_of[child] = cluster_of[b];
      level->child_weight[child] += double(fine.bodies[b].faces.size());
    }
    std::vector<int> face_cluster(n_faces);
    for (int f = 0; f < n_faces; ++f) face_cluster[f] = cluster_of[fine.face_body[f]];
    std::vector<BodyKind> kinds(n_clusters, BodyKind::Free);
    std::vector<int> representative(n_clusters, -1);
    for (int b = 0; b < fine.n_bodies(); ++b) {
      const int c = cluster_of[b];
      if (fine.bodies[b].kind != BodyKind::Free) kinds[c] = fine.bodies[b].kind;  // alone
      if (representative[c] < 0 ||
          fine.bodies[b].faces.size() > fine.bodies[representative[c]].faces.size())
        representative[c] = b;
    }
    level->children = group_by(level->parent_of, n_clusters);
    level->representative_child.resize(n_clusters);
    for (int c = 0; c < n_clusters; ++c) {
      const int rep = representative[c];
      level->representative_child[c] = finer_cluster_of ? (*finer_cluster_of)[rep] : rep;
    }
    level->orientation.assign(n_clusters, Mat3::Identity());
    RigidSystem& sys = level->system;
    sys.face_body = face_cluster;
    sys.bodies.resize(n_clusters);
    for (int b = 0; b < fine.n_bodies(); ++b) {
      RigidSystem::Body& cluster = sys.bodies[cluster_of[b]];
      cluster.faces.insert(cluster.faces.end(), fine.bodies[b].faces.begin(), fine.bodies[b].faces.end());
    }
    for (int c = 0; c < n_clusters; ++c) sys.bodies[c].kind = kinds[c];
    std::vector<int> coupling_fine;
    if (l + 1 < hierarchy.coarse_levels()) {
      sys.couplings.reserve(finer->couplings.size());
      level->coupling_parent.reserve(finer->couplings.size());
      coupling_fine.reserve(finer->couplings.size());
      for (size_t k = 0; k < finer->couplings.size(); ++k) {
        const auto& fc = fine.couplings[finer_coupling_fine[k]];
        const int a = cluster_of[fc.body[0]], b = cluster_of[fc.body[1]];
        if (a == b) continue;
        RigidSystem::Coupling c = fc;
        c.body[0] = a;
        c.body[1] = b;
        sys.couplings.push_back(c);
        level->coupling_parent.push_back(int(k));
        coupling_fine.push_back(finer_coupling_fine[k]);
      }
    } else {
      merge_coupled_pairs(*level, levels_.empty() ? nullptr : levels_.back().get(), fine,
                          finer_coupling_fine, cluster_of);
    }
    index_couplings(sys);

    // Rest metrics of the clusters (their prisms' sides about the cluster's rest centre),
    // combined from the fine bodies' metrics by the parallel-axis rule.
    level->rest_metric_mean.assign(n_clusters, Vec3::Zero());
    level->rest_metric_centered.assign(n_clusters, Mat3::Zero());
    level->rest_metric_pinned.assign(n_clusters, Mat3::Zero());
    std::vector<double> weight(n_clusters, 0.0);
    std::vector<Vec3> rest_center(n_clusters, Vec3::Zero());
    for (int b = 0; b < fine.n_bodies(); ++b) {
      const int c = cluster_of[b];
      const double w = double(fine.bodies[b].faces.size());
      rest_center[c] += w * fine.bodies[b].rest_center;
      weight[c] += w;
    }
    for (int c = 0; c < n_clusters; ++c) rest_center[c] /= weight[c];
    std::vector<double> metric_weight(n_clusters, 0.0);
    for (int b = 0; b < fine.n_bodies(); ++b) {
      const RigidSystem::Body& body = fine.bodies[b];
      const int c = cluster_of[b];
      const Vec3 offset = body.rest_center - rest_center[c];
      // metric_pinned of the fine body is about its own rest_center; shift to the cluster's.
      const Vec3 first = body.metric_weight * body.metric_mean;
      level->rest_metric_pinned[c] += body.metric_pinned + first * offset.transpose() +
                                      offset * first.transpose() +
                                      body.metric_weight * offset * offset.transpose();
      level->rest_metric_mean[c] += first + body.metric_weight * offset;
      metric_weight[c] += body.metric_weight;
    }
    for (int c = 0; c < n_clusters; ++c) {
      level->rest_metric_mean[c] /= metric_weight[c];
      const Vec3& m = level->rest_metric_mean[c];
      level->rest_metric_centered[c] =
          level->rest_metric_pinned[c] - metric_weight[c] * m * m.transpose();
      sys.bodies[c].metric_weight = metric_weight[c];
    }
    if (l + 1 < hierarchy.coarse_levels()) level->plan = plan_sweep(sys);
    finer_coupling_fine = std::move(coupling_fine);
    levels_.push_back(std::move(level));
    finer = &levels_.back()->system;
    finer_cluster_of = &cluster_of;
  }
}

HierarchicalSolver::~HierarchicalSolver() = default;

int HierarchicalSolver::drag_factor_lag() const {
  if (options_.drag_factor_lag >= 0 || !coarse_solver_) return std::max(options_.drag_factor_lag, 0);
  const double flops = coarse_solver_->factorization_flops();
  if (flops <= 0.0) return 0;
  // A preview's cycles stop at its level: they take as long as that level's bodies make them.
  const int finest = previewing() ? preview_level_ : 0;
  return automatic_drag_factor_lag(flops, bodies(finest), coarse_steps_from(std::max(finest, 1)));
}

int HierarchicalSolver::coarse_steps_from(int level) const {
  // The coarsest level is visited intermediate_cycles times per visit of the level above it.
  int steps = options_.coarse_iterations;
  for (int l = level; l < int(levels_.size()); ++l) steps *= options_.intermediate_cycles;
  return steps;
}

int automatic_drag_factor_lag(double factorization_flops, int fine_bodies,
                              int coarse_steps_per_cycle) {
  const double cycles = factorization_flops / (kFlopsPerFineBodyCycle * std::max(fine_bodies, 1));
  const double steps = std::ceil(cycles * coarse_steps_per_cycle);
  return int(std::clamp(steps, double(kMinAutoLag), double(kMaxAutoLag)));
}

int HierarchicalSolver::bodies(int level) const { return system(level).n_bodies(); }

const RigidSystem& HierarchicalSolver::system(int level) const {
  return level == 0 ? fine_ : levels_[size_t(level - 1)]->system;
}

void HierarchicalSolver::restrict_level(Level& level, const RigidSystem& finer,
                                        const std::vector<BodyState>& finer_state,
                                        const std::vector<Mat3>* finer_orientation) {
  RigidSystem& sys = level.system;
  const int n = sys.n_bodies();
  const bool swept = &level != levels_.back().get();  // the coarsest level is solved globally
  level.correction.resize(n);
  level.center.resize(size_t(n));
  auto child_orientation = [&](int child) {
    return finer_orientation ? Mat3(finer_state[child].rotation * (*finer_orientation)[child])
                             : finer_state[child].rotation;
  };
  // The coarsest level's orientations are its clusters' mean rotations: they orient the
  // metric of the coarse Newton step and turn its reused factors. Elsewhere one child's
  // rotation is enough (they only pass on to the next coarser level).
  // Each cluster from its children, in their order (the same sums on any number of threads).
  parallel_chunks(size_t(n), kParallelGrain / 8, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      Vec3 center = Vec3::Zero();
      double weight = 0.0;
      Mat3 rotation_sum = Mat3::Zero();
      for (int k = level.children.begin[c]; k < level.children.begin[c + 1]; ++k) {
        const int b = level.children.items[size_t(k)];
        center += level.child_weight[b] * finer_state[b].position;
        weight += level.child_weight[b];
        if (!swept) rotation_sum += level.child_weight[b] * child_orientation(b);
      }
      RigidSystem::Body& body = sys.bodies[c];
      body.rest_center = center / weight;
      level.center[c] = body.rest_center;
      // The cluster's prisms have moved; orient its rest metric by them.
      level.orientation[c] = child_orientation(level.representative_child[c]);
      if (!swept) {  // only the coarse Newton step measures motions in the metric
        level.orientation[c] = horn_rotation(rotation_sum.transpose(), level.orientation[c]);
        const Mat3& R = level.orientation[c];
        body.metric_mean = R * level.rest_metric_mean[c];
        body.metric_centered = R * level.rest_metric_centered[c] * R.transpose();
        body.metric_pinned = R * level.rest_metric_pinned[c] * R.transpose();
      }
      level.correction[c] = {Mat3::Identity(), body.rest_center};
    }
  });
  if (swept) {
    std::vector<OrientedCoupling>* merged =
        level.merged_slot.empty() ? nullptr : &levels_.back()->merged;
    parallel_chunks(sys.couplings.size(), kParallelGrain, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) {
        if (k + kRestrictAhead < end)
          prefetch_bytes(&finer.couplings[size_t(level.coupling_parent[k + kRestrictAhead])],
                         sizeof(RigidSystem::Coupling));
        if (k + kRestrictAhead / 2 < end) {
          const RigidSystem::Coupling& soon =
              finer.couplings[size_t(level.coupling_parent[k + kRestrictAhead / 2])];
          prefetch_line(&finer_state[size_t(soon.body[0])]);
          prefetch_line(&finer_state[size_t(soon.body[1])]);
        }
        const RigidSystem::Coupling& fc = finer.couplings[size_t(level.coupling_parent[k])];
        RigidSystem::Coupling& c = sys.couplings[k];
        // Each side in world orientation about its cluster's centre.
        for (int s = 0; s < 2; ++s) {
          const BodyState& st = finer_state[size_t(fc.body[s])];
          const PatchModes& m = fc.local[s];
          c.local[s] = {st.rotation * m.mean + st.position - level.center[size_t(c.body[s])],
                        st.rotation * m.du, st.rotation * m.dv, st.rotation * m.duv};
        }
        c.update_cross();  // local matching reads the cross moments
        if (merged && level.merged_slot[k] >= 0) {
          const int slot = level.merged_slot[k];
          (*merged)[size_t(slot / 2)] = OrientedCoupling::of(c, slot % 2 == 1);
        }
      }
    });
  } else {
    // Each pair's finer couplings summed into its one coupling; the constants by which their
    // energies differ make the level's internal energy (chunks fixed by the size, summed in
    // order: the same bits on any number of threads).
    sys.internal_energy = parallel_sum(
        sys.couplings.size(), kParallelGrain / 4, 0.0, [&](size_t begin, size_t end) {
          double shortfall = 0.0;
          const size_t last = size_t(level.merged_begin[end]);
          for (size_t k = begin; k < end; ++k) {
            RigidSystem::Coupling& c = sys.couplings[k];
            const Vec3& center0 = level.center[size_t(c.body[0])];
            const Vec3& center1 = level.center[size_t(c.body[1])];
            CouplingMoments moments;
            moments.trace = level.merged_trace[k];
            for (int i = level.merged_begin[k]; i < level.merged_begin[k + 1]; ++i) {
              if (size_t(i) + kRestrictAhead < last) {
                const OrientedCoupling& soon = level.merged[size_t(i) + kRestrictAhead];
                prefetch_line(&finer_state[size_t(soon.own)]);
                prefetch_line(&finer_state[size_t(soon.other)]);
              }
              const OrientedCoupling& m = level.merged[size_t(i)];
              const BodyState& own = finer_state[size_t(m.own)];
              const BodyState& other = finer_state[size_t(m.other)];
              moments.add_moved(m, own.rotation, own.position - center0, other.rotation,
                                other.position - center1);
            }
            shortfall += moments.write(c);
          }
          return shortfall;
        });
  }
  sys.springs.resize(finer.springs.size());
  for (size_t k = 0; k < finer.springs.size(); ++k) {
    const RigidSystem::Spring& fs = finer.springs[k];
    const int c = level.parent_of[fs.body];
    sys.springs[k] = {c, world_point(finer_state[fs.body], fs.local) - level.center[size_t(c)],
                      fs.target, fs.weight};
  }
  index_springs(sys);
  if (swept) refresh_sweep_plan(level.plan, sys);
}

void HierarchicalSolver::prolong_level(const Level& level, std::vector<BodyState>& finer_state) const {
  parallel_chunks(finer_state.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const int c = level.parent_of[b];
      const BodyState& corr = level.correction[c];
      BodyState& s = finer_state[b];
      s.position = corr.rotation * (s.position - level.center[size_t(c)]) + corr.position;
      s.rotation = corr.rotation * s.rotation;
    }
  });
}

void HierarchicalSolver::solve_level(int l) {
  Level& level = *levels_[l];
  auto t = Clock::now();
  if (l + 1 == int(levels_.size())) {
    // While targets move (a drag: they change before every cycle), spent factors are refreshed
    // in the background so that no frame stops for a factorization; once they stay put, in
    // the foreground, where a fresh factor pays off at once.
    const int lag = drag_factor_lag();
    const bool in_drag = cycles_since_restart_ <= kMovingCycles;
    const bool moving = in_drag && lag > 0;
    const bool near_minimum =
        settle_start_decrease_ && *settle_start_decrease_ <= kNearMinimumDecrease;
    const int reuse = moving         ? options_.drag_factor_reuse
                      : near_minimum ? options_.settle_factor_reuse
                                     : options_.coarse_factor_reuse;
    // A drag's frame (a solve of one cycle or two) has no later step to make up for a cut one:
    // a reused factor whose full step overshoots is replaced by a fresh one rather than
    // halved. Cut steps left a thin blade's drag up to 470 times above its minimum, growing
    // from frame to frame as the drag predictor repeated them (docs/decisions/0002).
    // Longer solves keep the halvings: there they cost less than factorizing (a full solve
    // from rest at 240k faces took 14 iterations instead of 13 without them).
    const bool drag_frame = in_drag && iterations_ahead_ <= kMovingCycles;
    coarse_solver_->set_factor_reuse(reuse, moving ? lag : 0,
                                     drag_frame ? 0 : GlobalSolver::kReusedStepHalvings);
    // coarse_factor_reuse 0 makes a drag's steps factorize too.
    const bool reusing = moving ? options_.coarse_factor_reuse > 0 : reuse > 0;
    // One coarse Newton iteration; false when it did not lower the energy.
    auto coarse_step = [&] {
      const GlobalStep step = coarse_solver_->iterate(level.correction, coarse_exact_, reusing);
      coarse_exact_ = options_.exact_hessian_below > 0 && step.decreased &&
                      step.step_scale == 1.0 &&
                      step.energy_before - step.energy_after <
                          options_.exact_hessian_below * step.energy_before;
      return step.decreased;
    };
    int done = 0;
    // A solve that will take steps builds their structure beside a foreground factorization
    // (one thread): the same structure, built while a core would wait.
    const bool steps_likely =
        iterations_ahead_ > kMovingCycles + 1 &&
        (options_.newton_krylov_above > 0.0 || options_.newton_krylov_below > 0.0);
    if (steps_likely && options_.coarse_iterations > 0 && !coarse_solver_->has_factor() &&
        !newton_krylov_ready()) {
      if (!newton_krylov_)
        newton_krylov_ = std::make_unique<NewtonKrylov>(fine_, options_.newton_krylov);
      bool decreased = false;
      parallel_tasks(2, [&](size_t task) {
        if (task == 0)
          decreased = coarse_step();
        else
          newton_krylov_->build_structure();
      });
      done = decreased ? 1 : options_.coarse_iterations;
    }
    for (int it = done; it < options_.coarse_iterations; ++it)
      if (!coarse_step()) break;
    timings_.coarse += seconds_since(t);
    return;
  }
  Level& coarser = *levels_[l + 1];
  for (int r = 0; r < options_.intermediate_cycles; ++r) {
    t = Clock::now();
    restrict_level(coarser, level.system, level.correction, &level.orientation);
    timings_.restrict_prolong += seconds_since(t);
    solve_level(l + 1);
    t = Clock::now();
    prolong_level(coarser, level.correction);
    timings_.restrict_prolong += seconds_since(t);
    t = Clock::now();
    for (int k = 0; k < options_.intermediate_sweeps; ++k)
      planned_sweep(level.system, level.plan, level.correction, options_.intermediate_relaxation);
    timings_.sweeps += seconds_since(t);
  }
}

void HierarchicalSolver::prepare(const std::vector<BodyState>& fine_state) {
  if (levels_.empty()) return;
  cancel_preview();  // the levels are restricted from `fine_state` again
  restrict_level(*levels_[0], fine_, fine_state, nullptr);
  for (size_t l = 0; l + 1 < levels_.size(); ++l)
    restrict_level(*levels_[l + 1], levels_[l]->system, levels_[l]->correction,
                   &levels_[l]->orientation);
  coarse_solver_->factorize_at(levels_.back()->correction);
}

int HierarchicalSolver::automatic_preview_level() const {
  for (int l = 1; l < levels(); ++l)
    if (int(system(l).couplings.size()) <= options_.preview_max_couplings) return l;
  return levels() - 1 >= 1 ? levels() - 1 : -1;
}

void HierarchicalSolver::begin_preview(const std::vector<BodyState>& fine_state, int level,
                                       double fine_energy) {
  if (levels_.empty()) throw Error("a preview needs a coarse level: the mesh is too small");
  if (level < 0) level = automatic_preview_level();
  level = std::clamp(level, 1, int(levels_.size()));
  const auto t = Clock::now();
  // The levels up to the preview's from the fine state, as a cycle restricts them; the ones
  // above it are restricted by its frames.
  restrict_level(*levels_[0], fine_, fine_state, nullptr);
  for (int l = 1; l < level; ++l)
    restrict_level(*levels_[size_t(l)], levels_[size_t(l - 1)]->system,
                   levels_[size_t(l - 1)]->correction, &levels_[size_t(l - 1)]->orientation);
  const Level& top = *levels_[size_t(level - 1)];
  preview_cluster_.resize(fine_state.size());
  parallel_chunks(fine_state.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      int c = levels_[0]->parent_of[b];
      for (int l = 1; l < level; ++l) c = levels_[size_t(l)]->parent_of[size_t(c)];
      preview_cluster_[b] = c;
    }
  });
  // Locked bodies are alone in their clusters at every level (cluster_hierarchy.h): the
  // preview moves each as its target moved since now.
  size_t anchors = 0;
  for (size_t b = 0; b < fine_state.size(); ++b)
    if (fine_.bodies[b].kind != BodyKind::Free) anchors = b + 1;
  preview_anchor_.assign(fine_state.begin(), fine_state.begin() + std::ptrdiff_t(anchors));
  preview_correction_ = &top.correction;
  preview_center_ = &top.center;
  // The level leaves out the joints inside its clusters, which its motions do not change.
  if (std::isnan(fine_energy)) fine_energy = fine_.energy(fine_state);
  preview_energy_offset_ = fine_energy - top.system.energy(top.correction);
  preview_level_ = level;
  restart_acceleration();
  timings_.restrict_prolong += seconds_since(t);
}

double HierarchicalSolver::preview_frame(const std::vector<BodyState>& fine_state) {
  if (!previewing()) throw Error("no preview under way");
  Level& top = *levels_[size_t(preview_level_ - 1)];
  for (size_t b = 0; b < preview_anchor_.size(); ++b) {
    const BodyKind kind = fine_.bodies[b].kind;
    if (kind == BodyKind::Free) continue;
    const BodyState& from = preview_anchor_[b];
    const BodyState& to = fine_state[b];
    const size_t c = size_t(preview_cluster_[b]);
    BodyState& correction = top.correction[c];
    if (kind != BodyKind::PinnedPosition)
      correction.rotation = to.rotation * from.rotation.transpose();
    if (kind != BodyKind::FixedRotation)
      correction.position = to.position - correction.rotation * (from.position - top.center[c]);
  }
  // Springs keep their number and order at every level; only their targets move.
  for (int l = 0; l < preview_level_; ++l) {
    std::vector<RigidSystem::Spring>& springs = levels_[size_t(l)]->system.springs;
    for (size_t k = 0; k < springs.size(); ++k) springs[k].target = fine_.springs[k].target;
  }
  ++timings_.cycles;
  // A frame of a drag for the coarse factors' refreshes (solve_level), but one whose reused
  // factors' steps are halved where they overshoot rather than replaced in the foreground:
  // the preview's frames are short, and a fresh factor made there (at a million faces 50-90
  // ms beside them) would be most of a frame.
  cycles_since_restart_ = 0;
  const int iterations_ahead = iterations_ahead_;
  iterations_ahead_ = kMovingCycles + 1;
  solve_level(preview_level_ - 1);
  iterations_ahead_ = iterations_ahead;
  ++cycles_since_restart_;
  return top.system.energy(top.correction) + preview_energy_offset_;
}

void HierarchicalSolver::end_preview(std::vector<BodyState>& fine_state) {
  if (!previewing()) return;
  const auto t = Clock::now();
  parallel_chunks(fine_state.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) fine_state[b] = previewed(fine_state, int(b));
  });
  preview_level_ = -1;
  restart_acceleration();
  timings_.restrict_prolong += seconds_since(t);
}

double HierarchicalSolver::cycle(std::vector<BodyState>& fine_state, double energy_before) {
  if (previewing()) {  // cycles go on from the preview's picture
    end_preview(fine_state);
    energy_before = std::numeric_limits<double>::quiet_NaN();
  }
  const bool settling = cycles_since_restart_ > kMovingCycles;
  interrupted_ = false;
  // A Newton step that lowered the energy by less than kConfirmBelow of it left the state
  // within about the square of that of the minimum (Newton converges quadratically): all the
  // next iteration has to do is confirm it, and a cycle does so at a tenth of a step's cost.
  const bool confirming = last_was_newton_ && last_decrease_ < kConfirmBelow;
  last_was_newton_ = false;
  // The first cycle at fixed targets has run (the drag's last frame made the one before it).
  if (cycles_since_restart_ >= kMovingCycles && !settle_start_decrease_)
    settle_start_decrease_ = last_decrease_;
  // This settle started far from the minimum (HierarchicalOptions::newton_krylov_above).
  const bool from_afar = options_.newton_krylov_above > 0.0 && settle_start_decrease_ &&
                         *settle_start_decrease_ > options_.newton_krylov_above;
  // The second iteration of a drag's frame (HierarchicalOptions::newton_krylov_in_frames):
  // known from the first, whose call said how many it meant to run; not when that call
  // stopped after its cycle and this is another's, no frame.
  const bool frame_step = frame_step_next_ && drag_frame_ && cycles_since_restart_ == 1;
  frame_step_next_ = options_.newton_krylov_in_frames && cycles_since_restart_ == 0 &&
                     iterations_ahead_ >= 2 && drag_frame_;
  const bool newton =
      !krylov_failed_ && !confirming &&
      (frame_step || from_afar || (settling && last_decrease_ < options_.newton_krylov_below));
  if (newton) {
    const auto t = Clock::now();
    if (!newton_krylov_)
      newton_krylov_ = std::make_unique<NewtonKrylov>(fine_, options_.newton_krylov);
    const NewtonKrylovStep step = newton_krylov_->iterate(fine_state, energy_before, interrupt_);
    timings_.newton_krylov += seconds_since(t);
    if (step.interrupted) {
      interrupted_ = true;
      return std::isnan(energy_before) ? fine_.energy(fine_state) : energy_before;
    }
    ++timings_.newton_krylov_steps;
    timings_.newton_krylov_iterations += step.cg_iterations;
    timings_.newton_krylov_applications += step.preconditioner_applications;
    ++cycles_since_restart_;
    if (step.decreased) {
      acceleration_.reset();  // the cycles' history is no longer that of this state
      last_decrease_ = (step.energy_before - step.energy_after) / step.energy_before;
      last_was_newton_ = true;
      return step.energy_after;
    }
    krylov_failed_ = true;
    energy_before = step.energy_before;
  }
  const double result = cycle_only(fine_state, energy_before);
  if (std::isfinite(energy_before) && energy_before > 0.0)
    last_decrease_ = (energy_before - result) / energy_before;
  return result;
}

double HierarchicalSolver::cycle_only(std::vector<BodyState>& fine_state, double energy_before) {
  // The first cycle after a restart is not recorded: a drag updates the targets before every
  // cycle, and would pay for bookkeeping it can never use.
  const bool accelerate = acceleration_.history() > 0 && cycles_since_restart_ > 0;
  ++cycles_since_restart_;
  // The acceleration knows the state its last proposal left (kept or refused) by its
  // embedding; only the first accelerated cycle needs a copy of the input.
  const bool input_known = accelerate && acceleration_.knows_input();
  if (accelerate && !input_known) parallel_copy(fine_state, cycle_input_);
  // With the energy before the cycle known, an accelerated proposal is kept when it lies below
  // it (still a descent method), and the plain cycle's result needs no energy of its own
  // unless the proposal is refused: one pass over all joints less per accepted cycle.
  const bool skip_plain_energy = accelerate && std::isfinite(energy_before);
  double energy = plain_cycle(fine_state, !skip_plain_energy);
  if (accelerate) {
    const auto t = Clock::now();
    if (acceleration_.propose(input_known ? nullptr : &cycle_input_, fine_state, proposal_)) {
      const double proposed = fine_.energy(proposal_);
      if (proposed < (skip_plain_energy ? energy_before : energy)) {
        fine_state.swap(proposal_);
        energy = proposed;
        ++timings_.accepted_accelerations;
      } else {
        acceleration_.refuse();
      }
    }
    timings_.acceleration += seconds_since(t);
  }
  if (std::isnan(energy)) energy = fine_.energy(fine_state);  // skipped, and no proposal kept
  return energy;
}

double HierarchicalSolver::plain_cycle(std::vector<BodyState>& fine_state, bool with_energy) {
  ++timings_.cycles;
  if (!levels_.empty()) {
    auto t = Clock::now();
    restrict_level(*levels_[0], fine_, fine_state, nullptr);
    timings_.restrict_prolong += seconds_since(t);
    solve_level(0);
    t = Clock::now();
    prolong_level(*levels_[0], fine_state);
    timings_.restrict_prolong += seconds_since(t);
    if (coarse_correction_callback_) coarse_correction_callback_();
  }
  const auto t = Clock::now();
  for (int k = 0; k < options_.sweeps_per_level; ++k) planned_sweep(fine_, fine_plan_, fine_state);
  timings_.sweeps += seconds_since(t);
  return with_energy ? fine_.energy(fine_state) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace primo
