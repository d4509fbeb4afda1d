#include "primo/solve/deformer.h"
#include "primo/util/parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "primo/util/error.h"
#include "primo/solve/local_solver.h"
#include "primo/mesh/mesh_order.h"
#include "primo/model/turn.h"

namespace primo {
namespace {

BodyKind body_kind(Fix fix) {
  switch (fix) {
    case Fix::All: return BodyKind::Fixed;
    case Fix::Position: return BodyKind::PinnedPosition;
    case Fix::Orientation: return BodyKind::FixedRotation;
  }
  return BodyKind::Fixed;
}

std::string handle_label(const Handle& h, size_t index) {
  return h.name.empty() ? "handles[" + std::to_string(index) + "]" : "handle '" + h.name + "'";
}

// A transform that is not finite, or whose rotation is not one, would poison every state it
// touches: refused where it enters.
void check_transform(const Handle& h, size_t index, const RigidTransform& t) {
  if (!t.rotation.allFinite() || !t.translation.allFinite())
    throw Error(handle_label(h, index) + ": the transform is not finite");
  if (!((t.rotation.transpose() * t.rotation - Mat3::Identity()).norm() < 1e-6) ||
      !(t.rotation.determinant() > 0))
    throw Error(handle_label(h, index) + ": the transform's rotation is not a rotation");
}

// `turn` makes `rotation`, the one `h` is being given.
void check_turn(const Handle& h, size_t index, const Vec3& turn, const Mat3& rotation) {
  if (!turn_makes(turn, rotation))
    throw Error(handle_label(h, index) + ": the turn does not make the transform's rotation");
}

// Bit for bit: a resumed path recomputes its sub-step from the same inputs.
bool same_transforms(const std::vector<RigidTransform>& a, const std::vector<RigidTransform>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].rotation != b[i].rotation || a[i].translation != b[i].translation) return false;
  return true;
}

// The transform a fraction s of the way from `from` (turned `from_turn`) to `to` (turned
// `to_turn`), for a body whose rest centre is `center`: the centre moves on the straight line,
// the body turns about it by the same fraction of the turn between them, whole turns
// included, as a handle dragged and turned with the gizmo does. Between turns about one axis
// this is the turn itself; from rest it is the shorter great circle for a turn of at most
// half a turn.
RigidTransform interpolate(const RigidTransform& from, const Vec3& from_turn,
                           const RigidTransform& to, const Vec3& to_turn, const Vec3& center,
                           double s) {
  RigidTransform t;
  t.rotation = rotation_of_turn((1.0 - s) * from_turn + s * to_turn);
  const Vec3 c = (1.0 - s) * from.apply(center) + s * to.apply(center);
  t.translation = c - t.rotation * center;
  return t;
}

// Sub-steps a target move needs (Deformer::target_move): its longest piece, rounded up, at
// least 1. Not finite only for non-finite targets, which the solve will reject on its own.
// At most kMaxPathSteps: a move of 100 bounding-box diagonals already takes 1,000, and a huge
// one (1e6 diagonals) would otherwise take a million sub-steps, each a factorization.
int path_steps(const std::vector<double>& move) {
  double steps = 1.0;
  for (size_t i = 0; i + 2 < move.size(); i += 3)
    steps = std::max(steps, Vec3(move[i], move[i + 1], move[i + 2]).norm());
  return std::isfinite(steps) ? int(std::min(std::ceil(steps - 1e-9), double(kMaxPathSteps))) : 1;
}

// The prism layer of `mesh` in the solver's numbering `order`; in the file's own numbering,
// with `order` set to it, when OpenMesh cannot rebuild the mesh renumbered (the layer is then
// as good, only slower to sweep).
PrismLayer solver_layer(const Mesh& mesh, const PrismParameters& params, MeshOrder& order) {
  Mesh renumbered;
  if (!build_reordered_mesh(mesh, order, renumbered)) {
    order = identity_order(mesh);
    return build_prism_layer(mesh, params);
  }
  PrismParameters solver_params = params;
  for (std::vector<double>* factors : {&solver_params.face_height_factor, &solver_params.face_width_factor})
    if (factors->size() == mesh.n_faces()) *factors = order.faces_to_solver(*factors);
  return build_prism_layer(renumbered, solver_params, &order);
}

}  // namespace

