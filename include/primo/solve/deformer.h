#pragma once
// The deformation engine as the editor and `primo deform` use it: set up once for a mesh,
// its prism parameters, handles and forces; then move handle targets and iterate, each solve
// warm-started from the current state; read vertex positions and energy. Nothing is printed.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "primo/model/constraints.h"
#include "primo/solve/drag_predictor.h"
#include "primo/solve/global_solver.h"
#include "primo/solve/hierarchical_solver.h"
#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_order.h"
#include "primo/model/prism_layer.h"
#include "primo/model/rigid_system.h"

namespace primo {

enum class SolveMethod {
  Global,        // Newton matching on all prisms (paper Sect. 4.2)
  Local,         // Gauss-Seidel sweeps of Horn matches (Sect. 4.1)
  Hierarchical,  // coarse Newton + sweeps per level, one cycle per iteration (Sect. 4.3)
};

// The solver to use when none is asked for (primo deform, the editor): global Newton up to
// 20,000 faces, where it converges exactly in a few iterations; hierarchical above, where one
// global iteration costs seconds and gigabytes (measurements in docs/engine.md).
inline constexpr size_t kHierarchicalFromFaces = 20000;
inline SolveMethod default_solve_method(size_t n_faces) {
  return n_faces > kHierarchicalFromFaces ? SolveMethod::Hierarchical : SolveMethod::Global;
}

// How a solve reaches targets that jumped far from the ones the state was solved for.
// A one-step solve of a large edit (a handle turned 180 degrees from rest) starts far from
// any minimum and often lands in a poor one: the tube of the paper's Figure 2 bent 180 degrees
// in one step collapses flat, where the same edit made by dragging stays round. So a jump
// is followed as a drag would follow it: the targets move from where the state was solved
// to where they were set in sub-steps no larger than these, each solved loosely and warm-
// started, and the last one to the full tolerance (docs/engine.md, "Large steps").
// A jump is followed in at most this many sub-steps (PathOptions).
inline constexpr int kMaxPathSteps = 1000;

struct PathOptions {
  bool enabled = true;
  double max_turn_deg = 15.0;  // largest rotation of any handle per sub-step
  double max_move = 0.1;       // largest move of a handle centroid or force offset per
                               // sub-step, as a fraction of the bounding-box diagonal
  double step_tolerance = 1e-2;  // relative energy change that ends a sub-step
  int max_step_iterations = 2;   // and at most this many iterations per sub-step
  // Sub-step iterations per call (the editor's solver thread passes its batch size): a path
  // left unfinished is resumed by the next call.
  int max_iterations = 100000;
};

struct SolveOptions {
  SolveMethod method = SolveMethod::Global;
  int max_iterations = 100;  // iterations at the final targets (path sub-steps not counted)
  double tolerance = 1e-8;  // stop when an iteration lowers E by less than tolerance * E
  PathOptions path;
  // Global only: switch to exact-Hessian Newton steps once Gauss-Newton takes full steps
  // that lower the energy by less than this fraction (0 disables exact steps).
  double exact_hessian_below = 1e-1;
  // Global only: first converge with hierarchical cycles (including any path), then polish
  // with Newton from there. Cycles cost a few milliseconds where a Newton iteration costs a
  // factorization, and on the default material they converge in 20-30 cycles: the Figure 2
  // tube (4,800 triangles) bent 180 degrees takes 0.3 s instead of 3-4 s, and the Newton
  // polish makes the result the global solve's minimum (exact steps near it). `primo deform`
  // uses it when no solver is asked for.
  bool hierarchical_start = false;
  int max_hierarchical_cycles = 300;  // of that first stage
  // Hierarchical only. The hierarchy is built on the first hierarchical solve and kept until
  // the handle set changes (a new Deformer).
  HierarchicalOptions hierarchical;
  // Hierarchical only: called in each cycle once the coarse levels' correction has reached
  // every prism, before the fine sweeps; vertex_positions() then gives that intermediate
  // shape (HierarchicalSolver::set_coarse_correction_callback). The editor shows it on big
  // meshes, so that the surface moves twice a cycle while a handle is dragged.
  std::function<void()> on_coarse_correction;
  // Asked before every iteration at the final targets and, inside a Newton-Krylov step, before
  // each of its conjugate-gradient iterations: true ends the solve there (stop_reason
  // "interrupted", not converged), in the state the last finished iteration left, and a later
  // solve goes on from it. The editor's solver thread asks whether a newer request came:
  // a Newton-Krylov step at 240k faces takes 0.4-0.9 s (empty: never).
  std::function<bool()> interrupt;
  // A solve that follows a target move like the one before it (a drag's frame) starts from
  // the state moved on by this fraction of its change over the last frame, where that lowers
  // the energy (DragPredictor; 0: from the state as it is). Not across a jump followed in
  // sub-steps (PathOptions). Measured in docs/decisions/0004-drag-prediction.md.
  double drag_prediction = 1.0;
  // The solve is a drag's frame: its targets moved with the hand since the last solve (the
  // editor's batches while a handle is dragged, the drag benchmark's frames). Hierarchical:
  // given two or more iterations, the second is a Newton-Krylov step
  // (HierarchicalOptions::newton_krylov_in_frames); not in a jump's sub-steps.
  bool drag_frame = false;
};

struct SolveReport {
  int iterations = 0;
  bool converged = false;
  double initial_energy = 0.0;
  double energy = 0.0;
  double seconds = 0.0;
  int exact_newton_steps = 0;
  int path_steps = 0;       // sub-steps of a large jump solved in this call (PathOptions)
  int path_iterations = 0;  // iterations spent on them (not in `iterations`)
  int hierarchical_cycles = 0;  // of SolveOptions::hierarchical_start (not in `iterations`)
  std::vector<double> energies;  // after each iteration at the final targets
  // "tolerance", "energy floor", "no further decrease", "max_iterations", "path budget",
  // "already converged", "interrupted" (SolveOptions::interrupt), or "not finite": the energy
  // at the start, or after an iteration, was NaN or infinite (settings too large); the state
  // is the last finite one, converged false.
  std::string stop_reason;
};

class Deformer {
 public:
  // Builds the prisms and bodies: one body per handle, one per remaining face. Handles must
  // not share faces. Throws Error for invalid input (face indices, overlapping handles,
  // degenerate extrusion directions). The state starts with every free prism at rest and
  // every handle at its full transform.
  Deformer(const Mesh& mesh, const PrismParameters& params, std::vector<Handle> handles,
           std::vector<Force> forces = {});
  ~Deformer();
  Deformer(Deformer&&) noexcept;
  Deformer& operator=(Deformer&&) noexcept;

