#pragma once
// The solver thread. It owns the Deformer (which is not thread-safe); the UI never touches it.
// The UI submits a problem when the structure changes (handles, modes, prism settings,
// painted factors: the Deformer is rebuilt, keeping the current pose) and targets when only
// poses change (latest wins: a drag sends a target per frame and the worker takes the newest).
// The worker runs a few iterations at a time, warm-started, and publishes a snapshot after
// each batch: positions, normals, energy, iteration counts, timings and, when asked, the
// per-face energy heat map and the prism corners. Until the latest request has converged
// (or hit solver.max_iterations) it keeps iterating; then it sleeps.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <optional>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "document/edit_state.h"
#include "document/selection/mesh_topology.h"
#include "primo/solve/deformer.h"
#include "primo/scenario/scenario.h"

namespace primo::editor {

// The method the editor solves with: the scenario's solver.method when it names one, else what
// `primo deform` picks by default (global Newton up to 20,000 faces, hierarchical above), so
// that both end at the same result. It is scenario_solve_method (primo/scenario/scenario_solve.h),
// which `primo deform` and `primo replay` use too.
SolveMethod interactive_solve_method(SolverMethod requested, int n_faces);

struct SolverProblem {
  std::shared_ptr<const Mesh> mesh;
  std::shared_ptr<const MeshTopology> topology;
  DeformationInputs inputs;  // handle transforms and force offsets included
  SolverSpec spec;           // max_iterations and tolerance of a settle
  // Where to start instead of rest or the current pose: an opened scenario's solved state
  // (one motion per face; empty for none).
  std::vector<RigidTransform> start_motions;
};

struct SolverTargets {
  std::vector<RigidTransform> handles;  // one per engine handle
  std::vector<Vec3> forces;             // one per engine force
  // The handles' rotations' whole turns (primo/model/turn.h); none or nullopt: continue the
  // handle's turn.
  std::vector<std::optional<Vec3>> turns = {};
};

enum class SolverPhase {
  Idle,      // no problem yet
  Building,  // making prisms and bodies
  Solving,   // iterating towards the current targets
  Settled,   // converged for the latest request
  Stopped,   // solver.max_iterations reached without converging
  Failed,    // the problem could not be built; `error` says why
};
const char* phase_label(SolverPhase phase);

// Immutable once published; shared with the UI.
struct SolverGeometry {
  std::vector<Vec3> positions;        // deformed vertices
  std::vector<float> render_positions;  // 3 per vertex
  std::vector<float> render_normals;    // 3 per vertex
  std::vector<float> face_energy;       // per face energy density (empty unless requested)
  double energy_scale = 1.0;            // robust maximum of face_energy
  std::vector<float> prism_corners;     // per corner: bottom xyz, top xyz (empty unless requested)
  // The solver's per-face motions, published when a request settles or stops (what a saved
  // scenario stores as its solved state); null while solving.
  std::shared_ptr<const std::vector<RigidTransform>> face_motions;
  // The picture is a drag's preview (Deformer::preview: the coarse levels' solve carried to
  // every vertex), not the full resolution, which follows once the hand pauses.
  bool preview = false;
  std::uint64_t serial = 0;             // increases with every publication
  // The serial of the problem request this geometry was solved for: a reader that switched
  // documents drops geometry of problems it submitted before the switch.
  std::uint64_t problem_serial = 0;
};

struct SolverStatus {
  SolverPhase phase = SolverPhase::Idle;
  std::string error;
  std::uint64_t request_serial = 0;  // latest request this status reflects
  double energy = 0.0;
  int iterations = 0;        // since the last request
  long total_iterations = 0;
  double seconds_per_iteration = 0.0;
  double build_seconds = 0.0;
  double progress = 0.0;     // rough convergence estimate in [0, 1]
  std::string detail;        // what a long first iteration does ("building the hierarchy")
  bool solver_ready = false;  // the solver of the current problem is set up (no first-use pause)
  bool stopped_by_user = false;  // Stopped by SolverWorker::stop, not by the iteration limit
  // A full cycle outlasts a frame of the drag's pictures (kPreviewAbove): drags show previews.
  bool previews = false;
  std::chrono::steady_clock::time_point phase_start;
  std::shared_ptr<const SolverGeometry> geometry;