Deformer::Deformer(const Mesh& mesh, const PrismParameters& params, std::vector<Handle> handles,
                   std::vector<Force> forces)
    : order_(locality_order(mesh)),
      layer_(solver_layer(mesh, params, order_)),
      handles_(std::move(handles)),
      forces_(std::move(forces)) {
  rest_points_.reserve(mesh.n_vertices());
  for (int v : order_.vertex_of) rest_points_.push_back(mesh.point(mesh.vertex_handle(v)));
  const std::vector<int> solver_face = order_.solver_faces();

  const int n_faces = layer_.n_faces();
  std::vector<int> face_body(n_faces, -1);
  std::vector<BodyKind> kinds;
  for (size_t h = 0; h < handles_.size(); ++h) {
    if (handles_[h].faces.empty()) throw Error(handle_label(handles_[h], h) + " has no faces");
    for (int f : handles_[h].faces) {
      if (f < 0 || f >= n_faces)
        throw Error(handle_label(handles_[h], h) + ": face " + std::to_string(f) +
                    " is out of range (the mesh has " + std::to_string(n_faces) + " faces)");
      const int owner = face_body[size_t(solver_face[size_t(f)])];
      if (owner >= 0)
        throw Error("face " + std::to_string(f) + " is in both " +
                    handle_label(handles_[size_t(owner)], size_t(owner)) + " and " +
                    handle_label(handles_[h], h));
      face_body[size_t(solver_face[size_t(f)])] = int(h);
    }
    check_transform(handles_[h], h, handles_[h].transform);
    // Absent, the principal turn (at most half a turn).
    if (!handles_[h].turn)
      handles_[h].turn = nearest_turn(handles_[h].transform.rotation);
    else
      check_turn(handles_[h], h, *handles_[h].turn, handles_[h].transform.rotation);
    kinds.push_back(body_kind(handles_[h].fix));
  }
  for (int f = 0; f < n_faces; ++f) {
    if (face_body[f] >= 0) continue;
    face_body[f] = int(kinds.size());
    kinds.push_back(BodyKind::Free);
  }
  for (size_t i = 0; i < forces_.size(); ++i) {
    if (!forces_[i].target_offset.allFinite() || !std::isfinite(forces_[i].stiffness) ||
        forces_[i].stiffness < 0)
      throw Error("forces[" + std::to_string(i) + "]: the target offset or stiffness is not finite "
                  "and non-negative");
  }
  for (size_t i = 0; i < forces_.size(); ++i) {
    force_faces_.emplace_back();
    for (int f : forces_[i].faces) {
      if (f < 0 || f >= n_faces)
        throw Error("forces[" + std::to_string(i) + "]: face " + std::to_string(f) +
                    " is out of range");
      force_faces_.back().push_back(solver_face[size_t(f)]);
    }
    // In the solver's order, so that the area sums come out the same for any file order.
    std::sort(force_faces_.back().begin(), force_faces_.back().end());
  }

  system_ = build_rigid_system(layer_, face_body, kinds, {});
  body_center_.reserve(system_.bodies.size());
  for (const RigidSystem::Body& body : system_.bodies) body_center_.push_back(body.rest_center);
  corner_body_.resize(layer_.corner_vertex.size());
  for (int f = 0; f < n_faces; ++f)
    for (int k = layer_.corner_begin[f]; k < layer_.corner_begin[f + 1]; ++k)
      corner_body_[size_t(k)] = system_.face_body[size_t(f)];
  rebuild_springs();
  reset();
}

Deformer::~Deformer() = default;

void Deformer::problem_changed() {
  settled_ = false;
  known_energy_.reset();
  // Accelerated cycles combine iterates of one fixed problem.
  if (hierarchical_) hierarchical_->restart_acceleration();
}
// The global solver refers to system_, whose address changes with a move: drop it, it is
// rebuilt (with its symbolic analysis) on the next global iteration.
Deformer::Deformer(Deformer&& other) noexcept
    : order_(std::move(other.order_)),
      rest_points_(std::move(other.rest_points_)),
      layer_(std::move(other.layer_)),
      handles_(std::move(other.handles_)),
      forces_(std::move(other.forces_)),
      force_faces_(std::move(other.force_faces_)),
      system_(std::move(other.system_)),
      body_center_(std::move(other.body_center_)),
      corner_body_(std::move(other.corner_body_)),
      state_(std::move(other.state_)),
      settled_(other.settled_),
      solved_to_minimum_(other.solved_to_minimum_),
      settled_method_(other.settled_method_),
      settled_tolerance_(other.settled_tolerance_),
      exact_newton_(other.exact_newton_),
      known_energy_(other.known_energy_),
      solved_transforms_(std::move(other.solved_transforms_)),
      solved_turns_(std::move(other.solved_turns_)),
      solved_offsets_(std::move(other.solved_offsets_)) {
  // A preview under way is carried into the state (its solver reads nothing of the system).
  if (other.previewing()) other.hierarchical_->end_preview(state_);
  other.global_.reset();
  other.hierarchical_.reset();
}