  // The solver numbers faces, vertices and prism corners in an order of its own, made from
  // the geometry so that neither speed nor result depends on the file's order (MeshOrder).
  // prisms(), system(), body_states() and the solvers use it; every other member, the
  // handles' and forces' faces included, speaks the file's numbering.
  const MeshOrder& order() const { return order_; }
  const PrismLayer& prisms() const { return layer_; }
  const RigidSystem& system() const { return system_; }
  const std::vector<Handle>& handles() const { return handles_; }
  const std::vector<Force>& forces() const { return forces_; }

  // Moves a handle's target. Fixed handles jump there; position handles move their pinned
  // centroid and keep their current rotation; orientation handles take the new rotation and
  // keep their current translation. Free prisms are untouched (warm start).
  // `turn` is the rotation with its whole turns (turn.h), which a path from the state solved
  // before follows through its whole angle; absent, the turn of the rotation nearest the
  // handle's current one (small steps accumulate, as a drag's frames do). Throws Error when
  // the turn does not make the rotation.
  void set_handle_transform(int handle, const RigidTransform& transform,
                            const std::optional<Vec3>& turn = std::nullopt);
  void set_force_offset(int force, const Vec3& target_offset);

  // Runs iterations from the current state until the stopping rule of the scenario format.
  // Global solves carry their Gauss-Newton/exact-Newton mode over to the next call, so a drag
  // solved one iteration per frame converges as fast as one long solve.
  // When nothing changed since a solve with the same method converged to the same or a
  // tighter tolerance, returns at once (0 iterations).
  SolveReport solve(const SolveOptions& options);
  // Sets up the solver that `options.method` uses, without iterating: the hierarchy, its
  // coarse symbolic analysis and a coarse factor of the current state, or the global
  // system's symbolic analysis. A solve sets the solver up on first use, but a problem still
  // at rest returns before that, so the first frame of the drag that follows would pay for it
  // (about 0.6 s at 240k faces). The state is unchanged, and later solves reach the same
  // minimum (the first cycles reuse the coarse factor made here).
  void prepare(const SolveOptions& options);

