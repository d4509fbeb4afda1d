#include "solver_worker.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <tbb/task_scheduler_observer.h>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include "view/energy_map.h"
#include "primo/util/parallel.h"
#include "primo/scenario/scenario_solve.h"

namespace primo::editor {
namespace {

using Clock = std::chrono::steady_clock;

// Wall time one batch of iterations should take: short enough that a new drag target is
// picked up quickly, long enough that exact Newton steps (which need a previous step in
// the same solve) happen on small meshes.
constexpr double kBatchSeconds = 0.05;
constexpr int kMaxBatch = 8;
// Once no request came for this long, the drag is over: batches get at least kSettleBatch
// iterations, so that the engine's exact Newton steps (which follow a Gauss-Newton step within
// one solve) finish the convergence as `primo deform` does. One-iteration Gauss-Newton
// batches converge only linearly and can stop early on a small, backtracked step.
constexpr double kDragPauseSeconds = 0.3;
constexpr int kSettleBatch = 4;
// A drag whose frames at full resolution take longer than this shows previews instead
// (Deformer::preview), so that the picture follows the hand ten times a second on any mesh.
constexpr double kPreviewAbove = 0.1;  // SolverWorker::set_preview_above

}  // namespace

SolveMethod interactive_solve_method(SolverMethod requested, int n_faces) {
  return scenario_solve_method(requested, size_t(n_faces));
}

namespace {

bool solver_set_up(const Deformer& deformer, SolveMethod method) {
  switch (method) {
    case SolveMethod::Global: return deformer.global_solver() != nullptr;
    case SolveMethod::Hierarchical: return deformer.hierarchical_solver() != nullptr;
    case SolveMethod::Local: return true;  // nothing to set up
  }
  return true;
}

}  // namespace

const char* phase_label(SolverPhase phase) {
  switch (phase) {
    case SolverPhase::Idle: return "idle";
    case SolverPhase::Building: return "building prisms";
    case SolverPhase::Solving: return "solving";
    case SolverPhase::Settled: return "settled";
    case SolverPhase::Stopped: return "stopped";
    case SolverPhase::Failed: return "failed";
  }
  return "?";
}

SolverWorker::SolverWorker(std::function<void()> notify)
    : notify_(std::move(notify)), preview_above_(kPreviewAbove) {
  status_.phase_start = Clock::now();
  thread_ = std::thread([this] { run(); });
}

SolverWorker::~SolverWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t SolverWorker::submit_problem(std::shared_ptr<const SolverProblem> problem) {
  std::uint64_t serial;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    serial = ++serial_;
    pending_problem_ = std::move(problem);
    pending_problem_serial_ = serial;
    pending_targets_.reset();  // the problem carries newer targets
  }
  wake_.notify_all();
  return serial;
}

std::uint64_t SolverWorker::submit_targets(SolverTargets targets) {
  std::uint64_t serial;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    serial = ++serial_;
    pending_targets_ = std::make_unique<SolverTargets>(std::move(targets));
    pending_targets_serial_ = serial;
  }
  wake_.notify_all();
  return serial;
}

void SolverWorker::set_outputs(bool energy_map, bool prism_corners) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (want_energy_ == energy_map && want_prisms_ == prism_corners) return;
    want_energy_ = energy_map;
    want_prisms_ = prism_corners;
    outputs_dirty_ = true;
  }
  wake_.notify_all();
}

void SolverWorker::set_iteration_limit(bool limited) {
  std::lock_guard<std::mutex> lock(mutex_);
  iteration_limit_ = limited;
}

void SolverWorker::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_requested_ = true;
  }
  wake_.notify_all();
}

SolverStatus SolverWorker::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

bool SolverWorker::idle_for_latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_.request_serial == serial_ && !status_.busy() && !pending_problem_ &&
         !pending_targets_;
}

bool SolverWorker::wait_idle(double timeout_seconds) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return published_.wait_for(lock, std::chrono::duration<double>(timeout_seconds), [&] {
    return status_.request_serial == serial_ && !status_.busy() && !pending_problem_ &&
           !pending_targets_;
  });
}

void SolverWorker::set_phase(SolverPhase phase, std::string error) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.phase != phase) status_.phase_start = Clock::now();
    status_.phase = phase;
    status_.error = std::move(error);
  }
  published_.notify_all();
  if (notify_) notify_();
}

namespace {

// The engine's parallel loops run on oneTBB's worker threads: each one that joins lowers its
// own priority as the solver thread does, so that the window's frames never wait for them.
class LowerWorkerPriority : public tbb::task_scheduler_observer {
 public:
  LowerWorkerPriority() { observe(true); }
  ~LowerWorkerPriority() override { observe(false); }
  void on_scheduler_entry(bool worker) override {
#ifdef __linux__
    if (worker) setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), 5);
#endif
  }
};

}  // namespace