Deformer& Deformer::operator=(Deformer&& other) noexcept {
  if (other.previewing()) other.hierarchical_->end_preview(other.state_);
  order_ = std::move(other.order_);
  rest_points_ = std::move(other.rest_points_);
  layer_ = std::move(other.layer_);
  handles_ = std::move(other.handles_);
  forces_ = std::move(other.forces_);
  force_faces_ = std::move(other.force_faces_);
  system_ = std::move(other.system_);
  body_center_ = std::move(other.body_center_);
  corner_body_ = std::move(other.corner_body_);
  state_ = std::move(other.state_);
  settled_ = other.settled_;
  settled_method_ = other.settled_method_;
  settled_tolerance_ = other.settled_tolerance_;
  exact_newton_ = other.exact_newton_;
  known_energy_ = other.known_energy_;
  solved_transforms_ = std::move(other.solved_transforms_);
  solved_turns_ = std::move(other.solved_turns_);
  solved_offsets_ = std::move(other.solved_offsets_);
  path_ = {};           // its predictor's record refers to the other system's address
  solved_to_minimum_ = other.solved_to_minimum_;
  coarse_factor_of_state_ = false;  // the hierarchy is rebuilt
  predictor_.forget();  // the last frame was another deformer's
  global_.reset();
  hierarchical_.reset();
  other.global_.reset();
  other.hierarchical_.reset();
  return *this;
}

void Deformer::rebuild_springs() {
  std::vector<Vec3> offsets;
  for (const Force& force : forces_) offsets.push_back(force.target_offset);
  place_springs(offsets);
}

void Deformer::place_springs(const std::vector<Vec3>& offsets) {
  std::vector<FaceSpring> springs;
  for (size_t i = 0; i < forces_.size(); ++i) {
    const Force& force = forces_[i];
    double total_area = 0.0;
    for (int f : force_faces_[i]) total_area += layer_.face_area[f];
    if (!(total_area > 0.0)) continue;
    for (int f : force_faces_[i])
      springs.push_back({f, layer_.face_centroid[f] + offsets[i],
                         force.stiffness * layer_.face_area[f] / total_area});
  }
  set_springs(system_, layer_, springs);
}

BodyState Deformer::handle_state(int handle) const {
  const RigidTransform& t = handles_[handle].transform;
  return {t.rotation, t.apply(system_.bodies[handle].rest_center)};
}

void Deformer::reset() {
  cancel_preview();
  problem_changed();
  predictor_.forget();
  path_ = {};
  solved_to_minimum_ = true;  // free prisms at rest are the minimum for handles at rest
  coarse_factor_of_state_ = false;
  exact_newton_ = false;
  // Free prisms at rest are the solution for handles at rest: a path starts there.
  solved_transforms_.assign(handles_.size(), RigidTransform::identity());
  solved_turns_.assign(handles_.size(), Vec3::Zero());
  solved_offsets_.assign(forces_.size(), Vec3::Zero());
  rebuild_springs();
  state_.resize(system_.n_bodies());
  for (int b = 0; b < system_.n_bodies(); ++b)
    state_[b] = b < int(handles_.size()) ? handle_state(b)
                                         : BodyState{Mat3::Identity(), system_.bodies[b].rest_center};
}

void Deformer::set_handle_transform(int handle, const RigidTransform& transform,
                                    const std::optional<Vec3>& turn) {
  if (handle < 0 || handle >= int(handles_.size())) throw Error("no such handle");
  Handle& h = handles_[size_t(handle)];
  check_transform(h, size_t(handle), transform);
  if (turn) check_turn(h, size_t(handle), *turn, transform.rotation);
  h.turn = turn ? *turn : nearest_turn(transform.rotation, *h.turn);
  h.transform = transform;
  place_handle(handle, transform);
}

void Deformer::place_handle(int handle, const RigidTransform& transform) {
  std::optional<double> known = known_energy_;
  if (known) *known -= body_energy(handle);
  problem_changed();
  const BodyState target{transform.rotation, transform.apply(system_.bodies[handle].rest_center)};
  BodyState& s = state_[handle];
  switch (handles_[handle].fix) {
    case Fix::All: s = target; break;
    case Fix::Position: s.position = target.position; break;
    case Fix::Orientation: s.rotation = target.rotation; break;
  }
  if (known) known_energy_ = *known + body_energy(handle);
}