  bool busy() const { return phase == SolverPhase::Building || phase == SolverPhase::Solving; }
  // The published picture is a drag's preview (SolverGeometry::preview).
  bool showing_preview() const { return geometry && geometry->preview; }
};

class SolverWorker {
 public:
  // `notify` is called from the worker thread after each publication (e.g. to wake the UI).
  explicit SolverWorker(std::function<void()> notify = {});
  ~SolverWorker();
  SolverWorker(const SolverWorker&) = delete;
  SolverWorker& operator=(const SolverWorker&) = delete;

  // Each returns the request's serial number.
  std::uint64_t submit_problem(std::shared_ptr<const SolverProblem> problem);
  std::uint64_t submit_targets(SolverTargets targets);
  // What to compute at each publication besides positions and normals.
  void set_outputs(bool energy_map, bool prism_corners);
  // With the limit (the default, as batch commands and replays have it), a request stops at
  // the problem's solver.max_iterations; without it (the editor), it settles until converged
  // unless stop() is called.
  void set_iteration_limit(bool limited);
  // A drag whose frames at full resolution take longer than this many seconds shows previews
  // (Deformer::preview) until the hand pauses (default 0.1: ten pictures a second).
  void set_preview_above(double seconds) { preview_above_ = seconds; }
  // Ends the current solve where it is (phase Stopped, stopped_by_user); the next request, or
  // the same targets submitted again, solves on from there.
  void stop();

  SolverStatus status() const;
  // True when the latest request has been fully handled (settled, stopped or failed).
  bool idle_for_latest() const;
  // Blocks until idle_for_latest() or the timeout; returns whether it became idle.
  bool wait_idle(double timeout_seconds) const;

 private:
  void run();
  bool build(const SolverProblem& problem);  // false when it failed (the old deformer stays)
  void apply(const SolverTargets& targets);
  void step();
  void publish_geometry(bool with_motions = false);
  void set_phase(SolverPhase phase, std::string error = {});

  std::function<void()> notify_;
  mutable std::mutex mutex_;
  mutable std::condition_variable wake_;         // worker waits for requests
  mutable std::condition_variable published_;    // wait_idle waits for progress
  bool stop_ = false;
  std::uint64_t serial_ = 0;
  std::shared_ptr<const SolverProblem> pending_problem_;
  std::uint64_t pending_problem_serial_ = 0;
  std::unique_ptr<SolverTargets> pending_targets_;
  std::uint64_t pending_targets_serial_ = 0;
  bool want_energy_ = false, want_prisms_ = false, outputs_dirty_ = false;
  bool iteration_limit_ = true;
  std::atomic<double> preview_above_;
  bool stop_requested_ = false;
  SolverStatus status_;

  // Worker-thread only.
  std::shared_ptr<const SolverProblem> problem_;
  std::unique_ptr<Deformer> deformer_;
  int chunk_ = 1;
  // Seconds of a drag's frame solved at full resolution (the last measured; 0: none yet).
  double full_frame_seconds_ = 0.0;
  bool first_solve_ = true;  // the first solve of a Deformer also sets up its solver
  std::chrono::steady_clock::time_point last_request_;
  bool confirming_ = false;
  double first_decrease_ = 0.0;
  bool energy_on_ = false, prisms_on_ = false;
  std::uint64_t geometry_serial_ = 0;
  // Geometries published before, whose buffers a publication reuses once only this holds them
  // (the status holds the newest, the window the one on screen).
  std::shared_ptr<SolverGeometry> spare_geometry_[3];
  std::uint64_t built_problem_serial_ = 0;  // the request deformer_ was built from
  bool limited_ = true;  // iteration_limit_ as of the latest request

  std::thread thread_;
};

}  // namespace primo::editor