void SolverWorker::run() {
  static LowerWorkerPriority lower_workers;
#ifdef __linux__
  // Below the window's thread: a frame waits for the CPU less while the solver iterates.
  setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), 5);
#endif
  for (;;) {
    std::shared_ptr<const SolverProblem> problem;
    std::unique_ptr<SolverTargets> targets;
    std::uint64_t problem_serial = 0, targets_serial = 0;
    bool outputs_changed = false, stop_now = false;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      const bool solving = status_.phase == SolverPhase::Solving;
      wake_.wait(lock, [&] {
        return stop_ || pending_problem_ || pending_targets_ || outputs_dirty_ ||
               stop_requested_ || solving;
      });
      if (stop_) return;
      problem = std::move(pending_problem_);
      problem_serial = pending_problem_serial_;
      targets = std::move(pending_targets_);
      targets_serial = pending_targets_serial_;
      outputs_changed = outputs_dirty_;
      outputs_dirty_ = false;
      // A stop asked for before a new request arrived ends the solve that was running.
      stop_now = stop_requested_ && !pending_problem_ && !pending_targets_ &&
                 status_.phase == SolverPhase::Solving;
      stop_requested_ = false;
      limited_ = iteration_limit_;
      energy_on_ = want_energy_;
      prisms_on_ = want_prisms_;
    }
    if (problem || targets) {
      last_request_ = Clock::now();
      confirming_ = false;
      std::lock_guard<std::mutex> lock(mutex_);
      status_.stopped_by_user = false;
    }
    if (stop_now) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        status_.stopped_by_user = true;
      }
      publish_geometry(true);
      set_phase(SolverPhase::Stopped);
      continue;
    }
    if (problem) {
      if (build(*problem)) built_problem_serial_ = problem_serial;
      std::lock_guard<std::mutex> lock(mutex_);
      status_.request_serial = problem_serial;
    }
    if (targets && deformer_) {
      apply(*targets);
      std::lock_guard<std::mutex> lock(mutex_);
      status_.request_serial = targets_serial;
    } else if (targets) {
      std::lock_guard<std::mutex> lock(mutex_);
      status_.request_serial = targets_serial;  // nothing to move yet
    }
    published_.notify_all();  // the request serials moved on
    if (!deformer_) {
      if (status().phase != SolverPhase::Failed) set_phase(SolverPhase::Idle);
      continue;
    }
    if (status().phase == SolverPhase::Solving)
      step();
    else if (outputs_changed)
      publish_geometry();
  }
}

bool SolverWorker::build(const SolverProblem& problem) {
  set_phase(SolverPhase::Building);
  const auto start = Clock::now();
  try {
    auto next = std::make_unique<Deformer>(*problem.mesh, problem.inputs.params,
                                           problem.inputs.handles, problem.inputs.forces);
    // Start from the given solved state, or keep the current pose across the rebuild when it
    // is the same mesh.
    if (!problem.start_motions.empty())
      next->set_face_motions(problem.start_motions);
    else if (deformer_ && problem_ && problem_->mesh == problem.mesh)
      next->set_face_motions(deformer_->face_motions());
    deformer_ = std::move(next);
  } catch (const std::exception& e) {
    set_phase(SolverPhase::Failed, e.what());
    {
      std::lock_guard<std::mutex> lock(mutex_);
      status_.build_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    }
    // The last good deformer (if any) stays, so the view keeps its last result; it must not
    // be solved against targets of a problem it does not describe.
    return false;
  }
  const bool same_mesh = problem_ && problem_->mesh == problem.mesh;
  problem_ = std::make_shared<SolverProblem>(problem);
  first_solve_ = true;
  if (!same_mesh) full_frame_seconds_ = 0.0;  // a new mesh: measured on its first drag
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.build_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    status_.solver_ready = false;
    status_.iterations = 0;
    status_.progress = 0.0;
  }
  first_decrease_ = 0.0;
  set_phase(SolverPhase::Solving);
  return true;
}

void SolverWorker::apply(const SolverTargets& targets) {
  if (status().phase == SolverPhase::Failed) return;
  if (targets.handles.size() != deformer_->handles().size() ||
      targets.forces.size() != deformer_->forces().size())
    return;  // stale: made for a different set of handles
  for (size_t h = 0; h < targets.handles.size(); ++h)
    deformer_->set_handle_transform(int(h), targets.handles[h],
                                    h < targets.turns.size() ? targets.turns[h] : std::nullopt);
  for (size_t f = 0; f < targets.forces.size(); ++f)
    if (targets.forces[f] != deformer_->forces()[f].target_offset)
      deformer_->set_force_offset(int(f), targets.forces[f]);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.iterations = 0;
    status_.progress = 0.0;
  }
  first_decrease_ = 0.0;
  set_phase(SolverPhase::Solving);
}

