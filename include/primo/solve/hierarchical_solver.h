#pragma once
// Hierarchical shape matching (paper Sect. 4.3), as a multilevel subspace correction: every
// coarse level moves whole clusters of fine prisms rigidly on top of the current fine state.
//
// One cycle: restrict every level from the next finer one in its current state (the fine
// joints crossing cluster borders and the springs become the level's couplings, on the
// coarsest level summed into one coupling per pair of clusters, coupling_moments.h; only the
// first coarse level reads the fine bodies), optimize the coarsest level's corrections by
// global Newton matching, then for each finer level apply (prolong) the corrections of the
// level above and run local sweeps on it, and finally on the fine level. Every step lowers
// the true energy, and repeating cycles converges to the same minimum as the flat solvers;
// the coarse Newton step carries the smooth, global part of a deformation at the cost of a
// small system. Restriction is done once per level and cycle, so a coarse Newton iteration
// costs what the number of clusters (and their borders) requires. The coarse sparsity
// pattern, hence the symbolic factorization, is fixed for the life of the solver (one
// handle set).

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "primo/solve/anderson_acceleration.h"
#include "primo/solve/cluster_hierarchy.h"
#include "primo/solve/global_solver.h"
#include "primo/solve/local_solver.h"
#include "primo/solve/newton_krylov.h"
#include "primo/model/rigid_system.h"