double Deformer::body_energy(int body) const {
  double e = 0.0;
  for (int k = system_.coupling_begin[body]; k < system_.coupling_begin[body + 1]; ++k) {
    const RigidSystem::Coupling& c = system_.couplings[system_.body_couplings[k].first];
    e += system_.coupling_energy(c, state_[c.body[0]], state_[c.body[1]]);
  }
  for (int k = system_.spring_begin[body]; k < system_.spring_begin[body + 1]; ++k) {
    const RigidSystem::Spring& sp = system_.springs[system_.body_springs[k]];
    e += RigidSystem::spring_energy(sp, state_[sp.body]);
  }
  return e;
}

void Deformer::set_force_offset(int force, const Vec3& target_offset) {
  if (force < 0 || force >= int(forces_.size())) throw Error("no such force");
  if (!target_offset.allFinite())
    throw Error("forces[" + std::to_string(force) + "]: the target offset is not finite");
  forces_[force].target_offset = target_offset;
  problem_changed();
  rebuild_springs();
}

std::vector<double> Deformer::target_move(const PathOptions& limits) const {
  const double move = limits.max_move * layer_.bounding_box_diagonal;
  std::vector<double> d;
  d.reserve(6 * handles_.size() + 3 * forces_.size());
  auto add = [&d](const Vec3& piece) { d.insert(d.end(), {piece.x(), piece.y(), piece.z()}); };
  for (size_t h = 0; h < handles_.size(); ++h) {
    const RigidTransform& from = solved_transforms_[h];
    const RigidTransform& to = handles_[h].transform;
    const Vec3& center = system_.bodies[h].rest_center;
    const Fix fix = handles_[h].fix;
    if (fix != Fix::Orientation) add((to.apply(center) - from.apply(center)) / move);
    if (fix != Fix::Position)
      add((*handles_[h].turn - solved_turns_[h]) * (180.0 / M_PI / limits.max_turn_deg));
  }
  for (size_t f = 0; f < forces_.size(); ++f)
    add((forces_[f].target_offset - solved_offsets_[f]) / move);
  return d;
}



void Deformer::predict(DragPredictor& predictor, const std::vector<double>& move,
                       double multiplier) {
  const double fraction = predictor.fraction(move, multiplier);
  const double now = fraction > 0.0 ? energy() : 0.0;
  if (fraction > 0.0 && std::isfinite(now)) {
    predictor.predict(system_, state_, fraction, predicted_);
    const double predicted = system_.energy(predicted_);
    // Where the prediction does not lower the energy (the drag turned, the minimum jumped),
    // the frame starts where the last one ended, as without it.
    if (predicted < now) {
      state_.swap(predicted_);
      known_energy_ = predicted;
      predictor.take(move, predicted_);  // the state before the prediction, without a copy
      return;
    }
  }
  predictor.remember(move, state_);
}

void Deformer::solved_for_current_targets() {
  for (size_t h = 0; h < handles_.size(); ++h) {
    solved_transforms_[h] = handles_[h].transform;
    solved_turns_[h] = *handles_[h].turn;
  }
  for (size_t f = 0; f < forces_.size(); ++f) solved_offsets_[f] = forces_[f].target_offset;
}

void Deformer::end_preview() {
  if (!previewing()) return;
  hierarchical_->end_preview(state_);
  known_energy_.reset();
  settled_ = false;
  solved_to_minimum_ = false;
  coarse_factor_of_state_ = false;
  predictor_.forget();  // the state jumped from the fine one to the preview's
}

void Deformer::cancel_preview() {
  if (hierarchical_) hierarchical_->cancel_preview();
}