void SolverWorker::step() {
  SolveOptions options;
  options.method = interactive_solve_method(problem_->spec.method, problem_->topology->n_faces);
  options.tolerance = problem_->spec.tolerance;
  const int done = status().iterations;
  const bool dragging =
      std::chrono::duration<double>(Clock::now() - last_request_).count() < kDragPauseSeconds;
  // A settling batch ends as soon as a newer request comes: after a jump its iterations can
  // be Newton-Krylov steps (HierarchicalOptions::newton_krylov_above) of 0.4-0.9 s each at
  // 240k faces, which would keep a new drag waiting for seconds. A drag's batches are short
  // already (kBatchSeconds) and keep their size.
  if (!dragging)
    options.interrupt = [this] {
      std::lock_guard<std::mutex> lock(mutex_);
      return stop_ || stop_requested_ || pending_problem_ != nullptr || pending_targets_ != nullptr;
    };
  const int batch = dragging ? chunk_ : std::max(chunk_, kSettleBatch);
  // Where a batch has room for more than one cycle, a drag's frame takes a Newton-Krylov step
  // after its cycle (HierarchicalOptions::newton_krylov_in_frames).
  options.drag_frame = dragging;
  options.max_iterations =
      limited_ ? std::max(0, std::min(batch, problem_->spec.max_iterations - done)) : batch;
  // A jump (undo, typed values, an opened scenario) is followed in sub-steps, a batch at a
  // time, so new targets are still picked up between batches.
  options.path.max_iterations = std::max(1, batch);
  // A drag on a big mesh, where one cycle outlasts a batch (240k faces: about 100 ms): the
  // coarse correction is shown as soon as it reaches the prisms, and the swept result after,
  // so the surface follows the hand twice a cycle.
  const bool slow_cycles = status().seconds_per_iteration > kBatchSeconds;
  const bool preview = dragging && options.method == SolveMethod::Hierarchical &&
                       full_frame_seconds_ > preview_above_;
  if (dragging && slow_cycles && !preview && options.method == SolveMethod::Hierarchical)
    options.on_coarse_correction = [this] { publish_geometry(); };
  if (first_solve_) {  // say what the wait is for: it can take seconds on big meshes
    {
      std::lock_guard<std::mutex> lock(mutex_);
      status_.detail = options.method == SolveMethod::Hierarchical ? "building the hierarchy"
                                                                   : "analysing the system";
      status_.phase_start = Clock::now();
    }
    if (notify_) notify_();
  }
  SolveReport report;
  try {
    report = preview ? deformer_->preview(options) : deformer_->solve(options);
    if (dragging && !preview && report.iterations > 0 && report.path_steps == 0)
      full_frame_seconds_ = report.seconds;
    if (first_solve_) {
      // A problem at rest (new handles not moved yet) returns before the solver is set up:
      // set it up now, while the user has not started dragging, so the drag's first frame
      // does not pause for it.
      if (report.iterations == 0) deformer_->prepare(options);
      first_solve_ = false;
      std::lock_guard<std::mutex> lock(mutex_);
      status_.detail.clear();
      status_.solver_ready = solver_set_up(*deformer_, options.method);
    }
  } catch (const std::exception& e) {
    set_phase(SolverPhase::Failed, e.what());
    return;
  }
  // Converged only in a settling batch, and a stop on the tolerance is confirmed by one more
  // batch: a small (backtracked) step can come before the minimum, and the warm-started path
  // of a drag must end where a solve from scratch ends (docs/editor.md).
  bool converged = report.converged && !dragging;
  if (converged && report.stop_reason == "tolerance" && !confirming_) {
    confirming_ = true;
    converged = false;
  }
  if (report.iterations > 0 && !preview) {
    const double per_iteration = report.seconds / report.iterations;
    chunk_ = std::clamp(int(kBatchSeconds / std::max(per_iteration, 1e-6)), 1, kMaxBatch);
  }
  // Convergence estimate: how far the relative decrease has fallen towards the tolerance.
  double progress = 0.0;
  if (!report.energies.empty()) {
    const double before = report.energies.size() > 1 ? report.energies[report.energies.size() - 2]
                                                     : report.initial_energy;
    const double decrease = before > 0 ? std::max((before - report.energy) / before, 1e-300) : 0;
    if (first_decrease_ == 0.0) first_decrease_ = std::max(decrease, 1e-300);
    const double tol = std::max(problem_->spec.tolerance, 1e-300);
    if (first_decrease_ > tol && decrease > 0)
      progress = std::clamp(std::log(first_decrease_ / decrease) / std::log(first_decrease_ / tol),
                            0.0, 1.0);
  }
  SolverPhase next = SolverPhase::Solving;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.energy = report.energy;
    status_.iterations = done + report.iterations;
    status_.total_iterations += report.iterations;
    if (report.iterations > 0 && !preview)
      status_.seconds_per_iteration = report.seconds / report.iterations;
    status_.previews = full_frame_seconds_ > preview_above_;
    status_.progress = std::max(status_.progress, progress);
    if (converged)
      next = SolverPhase::Settled;
    else if (limited_ && status_.iterations >= problem_->spec.max_iterations)
      next = SolverPhase::Stopped;
    if (next != SolverPhase::Solving) status_.progress = 1.0;
  }
  publish_geometry(next != SolverPhase::Solving);
  if (next != SolverPhase::Solving) set_phase(next);
}