  // A drag's frame on a mesh whose full cycles outlast a frame (a million faces: about 0.3 s
  // on two cores): one cycle of the coarse levels only, their clusters moved rigidly on top of
  // the state the preview began from (HierarchicalSolver::begin_preview), at a cost that
  // hardly grows with the mesh. vertex_positions(), face_motions() and energy() then show the
  // preview; the next solve() starts from it and converges to the full resolution's minimum.
  // options.max_iterations cycles (at least one) at the current targets. Methods other than
  // hierarchical solve() instead.
  SolveReport preview(const SolveOptions& options);
  bool previewing() const { return hierarchical_ && hierarchical_->previewing(); }

  // The energy of the current state (known without a pass over the joints after a solve or
  // a handle move); while previewing, the preview's.
  double energy() const {
    if (previewing()) return preview_energy_;
    return known_energy_ ? *known_energy_ : system_.energy(state_);
  }
  // Deformed vertex positions: the average over incident prisms of each prism's motion
  // applied to its own width-scaled copy of the vertex. Vertices without faces stay put.
  std::vector<Vec3> vertex_positions() const;
  // The same into `points`, whose storage is reused: a caller asking every frame (the editor,
  // the drag benchmark) keeps one buffer instead of a fresh 11 MB a frame at a million faces.
  void vertex_positions(std::vector<Vec3>& points) const;
  // A copy of `mesh` with the deformed positions.
  Mesh deformed_mesh(const Mesh& mesh) const;

  // Per-face rigid motions in rest coordinates (x -> R x + t), and setting them as the state
  // (a warm start: the editor keeping its pose through a rebuild, a scenario's solved state).
  // Free bodies take their faces' motion; a position handle takes the rotation, an orientation
  // handle the translation, and what a handle prescribes stays. The state then counts as the
  // one for the current targets: no path is followed from rest (PathOptions).
  std::vector<RigidTransform> face_motions() const;
  void set_face_motions(const std::vector<RigidTransform>& motions);
  // The solver's state (while previewing, the one the preview began from, handles moved).
  const std::vector<BodyState>& body_states() const { return state_; }
  const GlobalSolver* global_solver() const { return global_.get(); }
  const HierarchicalSolver* hierarchical_solver() const { return hierarchical_.get(); }

  // Every free prism back to rest, every handle to its current full transform.
  void reset();

  // Whether a solve still has sub-steps to take before the targets (PathOptions): true
  // after targets jumped far, until a solve has walked the whole path.
  bool path_pending(const PathOptions& options) const;

 private:
  BodyState handle_state(int handle) const;
  // Moves a handle body as set_handle_transform does, to `transform` instead of the target.
  void place_handle(int handle, const RigidTransform& transform);
  // Sub-steps from the targets the state was solved for to the set ones (1: none needed).
  int path_steps_needed(const PathOptions& options) const;
  // Walks the path within the call's budget; false when the budget ran out first.
  bool follow_path(const SolveOptions& options, SolveReport& report);
  // One iteration of `options.method` from energy e; returns the energy after, or nullopt
  // when no step lowers the energy (a minimum to machine precision).
  std::optional<double> iterate(const SolveOptions& options, double e, SolveReport& report);
  // iterate(), except that an iteration ending in a non-finite energy is undone and sets
  // report.stop_reason to "not finite".
  std::optional<double> guarded_iterate(const SolveOptions& options, double e, SolveReport& report);
  // solve() after the drag prediction: the stages of a solve at the set targets.
  SolveReport solve_now(const SolveOptions& options);
  // Starts from `predictor`'s prediction for a target move `move`, where it lowers the energy,
  // and remembers the state for the next one.
  void predict(DragPredictor& predictor, const std::vector<double>& move, double multiplier);
  // How the targets moved since the state was solved, in pieces of 3 entries: per handle
  // what it prescribes of its centre's move and of its turn (axis times angle), per force its
  // offset's move, each over the sub-step limit of `limits`, so that a piece's length is the
  // sub-steps it needs and entries weigh alike (the drag predictor compares moves by them).
  std::vector<double> target_move(const PathOptions& limits) const;
  bool make_solver(const SolveOptions& options);  // whether it was made now
  double body_energy(int body) const;  // of the joints and springs on one body
  // vertex_positions: each vertex the mean of its prisms' rest copies plus the mean of their
  // displacements, `displacement(body, point relative to the body's rest centre)`.
  template <class Displacement>
  void gather_vertices(std::vector<Vec3>& points, const Displacement& displacement) const;
  void rebuild_springs();
  void place_springs(const std::vector<Vec3>& offsets);  // one target offset per force