namespace primo {

// Defaults were chosen by `primo bench drag` on 30k- and 240k-face meshes (docs/performance.md):
// they keep a drag within a few percent of the minimum at one cycle per frame.
struct HierarchicalOptions {
  HierarchyOptions hierarchy;
  // Local sweeps on the fine level per cycle. The paper uses 2; with the coarse Newton step
  // and acceleration a second sweep changed neither the drag's lag nor the cycles to
  // convergence measurably, and costs a third of a cycle.
  int sweeps_per_level = 1;
  int intermediate_sweeps = 2;   // local sweeps on a level between fine and coarsest, per visit
  int coarse_iterations = 1;     // global Newton iterations on the coarsest level per visit
  // Each intermediate level is improved this many times per visit (restrict the levels above,
  // solve them, prolong, sweep): 1 is a V-cycle, 2 a W-cycle. Sweeps on clusters are a weak
  // smoother; visiting the coarse level twice halved the lag of a 240k-face drag.
  int intermediate_cycles = 2;
  // Coarse Newton steps may reuse one numeric factorization this many times (modified
  // Newton; the coarse matrix changes little between cycles). 0: factorize every step.
  int coarse_factor_reuse = 16;
  // The same once a settle has started near the minimum (its first cycle at fixed targets
  // lowered the energy by at most 1e-2 of it: a drag that followed the hand; after the drag
  // benchmark's drags 1.3e-5 to 1e-4, from rest 0.1 to 0.6). The coarse matrix hardly
  // changes there: at 240k faces the settle after the drag benchmark's drag spent 0.34-0.53 s
  // of its 2.6-3.2 s on refactorizations with 16, and none with 48, in the same 24 cycles;
  // the armadillo's took 19 cycles instead of 14 but less time, the koala's 35 instead of 34
  // (docs/decisions/0002-reused-coarse-factors.md). Far from the minimum fresh factors pay:
  // a full solve by cycles took 116 cycles instead of 80 with 48.
  int settle_factor_reuse = 48;
  // During a drag (targets changed within the last 2 cycles) a spent factor is refreshed on a
  // background thread and takes over `drag_factor_lag` coarse steps later
  // (GlobalSolver::set_factor_reuse), so that no frame stops for a factorization: the
  // slowest frame of a 240k-face drag fell from about 350 to 210 ms, of a 29k-face one from
  // about 190 to 30 ms. Factors arrive late, so they serve fewer steps (`drag_factor_reuse`):
  // 12 kept the 240k drag as close to the minimum as foreground refreshes (4.6% against
  // 4.5%) at the same median frame; 8 was closer (4.3%) but slower (the background thread
  // shares the two cores), 16 further (4.8%).
  // drag_factor_lag -1: as many steps as the factorization needs on a background thread
  // (estimated from its flop count against the fine level's work per cycle, times the coarse
  // steps a cycle makes: automatic_drag_factor_lag); 0: factorize in the foreground during
  // drags too.
  int drag_factor_reuse = 12;
  int drag_factor_lag = -1;
  double intermediate_relaxation = 1.8;  // over-relaxation of intermediate sweeps (1: none)
  // Cycles are accelerated by Anderson acceleration over this many past cycles (0: plain
  // cycles). Memory per fine body: 2 x history x 7 floats of history, and 7 floats and
  // 7 doubles for the last cycle.
  int acceleration_history = 5;
  double exact_hessian_below = 1e-1;  // as SolveOptions::exact_hessian_below, for the coarsest level
  // Once the targets have stayed put for a few cycles and a cycle lowers the energy by less
  // than this fraction, iterations are Newton-Krylov steps on the fine level instead of
  // cycles (newton_krylov.h): the cycles' tail converges linearly, Newton's steps faster. A
  // step that fails to lower the energy hands back to cycles until the targets move. 0:
  // cycles only. On by default since the steps got cheaper
  // (docs/decisions/0005-newton-krylov-steps-for-the-tail.md): the drag benchmark's settles
  // took 1.5-1.7 instead of 2.1-2.9 s at 240k faces, 1.5-1.7 instead of 2.7-2.9 s on the
  // 100k koala, 0.32-0.33 instead of 0.35-0.52 s on the armadillo, 0.072-0.077 instead of
  // 0.047-0.052 s on the elephant, and 30 instead of 56 s on the koala subdivided to 400k
  // faces (whose cycles stop 0.18% above the minimum).
  double newton_krylov_below = 1e-3;
  // When the first cycle at fixed targets (the second since they moved: the first is a drag's
  // frame) lowered the energy by more than this fraction, the state is far from the minimum (a
  // jump or a solve from rest, not a drag that followed the hand): the rest of that solve is
  // Newton-Krylov steps, from the next iteration on (deciding a cycle later cost the 240k
  // solve from rest a third cycle for the same ten steps). There the cycles spend most of their
  // iterations (the 240k drag benchmark's solve from rest: 80 cycles), where steps of a Newton
  // method take 9 to 15; full solves took 0.19 instead of 0.28 s (elephant), 0.73 instead of
  // 0.89 s (armadillo), 3.8 instead of 5.7 s (koala) and about 5.5 instead of 9.5 s (240k
  // faces) (docs/performance.md). After the bench's 60-frame drags that cycle lowers the
  // energy by 1e-5 to 3e-4 of it, after a jump or from rest by 0.1 to 0.6; after a drag that
  // lagged the hand (15-30 frames, or an artist's fast 4-second pull at 240k faces) by 2e-3
  // to 1e-2, and there the steps win too: with 1e-2 such a settle at 240k faces took 13
  // cycles before its first step and 24 iterations (2.7 s), with 2e-3 it takes 10 (1.8 s)
  // (docs/decisions/0005). 0: cycles there too. A step takes 0.1-0.3 s at 240k
  // faces: the editor interrupts it when a newer request comes (SolveOptions::interrupt).
  double newton_krylov_above = 2e-3;
  // A drag's frame (SolveOptions::drag_frame) that its caller gives two or more iterations
  // (the editor gives a batch as many as fit 50 ms) makes the second a Newton-Krylov step
  // instead of a cycle. One cycle a frame lags the minimum along soft modes, which the step
  // takes as the cycles cannot: the drag benchmark's last frames ended 0.000-0.016% of the
  // diagonal from their minima (elephant, armadillo, beetle, skull, koala) instead of
  // 0.011-5.1%, for 2.5-4 times a cycle's time; two cycles were no closer
  // (docs/decisions/0008-newton-krylov-step-in-drag-frames.md).
  bool newton_krylov_in_frames = true;
  NewtonKrylovOptions newton_krylov;
  // A drag's preview (HierarchicalSolver::begin_preview) runs on the finest coarse level with
  // at most this many couplings, so that a preview frame costs about the same on any mesh:
  // its cycles, and one pass over the fine bodies for the picture.
  int preview_max_couplings = 300000;
};

struct HierarchicalTimings {
  double newton_krylov = 0.0;  // Newton-Krylov steps (all their phases)
  int newton_krylov_steps = 0;
  int newton_krylov_iterations = 0;  // their conjugate-gradient iterations
  int newton_krylov_applications = 0;  // their preconditioner's applications
  double restrict_prolong = 0.0;
  double acceleration = 0.0;  // Anderson proposals and their energy
  double coarse = 0.0;
  double sweeps = 0.0;
  int cycles = 0;
  int accepted_accelerations = 0;
};

class HierarchicalSolver {
 public:
  HierarchicalSolver(const RigidSystem& fine, const HierarchicalOptions& options = {});
  ~HierarchicalSolver();