SolveReport Deformer::preview(const SolveOptions& options) {
  if (options.method != SolveMethod::Hierarchical) return solve(options);
  make_solver(options);
  if (hierarchical_->levels() < 2) return solve(options);
  const auto start = std::chrono::steady_clock::now();
  SolveReport report;
  if (!previewing()) {
    report.initial_energy = energy();
    if (!std::isfinite(report.initial_energy)) {
      report.energy = report.initial_energy;
      report.stop_reason = "not finite";
      return report;
    }
    hierarchical_->begin_preview(state_, -1, report.initial_energy);
  } else {
    report.initial_energy = preview_energy_;
  }
  predictor_.forget();
  path_ = {};
  settled_ = false;
  solved_to_minimum_ = false;
  coarse_factor_of_state_ = false;
  double e = 0.0;
  for (int k = 0; k < std::max(options.max_iterations, 1); ++k)
    e = hierarchical_->preview_frame(state_);
  if (!std::isfinite(e)) {
    // Settings too large for the coarse levels: back to the state the preview began from.
    hierarchical_->cancel_preview();
    known_energy_.reset();
    report.energy = energy();
    report.stop_reason = "not finite";
    return report;
  }
  preview_energy_ = e;
  report.iterations = std::max(options.max_iterations, 1);
  report.energy = e;
  report.energies.push_back(e);
  report.stop_reason = "preview";
  solved_for_current_targets();  // the picture is the one for the targets set now
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

SolveReport Deformer::solve(const SolveOptions& options) {
  end_preview();
  // A drag's frame starts from the predicted state (SolveOptions::drag_prediction). A jump
  // followed in sub-steps is a continuation of its own: a prediction on top would put the
  // state ahead of the sub-steps' targets, and its change would be no frame of a drag.
  const std::vector<double> move = target_move(options.path);
  if (options.drag_prediction > 0.0 && !(options.path.enabled && path_steps(move) > 1))
    predict(predictor_, move, options.drag_prediction);
  else
    predictor_.forget();
  return solve_now(options);
}

SolveReport Deformer::solve_now(const SolveOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  SolveReport report;
  const double diagonal = layer_.bounding_box_diagonal;
  const double energy_floor = 1e-14 * diagonal * diagonal;
  report.initial_energy = energy();  // from the last solve when known: a drag frame skips a pass
  report.energy = report.initial_energy;
  if (!std::isfinite(report.initial_energy)) {
    // Targets, forces or settings so large that the energy overflows: nothing to solve.
    report.stop_reason = "not finite";
    return report;
  }
  if (settled_ && settled_method_ == options.method && options.tolerance >= settled_tolerance_) {
    report.converged = true;
    report.stop_reason = "already converged";
    return report;
  }
  auto finish = [&](SolveReport& r) {
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  };
  if (options.method == SolveMethod::Global && options.hierarchical_start) {
    SolveOptions first = options;
    first.method = SolveMethod::Hierarchical;
    first.hierarchical_start = false;
    first.max_iterations = options.max_hierarchical_cycles;
    const SolveReport cycles = solve_now(first);
    report.path_steps = cycles.path_steps;
    report.path_iterations = cycles.path_iterations;
    report.hierarchical_cycles = cycles.iterations;
    if (cycles.stop_reason == "path budget" || cycles.stop_reason == "not finite" ||
        cycles.stop_reason == "interrupted") {
      report.energy = cycles.energy;
      report.stop_reason = cycles.stop_reason;
      return finish(report);
    }
    // Near a minimum: an exact-Hessian step converges quadratically where Gauss-Newton's
    // converges linearly (docs/engine.md); it falls back to Gauss-Newton if refused.
    exact_newton_ = options.exact_hessian_below > 0;
  }
  if (!follow_path(options, report)) {
    report.energy = energy();
    report.stop_reason = "path budget";
    return finish(report);
  }
  double e = energy();
  if (report.stop_reason == "not finite") {
    report.energy = e;
    return finish(report);
  }
  report.stop_reason = "max_iterations";

  for (int it = 0; it < options.max_iterations; ++it) {
    if (e <= energy_floor) {
      report.converged = true;
      report.stop_reason = "energy floor";
      break;
    }
    if (options.interrupt && options.interrupt()) {
      report.stop_reason = "interrupted";
      break;
    }
    const double before = e;
    const std::optional<double> after = guarded_iterate(options, before, report);
    if (report.stop_reason == "not finite") break;
    if (options.method == SolveMethod::Hierarchical && hierarchical_->interrupted()) {
      report.stop_reason = "interrupted";
      break;
    }
    if (!after) {
      report.converged = true;
      report.stop_reason = "no further decrease";
      break;
    }
    ++report.iterations;
    report.energies.push_back(*after);
    e = *after;
    if (before - *after < options.tolerance * before) {
      report.converged = true;
      report.stop_reason = "tolerance";
      break;
    }
  }
  if (!report.converged && e <= energy_floor && report.stop_reason != "not finite") {
    report.converged = true;
    report.stop_reason = "energy floor";
  }
  report.energy = e;
  known_energy_ = e;
  if (report.converged && hierarchical_) hierarchical_->release_newton_krylov();
  settled_ = report.converged;
  solved_to_minimum_ = report.converged;
  settled_method_ = options.method;
  settled_tolerance_ = options.tolerance;
  solved_for_current_targets();
  return finish(report);
}

std::optional<double> Deformer::guarded_iterate(const SolveOptions& options, double e,
                                                SolveReport& report) {
  solved_to_minimum_ = false;
  coarse_factor_of_state_ = false;
  parallel_copy(state_, last_good_state_);  // reuses its capacity after the first
  const std::optional<double> after = iterate(options, e, report);
  if (!after || std::isfinite(*after)) return after;
  // An iteration went to NaN or infinity (a value too large for the solver somewhere): the
  // state before it is kept and the solve stops saying so.
  state_ = last_good_state_;
  if (hierarchical_) hierarchical_->restart_acceleration();
  exact_newton_ = false;
  report.stop_reason = "not finite";
  return e;
}

std::optional<double> Deformer::iterate(const SolveOptions& options, double e,
                                        SolveReport& report) {
  make_solver(options);
  // Accelerated cycles take their input to be the state their last cycle left.
  if (options.method != SolveMethod::Hierarchical && hierarchical_)
    hierarchical_->restart_acceleration();
  if (options.method == SolveMethod::Global) {
    const GlobalStep step = global_->iterate(state_, exact_newton_);
    // No step along the Newton direction lowers the energy: a minimum to machine precision.
    if (!step.decreased) return std::nullopt;
    if (step.exact_hessian) ++report.exact_newton_steps;
    exact_newton_ = options.exact_hessian_below > 0 && step.step_scale == 1.0 &&
                    (e - step.energy_after) < options.exact_hessian_below * e;
    return step.energy_after;
  }
  if (options.method == SolveMethod::Hierarchical) {
    hierarchical_->set_coarse_correction_callback(options.on_coarse_correction);
    hierarchical_->set_interrupt(options.interrupt);
    hierarchical_->set_iterations_ahead(options.max_iterations);
    hierarchical_->set_drag_frame(options.drag_frame);
    const double energy = hierarchical_->cycle(state_, e);
    hierarchical_->set_coarse_correction_callback({});
    hierarchical_->set_interrupt({});
    return energy;
  }
  local_sweep(system_, state_);
  return system_.energy(state_);
}

int Deformer::path_steps_needed(const PathOptions& options) const {
  return options.enabled ? path_steps(target_move(options)) : 1;
}

bool Deformer::path_pending(const PathOptions& options) const {
  return path_steps_needed(options) > 1;
}

bool Deformer::follow_path(const SolveOptions& options, SolveReport& report) {
  // A path the last call's budget cut short goes on where it stopped, with its sub-step's
  // iterations and its drag predictor's record, while its targets stay the same. Restarted
  // instead (the editor's first batches after an undo are single iterations), a sub-step
  // was counted as reached after one iteration and the final targets were entered without
  // the path's prediction: a 240k-face redo took 56 iterations instead of 15.
  const int steps = path_steps_needed(options.path);
  if (steps <= 1) {  // every drag frame: no target vectors built
    path_ = {};
    return true;
  }
  std::vector<RigidTransform> end(handles_.size());
  std::vector<Vec3> end_turns(handles_.size());
  for (size_t h = 0; h < handles_.size(); ++h) {
    end[h] = handles_[h].transform;
    end_turns[h] = *handles_[h].turn;
  }
  std::vector<Vec3> end_offsets(forces_.size());
  for (size_t f = 0; f < forces_.size(); ++f) end_offsets[f] = forces_[f].target_offset;
  if (!(same_transforms(path_.end, end) && path_.end_turns == end_turns &&
        path_.end_offsets == end_offsets))
    path_ = {};
  // A new path from a minimum (an undo, a redo, a typed value; not a drag's frame): the
  // hierarchy's coarse factor is of the state the last targets were solved at, and the
  // first cycles after the jump would reuse it (they count as a drag's, whose factors are
  // refreshed in the background): a fresh one at the path's start. Without it, a redo of
  // the koala's reach (100k faces) took 192 iterations and 18.6 s instead of 20 and 1.8 s.
  // (A path under way has iterated, so its state is no minimum: no test for a new path.)
  if (solved_to_minimum_ && !coarse_factor_of_state_ && hierarchical_ &&
      options.method == SolveMethod::Hierarchical) {
    hierarchical_->prepare(state_);
    coarse_factor_of_state_ = true;
  }
  path_.end = std::move(end);
  path_.end_turns = std::move(end_turns);
  path_.end_offsets = std::move(end_offsets);
  const std::vector<RigidTransform> from = solved_transforms_;
  const std::vector<Vec3> from_turns = solved_turns_;
  const std::vector<Vec3> from_offsets = solved_offsets_;
  int budget = options.path.max_iterations;
  // A sub-step is no drag's frame (SolveOptions::drag_frame): it ends on a small decrease.
  SolveOptions sub_step = options;
  sub_step.drag_frame = false;
  // The sub-steps are the frames of a drag at a steady pace: each starts from the state
  // carried on by the last one's change (DragPredictor), from the second on.
  const std::vector<double> step_move{1.0};  // equal sub-steps
  for (int k = 1; k < steps; ++k) {
    if (budget <= 0) return false;  // resumed from solved_transforms_ by the next call
    const double s = double(k) / steps;
    std::vector<RigidTransform> step(handles_.size());
    std::vector<Vec3> step_turns(handles_.size());
    for (size_t h = 0; h < handles_.size(); ++h) {
      step[h] = interpolate(from[h], from_turns[h], handles_[h].transform, *handles_[h].turn,
                            system_.bodies[h].rest_center, s);
      step_turns[h] = (1.0 - s) * from_turns[h] + s * *handles_[h].turn;
      place_handle(int(h), step[h]);
    }
    std::vector<Vec3> step_offsets(forces_.size());
    if (!forces_.empty()) {
      for (size_t f = 0; f < forces_.size(); ++f)
        step_offsets[f] = (1.0 - s) * from_offsets[f] + s * forces_[f].target_offset;
      place_springs(step_offsets);
      problem_changed();
    }
    // The sub-step a call's budget ran out in is the first of the next call's, bit for bit.
    const bool resumed = path_.step_iterations > 0 && same_transforms(path_.step, step) &&
                         path_.step_turns == step_turns &&
                         path_.step_offsets == step_offsets;
    if (!resumed) {
      path_.step = step;
      path_.step_turns = step_turns;
      path_.step_offsets = step_offsets;
      path_.step_iterations = 0;
      if (options.drag_prediction > 0.0)
        predict(path_.predictor, step_move, options.drag_prediction);
    }
    double e = energy();
    while (path_.step_iterations < options.path.max_step_iterations) {
      if (budget-- <= 0) return false;  // a sub-step counts even when it finds no decrease
      const std::optional<double> after = guarded_iterate(sub_step, e, report);
      if (report.stop_reason == "not finite") {
        known_energy_.reset();
        path_ = {};
        return true;  // the solve at the final targets stops at its first check
      }
      ++path_.step_iterations;
      if (!after) break;
      ++report.path_iterations;
      const bool small = e - *after < options.path.step_tolerance * e;
      e = *after;
      known_energy_ = e;
      if (small) break;
    }
    path_.step_iterations = 0;
    solved_transforms_ = std::move(step);
    solved_turns_ = std::move(step_turns);
    solved_offsets_ = std::move(step_offsets);
    ++report.path_steps;
  }
  // The final targets: the regular solve takes it from here.
  for (size_t h = 0; h < handles_.size(); ++h) place_handle(int(h), handles_[h].transform);
  if (!forces_.empty()) {
    rebuild_springs();
    problem_changed();
  }
  if (options.drag_prediction > 0.0) predict(path_.predictor, step_move, options.drag_prediction);
  path_ = {};
  return true;
}

bool Deformer::make_solver(const SolveOptions& options) {
  if (options.method == SolveMethod::Global && !global_) {
    global_ = std::make_unique<GlobalSolver>(system_);
    return true;
  }
  if (options.method == SolveMethod::Hierarchical && !hierarchical_) {
    hierarchical_ = std::make_unique<HierarchicalSolver>(system_, options.hierarchical);
    return true;
  }
  return false;
}

void Deformer::prepare(const SolveOptions& options) {
  end_preview();
  // A global iteration always makes a fresh factor; the hierarchy's coarse one can be made
  // now, from the state the next cycle starts from.
  if (make_solver(options) && options.method == SolveMethod::Hierarchical) {
    hierarchical_->prepare(state_);
    coarse_factor_of_state_ = true;
  }
}

std::vector<Vec3> Deformer::vertex_positions() const {
  std::vector<Vec3> points;
  vertex_positions(points);
  return points;
}

void Deformer::vertex_positions(std::vector<Vec3>& points) const {
  if (previewing()) {
    const HierarchicalSolver& h = *hierarchical_;
    gather_vertices(points, [&](int b, const Vec3& x) {
      return Vec3(h.previewed_point(state_, b, x) - x - body_center_[size_t(b)]);
    });
  } else {
    // (R - I) x + (position - centre) rather than R x + position - rest: a body at rest adds
    // exactly nothing, so a mesh posed at rest (or its unmoved parts) comes out with the
    // file's very coordinates.
    gather_vertices(points, [&](int b, const Vec3& x) {
      const BodyState& s = state_[size_t(b)];
      return Vec3((s.rotation * x - x) + (s.position - body_center_[size_t(b)]));
    });
  }
}

template <class Displacement>
void Deformer::gather_vertices(std::vector<Vec3>& points, const Displacement& displacement) const {
  // Each vertex the mean of its prisms' copies of it where their motions put them (the
  // scenario format's rule), added in corner order, gathered per vertex in parallel: no buffer
  // of corners (at a million faces 69 MB, which the allocator maps afresh and the kernel
  // faults in on every call).
  points.resize(rest_points_.size());
  parallel_chunks(points.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      const int first = layer_.vertex_corner_begin[v], last = layer_.vertex_corner_begin[v + 1];
      Vec3& out = points[size_t(order_.vertex_of[v])];
      if (first == last) {
        out = rest_points_[v];
        continue;
      }
      // The mean of the prisms' copies of the vertex at rest (the vertex itself unless a width
      // scaled them) plus the mean of their displacements.
      Vec3 sum = Vec3::Zero(), copies = Vec3::Zero();
      bool copies_are_the_vertex = true;
      for (int i = first; i < last; ++i) {
        const int k = layer_.vertex_corners[size_t(i)];
        const int b = corner_body_[size_t(k)];
        const Vec3& copy = layer_.corner_point[size_t(k)];
        copies += copy;
        copies_are_the_vertex = copies_are_the_vertex && copy == rest_points_[v];
        sum += displacement(b, Vec3(copy - body_center_[size_t(b)]));
      }
      const double n = double(last - first);
      out = (copies_are_the_vertex ? rest_points_[v] : Vec3(copies / n)) + sum / n;
    }
  });
}