  MeshOrder order_;
  std::vector<Vec3> rest_points_;  // in the solver's order
  PrismLayer layer_;
  std::vector<Handle> handles_;
  std::vector<Force> forces_;
  std::vector<std::vector<int>> force_faces_;  // each force's faces in the solver's numbering
  RigidSystem system_;
  // Each body's rest_center, read by the vertex update and face_motions for every face: from
  // the 232-byte Bodies it cost a cache line a face (at 240k faces the vertex update took
  // 6.6-6.9 ms a frame against 4.5-5.5).
  std::vector<Vec3> body_center_;
  std::vector<int> corner_body_;  // each prism corner's body (the vertex update's gather)
  std::vector<BodyState> state_;
  std::vector<BodyState> last_good_state_;  // before the current iteration (guarded_iterate)
  DragPredictor predictor_;
  std::vector<BodyState> predicted_;
  std::unique_ptr<GlobalSolver> global_;  // made on first use: symbolic analysis once
  std::unique_ptr<HierarchicalSolver> hierarchical_;  // made on first use
  void problem_changed();  // targets or state were set from outside
  // Carries a preview into state_ (a solve goes on from it) or drops it (the state is set).
  void end_preview();
  void cancel_preview();
  // The state is the one for the targets set now (solved_transforms_, solved_offsets_): a
  // later solve follows no path to them.
  void solved_for_current_targets();
  double preview_energy_ = 0.0;
  // The last solve converged with this method and tolerance, and nothing changed since.
  bool settled_ = false;
  // The state is the minimum the last solve converged to (no iteration since; a jump from it
  // is an undo or a redo, not a drag's frame), and the hierarchy's coarse factor is of it.
  bool solved_to_minimum_ = false, coarse_factor_of_state_ = false;
  SolveMethod settled_method_ = SolveMethod::Global;
  double settled_tolerance_ = 0.0;
  bool exact_newton_ = false;  // the next global iteration takes an exact-Hessian step
  // The energy of state_ when known: set by a solve, carried through a handle move by
  // recomputing the handle's own joints only. A drag frame at 240k faces saves a pass over
  // all joints (about 5 ms of a 100 ms frame).
  std::optional<double> known_energy_;
  // The targets the state was last solved for (the start of a path): rest and zero offsets
  // at first, the set targets after every solve, the targets of the sub-step reached when a
  // path is interrupted.
  std::vector<RigidTransform> solved_transforms_;
  std::vector<Vec3> solved_turns_;  // their rotations' turns (handles_[h].turn is the target's)
  std::vector<Vec3> solved_offsets_;
  // A path a call's budget cut short (follow_path): its targets, the sub-step it was in and
  // the iterations that had, and its drag predictor's record, for the next call.
  struct PathProgress {
    std::vector<RigidTransform> end;
    std::vector<Vec3> end_turns;
    std::vector<Vec3> end_offsets;
    std::vector<RigidTransform> step;
    std::vector<Vec3> step_turns;
    std::vector<Vec3> step_offsets;
    int step_iterations = 0;
    DragPredictor predictor;
  };
  PathProgress path_;
};

}  // namespace primo