  // One cycle from `fine_state` (updated in place). Returns the fine energy after it. With
  // acceleration, the cycle's result is replaced by the accelerated proposal when that has
  // lower energy (otherwise the history is restarted): lower than `energy_before`, the energy
  // of `fine_state` on entry, when the caller knows it, else lower than the cycle's result.
  double cycle(std::vector<BodyState>& fine_state,
               double energy_before = std::numeric_limits<double>::quiet_NaN());
  // Makes the coarse factor of `fine_state` ahead of the first cycle, which then reuses it
  // instead of factorizing in the foreground (a drag's first frame: about 0.2 s at 240k
  // faces). Cycles from a state near `fine_state` reach the same minimum.
  void prepare(const std::vector<BodyState>& fine_state);
  // Called in every cycle once the coarse correction has reached the fine state, before the
  // fine sweeps: a caller that shows the mesh (the editor, at 240k faces a cycle takes about
  // 100 ms) can show it twice a cycle. Empty: nothing is called.
  void set_coarse_correction_callback(std::function<void()> callback) {
    coarse_correction_callback_ = std::move(callback);
  }
  // Asked by Newton-Krylov steps before each of their conjugate-gradient iterations
  // (SolveOptions::interrupt); empty: never. When it cut a step short, cycle() changed
  // nothing, returned the energy it was given and interrupted() is true until the next cycle.
  void set_interrupt(std::function<bool()> interrupt) { interrupt_ = std::move(interrupt); }
  bool interrupted() const { return interrupted_; }
  // Forget the acceleration history (the targets changed).
  void restart_acceleration() {
    acceleration_.reset();
    cycles_since_restart_ = 0;
    krylov_failed_ = false;
    last_decrease_ = 1.0;
    last_was_newton_ = false;
    frame_step_next_ = false;
    settle_start_decrease_.reset();
  }

  int levels() const { return int(levels_.size()) + 1; }  // including the fine level
  // Steps a background refactorization gets during a drag (0: none; with the automatic
  // setting, known after the first coarse factorization).
  int drag_factor_lag() const;
  // Coarse Newton steps per cycle: coarse_iterations on every visit of the coarsest level,
  // which each intermediate level visits intermediate_cycles times.
  int coarse_steps_per_cycle() const { return coarse_steps_from(1); }
  int bodies(int level) const;  // level 0 = fine
  // A level's system as its last restriction left it (level 0: the fine system).
  const RigidSystem& system(int level) const;
  const HierarchicalTimings& timings() const { return timings_; }
  const GlobalSolver* coarse_solver() const { return coarse_solver_.get(); }
  // Frees the Newton-Krylov steps' matrices and vectors (about 300 MB at 240k faces) once a
  // solve has converged; the next solve that settles makes them again (about 0.25 s there).
  void release_newton_krylov() { newton_krylov_.reset(); }
  // The iterations the caller means to run on the current targets (a drag's frame: 1). A solve
  // of more than the cycles a drag counts will most likely take Newton-Krylov steps; when its
  // coarse level must factorize in the foreground (on one thread: about 0.2 s at 240k faces),
  // the steps' structure is built beside it, in parallel, instead of in the first step.
  void set_iterations_ahead(int iterations) { iterations_ahead_ = iterations; }
  // Whether the coming iterations are a drag's frame (SolveOptions::drag_frame), not a jump's
  // sub-step or a solve to convergence (HierarchicalOptions::newton_krylov_in_frames).
  void set_drag_frame(bool drag_frame) { drag_frame_ = drag_frame; }
  bool newton_krylov_ready() const { return newton_krylov_ && newton_krylov_->structure_built(); }

  // A preview of a drag on a mesh whose cycles outlast a frame: the same energy minimized over
  // a coarse level's clusters only, each moved rigidly on top of the fine state as it was when
  // the preview began. Its frames restrict nothing from the fine level and sweep none of it,
  // so they cost what the coarse levels cost; the picture (previewed) is one pass over the
  // fine bodies. The fine state stays as it was, handles aside, until end_preview carries the
  // clusters' motions into it, from where cycles converge to the full resolution's minimum.
  // `level`: a coarse level, 1 to levels() - 1 (-1: automatic_preview_level). The bodies that
  // are not free must come first in the fine system, as the Deformer's handles do.
  // `fine_energy`: the energy of `fine_state` when the caller knows it (NaN: computed here).
  void begin_preview(const std::vector<BodyState>& fine_state, int level = -1,
                     double fine_energy = std::numeric_limits<double>::quiet_NaN());
  // One frame at the current targets: the fine state's locked bodies (moved by the caller)
  // and springs are taken over, then one cycle on the preview's levels. Returns the fine
  // energy of the picture (exact: clusters move their fine prisms rigidly).
  double preview_frame(const std::vector<BodyState>& fine_state);
  // Carries the preview's motions into `fine_state` and ends it.
  void end_preview(std::vector<BodyState>& fine_state);
  void cancel_preview() { preview_level_ = -1; }  // the fine state was replaced: drop it
  bool previewing() const { return preview_level_ > 0; }
  int preview_level() const { return preview_level_; }
  // The finest coarse level with at most HierarchicalOptions::preview_max_couplings couplings
  // (the coarsest when none has so few); -1 without coarse levels.
  int automatic_preview_level() const;
  // A fine body's state as the preview shows it (previewing() only).
  BodyState previewed(const std::vector<BodyState>& fine_state, int body) const {
    const BodyState& base = preview_base(fine_state, body);
    const int c = preview_cluster_[size_t(body)];
    const BodyState& corr = (*preview_correction_)[size_t(c)];
    return {corr.rotation * base.rotation,
            corr.rotation * (base.position - (*preview_center_)[size_t(c)]) + corr.position};
  }
  // Where the preview shows the point `x` (relative to the body's rest centre) of a fine body:
  // two turns of a vector, where previewed() turns a matrix.
  Vec3 previewed_point(const std::vector<BodyState>& fine_state, int body, const Vec3& x) const {
    const BodyState& base = preview_base(fine_state, body);
    const int c = preview_cluster_[size_t(body)];
    const BodyState& corr = (*preview_correction_)[size_t(c)];
    return corr.rotation * (base.rotation * x + base.position - (*preview_center_)[size_t(c)]) +
           corr.position;
  }