void SolverWorker::publish_geometry(bool with_motions) {
  // A geometry no one reads any more (neither the status nor the window) is filled again:
  // its buffers keep their pages, where a fresh one at a million faces maps and zeroes about
  // 30 MB for every picture of a drag.
  std::shared_ptr<SolverGeometry> g;
  for (std::shared_ptr<SolverGeometry>& spare : spare_geometry_)
    if (spare && spare.use_count() == 1) {
      g = spare;
      break;
    }
  if (g) {
    g->face_motions.reset();
    g->face_energy.clear();
    g->prism_corners.clear();
    g->energy_scale = 1.0;
  } else {
    g = std::make_shared<SolverGeometry>();
    for (std::shared_ptr<SolverGeometry>& spare : spare_geometry_)
      if (!spare) {
        spare = g;
        break;
      }
  }
  if (with_motions)
    g->face_motions = std::make_shared<const std::vector<RigidTransform>>(deformer_->face_motions());
  deformer_->vertex_positions(g->positions);
  g->preview = deformer_->previewing();
  g->render_positions.resize(3 * g->positions.size());
  parallel_chunks(g->positions.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v)
      for (int i = 0; i < 3; ++i) g->render_positions[3 * v + i] = float(g->positions[v][i]);
  });
  compute_vertex_normals(*problem_->topology, g->positions, g->render_normals);

  if (energy_on_ || prisms_on_) {
    // The prisms in the solver's numbering (Deformer::order), drawn in the file's.
    const MeshOrder& order = deformer_->order();
    const std::vector<RigidTransform> motions = order.faces_to_solver(deformer_->face_motions());
    const PrismLayer& layer = deformer_->prisms();
    if (energy_on_) {
      const std::vector<double> e = face_joint_energy(layer, motions);
      g->face_energy.resize(e.size());
      for (size_t f = 0; f < e.size(); ++f)
        g->face_energy[size_t(order.face_of[f])] =
            float(layer.face_area[f] > 0 ? e[f] / layer.face_area[f] : 0.0);
      g->energy_scale = robust_maximum(g->face_energy);
    }
    if (prisms_on_) {
      std::vector<int> file_corner_begin(size_t(layer.n_faces()) + 1, 0);
      for (int f = 0; f < layer.n_faces(); ++f)
        file_corner_begin[size_t(order.face_of[size_t(f)]) + 1] = layer.degree(f);
      for (int f = 0; f < layer.n_faces(); ++f)
        file_corner_begin[size_t(f) + 1] += file_corner_begin[size_t(f)];
      g->prism_corners.resize(6 * layer.corner_point.size());
      for (int f = 0; f < layer.n_faces(); ++f) {
        const int n = layer.degree(f), first = file_corner_begin[size_t(order.face_of[size_t(f)])];
        for (int j = 0; j < n; ++j) {
          const int k = layer.corner_begin[f] + j;
          const size_t file_corner = size_t(first + (j + order.face_rotation[size_t(f)]) % n);
          const Vec3 bottom = motions[size_t(f)].apply(layer.corner_point[k] - layer.corner_offset[k]);
          const Vec3 top = motions[size_t(f)].apply(layer.corner_point[k] + layer.corner_offset[k]);
          for (int i = 0; i < 3; ++i) {
            g->prism_corners[6 * file_corner + size_t(i)] = float(bottom[i]);
            g->prism_corners[6 * file_corner + 3 + size_t(i)] = float(top[i]);
          }
        }
      }
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    g->serial = ++geometry_serial_;
    g->problem_serial = built_problem_serial_;
    status_.geometry = std::move(g);
  }
  published_.notify_all();
  if (notify_) notify_();
}

}  // namespace primo::editor