Mesh Deformer::deformed_mesh(const Mesh& mesh) const {
  Mesh out = mesh;
  const std::vector<Vec3> points = vertex_positions();
  for (auto v : out.vertices()) out.set_point(v, points[v.idx()]);
  return out;
}

std::vector<RigidTransform> Deformer::face_motions() const {
  std::vector<RigidTransform> motions(layer_.n_faces());
  for (int f = 0; f < layer_.n_faces(); ++f) {
    const int b = system_.face_body[f];
    const BodyState s = previewing() ? hierarchical_->previewed(state_, b) : state_[size_t(b)];
    RigidTransform& m = motions[size_t(order_.face_of[size_t(f)])];
    m.rotation = s.rotation;
    m.translation = s.position - s.rotation * body_center_[size_t(b)];
  }
  return motions;
}

void Deformer::set_face_motions(const std::vector<RigidTransform>& motions) {
  if (int(motions.size()) != layer_.n_faces()) throw Error("one motion per face is needed");
  for (const RigidTransform& m : motions)
    if (!m.rotation.allFinite() || !m.translation.allFinite())
      throw Error("a face motion is not finite");
  cancel_preview();
  problem_changed();
  predictor_.forget();
  path_ = {};
  solved_to_minimum_ = false;
  coarse_factor_of_state_ = false;
  exact_newton_ = false;
  for (int b = 0; b < system_.n_bodies(); ++b) {
    const RigidSystem::Body& body = system_.bodies[b];
    const RigidTransform& m = motions[size_t(order_.face_of[size_t(body.faces.front())])];
    const BodyState given{m.rotation, m.apply(body.rest_center)};
    if (b >= int(handles_.size())) {
      state_[b] = given;
      continue;
    }
    // A handle keeps what it prescribes and takes the rest.
    switch (handles_[b].fix) {
      case Fix::All: break;
      case Fix::Position: state_[b].rotation = given.rotation; break;
      case Fix::Orientation: state_[b].position = given.position; break;
    }
  }
  // The state given is the one for the targets set now: no path to follow from rest.
  solved_for_current_targets();
}

}  // namespace primo