 private:
  struct Level;
  static void merge_coupled_pairs(Level& level, Level* finer_level, const RigidSystem& fine,
                                  const std::vector<int>& finer_coupling_fine,
                                  const std::vector<int>& cluster_of);
  void build_levels(const RigidSystem& fine);  // levels_, from the cluster hierarchy
  // Takes the level's joints and springs from the next finer level in its current state
  // (`finer_orientation`: that level's own orientations, null for the fine level).
  void restrict_level(Level& level, const RigidSystem& finer,
                      const std::vector<BodyState>& finer_state,
                      const std::vector<Mat3>* finer_orientation);
  double plain_cycle(std::vector<BodyState>& fine_state, bool with_energy = true);
  double cycle_only(std::vector<BodyState>& fine_state, double energy_before);  // no Newton step
  // Improves level l's corrections (restricted already) with the levels above it and sweeps.
  void solve_level(int l);
  // Coarse Newton steps of one visit of `level` (1: the first coarse level, as a cycle visits it).
  int coarse_steps_from(int level) const;
  // The state a preview moves: a locked body's as the preview began, another's as it is.
  const BodyState& preview_base(const std::vector<BodyState>& fine_state, int body) const {
    return size_t(body) < preview_anchor_.size() ? preview_anchor_[size_t(body)]
                                                 : fine_state[size_t(body)];
  }
  // Applies the level's corrections to the bodies of the next finer level.
  void prolong_level(const Level& level, std::vector<BodyState>& finer_state) const;

  const RigidSystem& fine_;
  HierarchicalOptions options_;
  std::vector<std::unique_ptr<Level>> levels_;  // finest coarse level first
  std::function<void()> coarse_correction_callback_;
  std::function<bool()> interrupt_;
  bool interrupted_ = false;
  std::unique_ptr<GlobalSolver> coarse_solver_;
  SweepPlan fine_plan_;
  bool coarse_exact_ = false;
  AndersonAcceleration acceleration_;
  std::vector<BodyState> cycle_input_, proposal_;
  int cycles_since_restart_ = 0;
  std::unique_ptr<NewtonKrylov> newton_krylov_;  // made on first use
  int iterations_ahead_ = 1;
  bool drag_frame_ = false;
  // The last cycle was a frame's first and its caller meant to run more on the same targets.
  bool frame_step_next_ = false;
  bool krylov_failed_ = false;    // a step did not lower the energy since the targets moved
  double last_decrease_ = 1.0;    // relative energy decrease of the last iteration
  bool last_was_newton_ = false;  // the last iteration was a Newton-Krylov step
  // The relative decrease of the first cycle at fixed targets (the second since they moved):
  // whether this settle started far from the minimum (newton_krylov_above), and near it.
  std::optional<double> settle_start_decrease_;
  // The preview (begin_preview): its level (-1: none), each fine body's cluster there, the
  // fine states of the leading locked bodies when it began (the level's couplings see them
  // there; the caller moves them since), the level's corrections and centres, and the
  // difference between the fine energy and the level's (joints inside clusters).
  int preview_level_ = -1;
  std::vector<int> preview_cluster_;
  std::vector<BodyState> preview_anchor_;
  const std::vector<BodyState>* preview_correction_ = nullptr;
  const std::vector<Vec3>* preview_center_ = nullptr;
  double preview_energy_offset_ = 0.0;
  HierarchicalTimings timings_;
};

// The automatic HierarchicalOptions::drag_factor_lag, in coarse steps: the cycles a coarse
// factorization of `factorization_flops` takes on a background thread beside cycles on
// `fine_bodies` bodies, times the coarse steps per cycle, within [2, 16].
int automatic_drag_factor_lag(double factorization_flops, int fine_bodies,
                              int coarse_steps_per_cycle);

}  // namespace primo
