#pragma once
// Hierarchical shape matching (paper Sect. 4.3), as a multilevel subspace correction: every
// coarse level moves whole clusters of fine prisms rigidly on top of the current fine state.
//
// One cycle: restrict every level from the next finer one in its current state (the fine
// joints crossing cluster borders and the springs become the level's couplings; only the
// first coarse level reads the fine bodies), optimize the coarsest level's corrections by
// global Newton matching, then for each finer level apply (prolong) the corrections of the
// level above and run local sweeps on it, and finally on the fine level. Every step lowers
// the true energy, and repeating cycles converges to the same minimum as the flat solvers;
// the coarse Newton step carries the smooth, global part of a deformation at the cost of a
// small system. Restriction is done once per level and cycle, so a coarse Newton iteration
// costs what the number of clusters (and their borders) requires. The coarse sparsity
// pattern, hence the symbolic factorization, is fixed for the life of the solver (one
// handle set).

#include <memory>
#include <vector>

#include "primo/cluster_hierarchy.h"
#include "primo/global_solver.h"
#include "primo/local_solver.h"
#include "primo/rigid_system.h"

namespace primo {

struct HierarchicalOptions {
  HierarchyOptions hierarchy;
  int sweeps_per_level = 2;      // local sweeps on the fine level (the paper uses 2)
  int intermediate_sweeps = 8;   // local sweeps on each level between fine and coarsest (cheap)
  int coarse_iterations = 1;     // global Newton iterations on the coarsest level per cycle
  double exact_hessian_below = 1e-1;  // as SolveOptions::exact_hessian_below, for the coarsest level
};

struct HierarchicalTimings {
  double restrict_prolong = 0.0;
  double coarse = 0.0;
  double sweeps = 0.0;
  int cycles = 0;
};

class HierarchicalSolver {
 public:
  HierarchicalSolver(const RigidSystem& fine, const HierarchicalOptions& options = {});
  ~HierarchicalSolver();

  // One cycle from `fine_state` (updated in place). Returns the fine energy after it.
  double cycle(std::vector<BodyState>& fine_state);

  int levels() const { return int(levels_.size()) + 1; }  // including the fine level
  int bodies(int level) const;  // level 0 = fine
  const HierarchicalTimings& timings() const { return timings_; }
  const GlobalSolver* coarse_solver() const { return coarse_solver_.get(); }

 private:
  struct Level;
  // Takes the level's joints and springs from the next finer level in its current state;
  // `fine_state` orients the cluster metrics.
  void restrict_level(Level& level, const RigidSystem& finer,
                      const std::vector<BodyState>& finer_state,
                      const std::vector<BodyState>& fine_state);
  // Applies the level's corrections to the bodies of the next finer level.
  void prolong_level(const Level& level, std::vector<BodyState>& finer_state) const;

  const RigidSystem& fine_;
  HierarchicalOptions options_;
  std::vector<std::unique_ptr<Level>> levels_;  // finest coarse level first
  std::unique_ptr<GlobalSolver> coarse_solver_;
  SweepPlan fine_plan_;
  bool coarse_exact_ = false;
  HierarchicalTimings timings_;
};

}  // namespace primo
