#include "editor.h"

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>

#include "primo/io/output_files.h"
#include "primo/util/error.h"
#include "user_files/autosave.h"
#include "document/pivot.h"
#include "primo/io/mesh_io.h"
#include "document/scenario_bridge.h"

namespace primo::editor {
namespace {

glm::dvec3 to_glm(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

// Seconds between solver rebuilds while a paint stroke is under way.
constexpr double kPaintSyncSeconds = 0.3;

}  // namespace

const char* tool_label(Tool tool) {
  switch (tool) {
    case Tool::Select: return "Select";
    case Tool::Drag: return "Drag";
    case Tool::Move: return "Move";
    case Tool::Rotate: return "Rotate";
    case Tool::Paint: return "Paint";
  }
  return "?";
}

Editor::Editor(std::function<void()> wake_ui)
    : wake_ui_(std::move(wake_ui)), worker_(std::make_unique<SolverWorker>(wake_ui_)) {
  // The editor settles until converged (Stop ends it early); solver.max_iterations is for
  // batch commands (docs/editor.md).
  worker_->set_iteration_limit(false);
  preferences_ = load_preferences();
  apply_preferences();
  if (!preferences_.problems.empty()) {
    std::string text = "Some preferences could not be used:";
    for (const std::string& problem : preferences_.problems) text += "\n" + problem;
    error(text);
  }
}

void Editor::apply_preferences() {
  const Preferences& p = preferences_;
  display.smooth = p.smooth;
  display.wireframe = p.wireframe;
  display.prisms = p.prisms;
  display.heat_map = p.heat_map;
  display.paint_overlay = p.paint_overlay;
  display.grid = p.grid;
  tools.brush_radius = p.brush_radius;
  tools.paint_strength = p.paint_strength;
  tools.paint_falloff = p.paint_falloff;
  autosave_every_ = 60.0 * p.autosave_minutes;
  settle_limit_ = p.settle_seconds;
}

Editor::~Editor() {
  if (task_.valid()) task_.wait();
}

// --- Files ------------------------------------------------------------------------------

void Editor::open(const std::string& path) { open_file(path, false); }

void Editor::open_file(const std::string& path, bool recovered) {
  if (task_.valid()) {
    // The newest request wins: it opens when the task under way is done, and an open under
    // way is then dropped unseen. Opening files in quick succession is no error.
    queued_open_ = QueuedOpen{path, recovered};
    info("Opening " + file_name(path) + " next (after " + task_label_ + ")");
    return;
  }
  task_is_open_ = true;
  task_label_ = (recovered ? "Recovering " : "Opening ") + file_name(path);
  task_started_ = clock_;
  const int above = stand_in_above_;  // read here: the load runs on another thread
  task_ = std::async(std::launch::async, [this, above, path, recovered]() -> std::function<void()> {
    std::shared_ptr<Document> doc = load_document(path, above);
    return [this, doc, path, recovered]() mutable {
      if (recovered) {
        // Unsaved work with no file of its own: Save asks where, and it counts as changed.
        doc->scenario_path.clear();
        doc->saved_state = initial_edit_state(doc->n_faces());
        doc->mesh_path = recovered_mesh_path(doc->mesh_path);  // not the autosave's link
      }
      // A mesh without a scenario settles to the user's tolerance.
      if (!recovered && doc->scenario_path.empty()) {
        doc->solver.tolerance = preferences_.tolerance;
        doc->solver.max_iterations = preferences_.max_iterations;
      }
      apply_document(std::make_unique<Document>(std::move(*doc)));
      if (!recovered) recent_.add(path);
      last_autosave_ = clock_;
    };
  });
}

void Editor::adopt(std::unique_ptr<Document> document) { apply_document(std::move(document)); }

void Editor::apply_document(std::unique_ptr<Document> doc) {
  cancel_gesture();
  doc_ = std::move(doc);
  mirror_maps_ = {};
  geometry_.reset();
  sent_any_ = false;
  hovered_handle_ = -1;
  geometry_changed_ = overlay_changed_ = true;
  Vec3 c;
  double r;
  bounding_sphere(doc_->topology->rest_points, c, r);
  camera_.set_scene_radius(r);
  follow_orientation(false);  // the new model seen from the same side of it as the last
  camera_.frame(to_glm(c), r, true);
  tools.tool = doc_->state.handles.empty() ? Tool::Select : Tool::Drag;
  sync_solver();
  info("Opened " + (doc_->scenario_path.empty() ? doc_->mesh_path : doc_->scenario_path) + ": " +
       std::to_string(doc_->topology->n_vertices) + " vertices, " +
       std::to_string(doc_->n_faces()) + " faces, " + std::to_string(doc_->state.handles.size()) +
       " handles" + (doc_->load_note.empty() ? "" : ". " + doc_->load_note));
}

void Editor::save_mesh(const std::string& path) {
  if (!doc_) return error_in_status("Nothing to save: open a mesh first");
  if (task_.valid()) return error_in_status("Still busy with " + task_label_ + "; try again when it is done");
  try {
    check_mesh_output_path(path);
  } catch (const std::exception& e) {
    return error(e.what());
  }
  auto mesh = std::make_shared<Mesh>(*doc_->mesh);
  const std::vector<Vec3>& points = positions();
  for (auto v : mesh->vertices()) mesh->set_point(v, points[v.idx()]);
  // The caveat goes into the message that stays, not one the "Saved" line replaces at once.
  const std::string caveat =
      status_.busy() ? " (not converged yet: the shape shown when you saved)"
      : status_.phase == SolverPhase::Stopped ? " (the solve was stopped before converging)"
                                              : "";
  task_is_open_ = false;
  task_label_ = "Saving " + file_name(path);
  task_started_ = clock_;
  task_ = std::async(std::launch::async, [this, mesh, attributes = doc_->attributes, path,
                                           caveat]() -> std::function<void()> {
    primo::save_mesh(*mesh, *attributes, path);
    // What the format cannot hold (a skin in an OBJ) is said with the "Saved" line.
    const std::string lost = save_note(*attributes, path);
    return [this, path, caveat, lost] {
      info("Saved the deformed mesh to " + path + caveat + (lost.empty() ? "" : ". " + lost));
    };
  });
}

std::string Editor::scenario_text(const std::string& path, const std::string& mesh) const {
  // The pose shown, when the solver has finished with the current state: reopening the
  // scenario or `primo deform` then starts there (docs/editor.md).
  const SolverGeometry* shown = geometry_.get();
  const bool solved = !status_.busy() && shown && shown->face_motions &&
                      int(shown->face_motions->size()) == doc_->n_faces();
  const Scenario s = export_scenario(doc_->state, mesh, path, doc_->solver,
                                     solved ? shown->face_motions.get() : nullptr);
  return scenario_to_json(s);
}

bool Editor::save_scenario(const std::string& path) {
  if (!doc_) {
    error_in_status("Nothing to save: open a mesh first");
    return false;
  }
  try {
    write_text_atomically(path, scenario_text(path, doc_->mesh_path));
  } catch (const std::exception& e) {
    error(e.what());
    return false;
  }
  doc_->scenario_path = path;
  doc_->saved_state = doc_->state;
  forget_autosave();
  recent_.add(path);
  info("Saved the scenario to " + path);
  return true;
}

double Editor::file_task_seconds() const { return task_.valid() ? clock_ - task_started_ : 0.0; }

bool Editor::cancel_open() {
  if (!opening()) return false;
  cancelled_opens_.push_back(std::move(task_));
  queued_open_.reset();
  std::string what = task_label_;  // "Opening big.obj"
  if (!what.empty()) what[0] = char(std::tolower(static_cast<unsigned char>(what[0])));
  task_label_.clear();
  const std::string open_now =
      doc_ ? file_name(doc_->scenario_path.empty() ? doc_->mesh_path : doc_->scenario_path) : "";
  info("Stopped " + what + (open_now.empty() ? "" : "; " + open_now + " stays open"));
  return true;
}

// --- Per frame --------------------------------------------------------------------------

void Editor::update(double seconds) {
  clock_ += seconds;
  idle_ = std::exchange(idle_wait_, false);
  if (!idle_) frame_ms_ = frame_ms_ == 0.0 ? 1000.0 * seconds : 0.9 * frame_ms_ + 100.0 * seconds;
  if (shown_frame_ms_ == 0.0 || clock_ - frame_ms_shown_at_ >= 0.5) {
    shown_frame_ms_ = frame_ms_;
    frame_ms_shown_at_ = clock_;
  }
  if (gesture_ != Gesture::None && !idle_) {
    ++current_gesture_.frames;
    current_gesture_.total_ms += 1000.0 * seconds;
    current_gesture_.max_ms = std::max(current_gesture_.max_ms, 1000.0 * seconds);
    current_gesture_.times.add(1000.0 * seconds);
  }

  if (task_.valid() &&
      task_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    // An open that a newer one replaced is neither shown nor reported.
    const bool superseded = task_is_open_ && queued_open_;
    try {
      std::function<void()> finish = task_.get();
      if (!superseded) finish();
    } catch (const std::exception& e) {
      if (!superseded) error(e.what());
    }
    if (queued_open_) {
      const QueuedOpen next = *std::exchange(queued_open_, std::nullopt);
      open_file(next.path, next.recovered);
    }
  }
  // Cancelled opens that have finished reading: their documents and errors go unseen.
  cancelled_opens_.erase(
      std::remove_if(cancelled_opens_.begin(), cancelled_opens_.end(),
                     [](std::future<std::function<void()>>& task) {
                       if (task.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
                         return false;
                       try {
                         task.get();
                       } catch (const std::exception&) {
                       }
                       return true;
                     }),
      cancelled_opens_.end());
  if (!doc_) return;
  sessions.update(*this, seconds);
  if (autosave_every_ > 0 && clock_ - last_autosave_ >= autosave_every_) {
    last_autosave_ = clock_;
    if (has_unsaved_changes()) autosave_now();
  }

  if (gesture_ == Gesture::Paint && clock_ - last_paint_sync_ >= kPaintSyncSeconds) {
    sync_solver();
    last_paint_sync_ = clock_;
  }
  worker_->set_outputs(display.heat_map, display.prisms);
  const SolverPhase before = status_.phase;
  status_ = worker_->status();
  if (status_.phase == SolverPhase::Failed && before != SolverPhase::Failed)
    error("The solver could not use this setup: " + status_.error);
  // Preferences > Settle at most: a settle that outlasts it stops as the Stop button would.
  if (settle_limit_ > 0 && gesture_ == Gesture::None && status_.phase == SolverPhase::Solving &&
      clock_ - last_submit_clock_ >= settle_limit_ && settle_stopped_at_ != last_submit_clock_) {
    settle_stopped_at_ = last_submit_clock_;
    worker_->stop();
    info("Stopped settling after " + format_duration(settle_limit_) +
         " (Edit > Preferences > Settle at most); Continue solves on");
  }
  // Geometry of a problem submitted before the document was opened belongs to the previous
  // document (the worker may still be publishing it): never show it.
  if (status_.geometry && status_.geometry != geometry_ &&
      status_.geometry->problem_serial >= document_serial_ &&
      status_.geometry->positions.size() == size_t(doc_->topology->n_vertices)) {
    geometry_ = status_.geometry;
    geometry_changed_ = true;
    if (gesture_ != Gesture::None) {
      ++current_gesture_.mesh_updates;
      if (geometry_->preview) ++current_gesture_.preview_updates;
    }
    if (display.heat_map) overlay_changed_ = true;
  }
  if (display.heat_map != last_display_.heat_map ||
      display.paint_overlay != last_display_.paint_overlay || tools.tool != last_tools_.tool ||
      tools.paint_layer != last_tools_.paint_layer)
    overlay_changed_ = true;
  last_display_ = display;
  last_tools_ = tools;
  follow_orientation(true);  // after an undo, redo or playback that changed it
  camera_.update(seconds);
}

void Editor::count_drawn_frame() {
  if (gesture_ != Gesture::None) ++current_gesture_.drawn_frames;
}

bool Editor::settled() const {
  if (task_.valid() || !doc_ || gesture_ != Gesture::None) return false;
  if (!worker_->idle_for_latest()) return false;
  return worker_->status().geometry == geometry_;
}

bool Editor::take_geometry_changed() { return std::exchange(geometry_changed_, false); }
bool Editor::take_overlay_changed() { return std::exchange(overlay_changed_, false); }

const std::vector<Vec3>& Editor::positions() const {
  static const std::vector<Vec3> none;
  if (geometry_) return geometry_->positions;
  return doc_ ? doc_->topology->rest_points : none;
}

// --- Solver -----------------------------------------------------------------------------

namespace {

SolverTargets targets_of(const EditState& s) {
  SolverTargets targets;
  for (const HandleGroup& g : s.handles) {
    if (g.mode == HandleMode::Spring)
      targets.forces.push_back(g.pose.translate);
    else {
      targets.handles.push_back(g.transform());
      targets.turns.push_back(g.pose.known_turn());
    }
  }
  for (const Force& f : falloff_forces(s)) targets.forces.push_back(f.target_offset);
  return targets;
}

}  // namespace

void Editor::sync_solver() {
  if (!doc_) return;
  const EditState& s = doc_->state;
  if (!sent_any_ || !same_structure(s, sent_)) {
    auto problem = std::make_shared<SolverProblem>();
    problem->mesh = doc_->mesh;
    problem->topology = doc_->topology;
    problem->inputs = deformation_inputs(s);
    problem->spec = doc_->solver;
    problem->start_motions = std::move(doc_->start_motions);  // once: later rebuilds keep the pose
    doc_->start_motions.clear();
    last_submit_clock_ = clock_;
    const std::uint64_t serial = worker_->submit_problem(std::move(problem));
    if (!sent_any_) document_serial_ = serial;  // the document's first problem
  } else {
    bool moved = false;
    for (size_t g = 0; g < s.handles.size(); ++g)
      moved = moved || !(s.handles[g].pose == sent_.handles[g].pose);
    if (moved) {
      worker_->submit_targets(targets_of(s));
      last_submit_clock_ = clock_;
    }
  }
  sent_ = s;
  sent_any_ = true;
}

void Editor::stop_solving() {
  if (doc_ && status_.busy()) worker_->stop();
}

bool Editor::continue_solving() {
  if (!doc_ || status_.phase != SolverPhase::Stopped || !sent_any_) return false;
  // The same targets again: a new request, whose iterations count from zero, warm-started
  // from the state where the last one stopped.
  worker_->submit_targets(targets_of(sent_));
  last_submit_clock_ = clock_;
  return true;
}

void Editor::live_edit() {
  follow_mirror();
  // Paint strokes rebuild the solver's prisms: at most every kPaintSyncSeconds (and at the
  // end of the stroke), not at every dab.
  if (gesture_ == Gesture::Paint) return;
  // More than poses changed (a session's playback replaces handles and painted factors at
  // every frame): the handle colours and painted overlay are redrawn now, not at the end.
  if (doc_ && sent_any_ && (!same_structure(doc_->state, sent_) || doc_->state.active != sent_.active))
    overlay_changed_ = true;
  sync_solver();
}

void Editor::commit(const std::string& label) {
  if (!doc_) return;
  follow_mirror();
  overlay_changed_ = true;
  sync_solver();
  doc_->commit(label);
}

// --- Commands ---------------------------------------------------------------------------

void Editor::undo() {
  if (!doc_) return;
  cancel_gesture();
  if (!doc_->history.can_undo()) return info("Nothing to undo");
  const std::string label = doc_->history.undo_label();
  doc_->state = doc_->history.undo();
  overlay_changed_ = true;
  sync_solver();
  info("Undo " + label);
}

void Editor::undo_group() {
  if (!doc_) return;
  const UndoStack& h = doc_->history;
  if (!h.can_undo()) return info("Nothing to undo");
  const UndoStack::Group g = h.group_of(h.position());
  const std::size_t steps = h.position() - g.first + 1;  // redone ones of the group only
  const std::string label = h.label(h.position());
  go_to_history(g.first - 1);
  info("Undo " + (steps > 1 ? std::to_string(steps) + " x " : std::string()) + label);
}

void Editor::go_to_history(std::size_t index) {
  if (!doc_ || index >= doc_->history.size() || index == doc_->history.position()) return;
  cancel_gesture();
  doc_->state = doc_->history.go_to(index);
  overlay_changed_ = true;
  sync_solver();
  info("Back to: " + (index == 0 ? std::string("as opened") : doc_->history.label(index)));
}

void Editor::redo() {
  if (!doc_) return;
  cancel_gesture();
  if (!doc_->history.can_redo()) return info("Nothing to redo");
  doc_->state = doc_->history.redo();
  overlay_changed_ = true;
  sync_solver();
  info("Redo " + doc_->history.undo_label());
}

void Editor::set_selection(const FaceMask& mask, const std::string& label) {
  if (!doc_) return;
  end_gesture_before_edit();
  FaceMask mirrored = mask;
  finish_selection(*doc_->state.selection, mirrored);
  if (selection_mode() == SelectionMode::Vertices)
    return set_vertex_selection(vertices_of_faces(*doc_->topology, mirrored), label);
  doc_->state.selection = std::make_shared<const FaceMask>(std::move(mirrored));
  commit(label);
}

void Editor::finish_selection(const FaceMask& before, FaceMask& after) {
  mirror_selection(before, after);
  deselect_hidden(after, doc_->state.hidden);
}

void Editor::select_all() {
  if (!doc_) return;
  FaceMask m = *doc_->state.selection;
  primo::editor::select_all(m);
  set_selection(m, "Select all");
}

void Editor::clear_selection() {
  if (!doc_) return;
  FaceMask m = *doc_->state.selection;
  primo::editor::clear_selection(m);
  set_selection(m, "Clear selection");
}

void Editor::invert_selection() {
  if (!doc_) return;
  if (selection_mode() == SelectionMode::Vertices) {
    VertexMask v = *doc_->state.vertex_selection;
    primo::editor::invert_selection(v);
    return set_vertex_selection(std::move(v), "Invert selection");
  }
  FaceMask m = *doc_->state.selection;
  primo::editor::invert_selection(m);
  set_selection(m, "Invert selection");
}

void Editor::grow_selection() {
  if (!doc_) return;
  // In vertex mode the faces touching the selection: their corners are one ring more.
  FaceMask m = selection_as_faces();
  if (selection_mode() == SelectionMode::Faces) primo::editor::grow_selection(m, *doc_->topology);
  set_selection(m, "Grow selection");
}

void Editor::select_linked(bool by_angle) {
  if (!doc_) return;
  FaceMask m = selection_as_faces();
  if (count_selected(m) == 0) return info("Select a face first: Select Linked grows from it");
  primo::editor::select_linked(m, *doc_->topology, by_angle ? tools.linked_angle_deg : 180.0);
  set_selection(m, by_angle ? "Select linked by angle" : "Select linked");
}

void Editor::shrink_selection() {
  if (!doc_) return;
  // In vertex mode the faces within the selection: their corners leave out its rim.
  FaceMask m = *doc_->state.selection;
  if (selection_mode() == SelectionMode::Faces) primo::editor::shrink_selection(m, *doc_->topology);
  set_selection(m, "Shrink selection");
}

void Editor::make_handle(HandleMode mode) {
  if (!doc_) return;
  end_gesture_before_edit();
  std::vector<int> faces = selected_faces(selection_as_faces());
  if (faces.empty())
    return error_in_status("Select faces first: press Q and brush over the surface, then make the handle");
  if (int(faces.size()) == doc_->n_faces() && mode != HandleMode::Spring)
    info("Every face is in this handle: the whole mesh will move rigidly");
  if (make_mirrored_handles(faces, mode)) return;
  EditState& s = doc_->state;
  const int g = add_handle(s, *doc_->topology, positions(), std::move(faces), mode);
  deselect_all(s);
  commit("New " + std::string(mode_label(mode)) + " '" + s.handles[g].name + "'");
  const std::string tool_note = drag_tool_after_making(mode);
  info("Made '" + s.handles[g].name + "' (" + mode_label(mode) + ") from " +
       std::to_string(s.handles[g].faces->size()) + " faces" + tool_note);
}

std::string Editor::drag_tool_after_making(HandleMode mode) {
  if (tools.tool != Tool::Select || !is_draggable(mode)) return "";
  set_tool(Tool::Drag);
  // Said, or a click meant to select would drag the new handle instead.
  return "; the Drag tool is on to pose it (" + key_map().label(Action::ToolSelect) +
         " selects again)";
}

void Editor::delete_handle(int index) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return;
  end_gesture_before_edit();
  const std::string name = doc_->state.handles[index].name;
  remove_handle(doc_->state, index);
  hovered_handle_ = -1;
  commit("Delete '" + name + "'");
}

void Editor::reset_handle(int index) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return;
  end_gesture_before_edit();
  primo::editor::reset_handle(doc_->state, index);
  primo::editor::reset_handle(doc_->state, doc_->state.handles[size_t(index)].mirror_twin);
  commit("Reset '" + doc_->state.handles[index].name + "'");
}

void Editor::reset_all_handles() {
  if (!doc_) return;
  end_gesture_before_edit();
  for (size_t i = 0; i < doc_->state.handles.size(); ++i)
    primo::editor::reset_handle(doc_->state, int(i));
  commit("Reset all handles");
}

void Editor::set_active_handle(int index) {
  if (!doc_ || index < -1 || index >= int(doc_->state.handles.size())) return;
  doc_->state.active = index;
  overlay_changed_ = true;
}

void Editor::set_handle_mode(int index, HandleMode mode) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return;
  if (doc_->state.handles[index].mode == mode) return;
  end_gesture_before_edit();
  primo::editor::set_handle_mode(doc_->state, index, mode);
  primo::editor::set_handle_mode(doc_->state, doc_->state.handles[size_t(index)].mirror_twin, mode);
  commit("'" + doc_->state.handles[index].name + "' to " + mode_label(mode));
  stale_up_to_ = message_serial_;
}

void Editor::set_tool(Tool tool) {
  if (gesture_ != Gesture::None) cancel_gesture();
  tools.tool = tool;
  overlay_changed_ = true;
  stale_up_to_ = message_serial_;
}

void Editor::frame_all() {
  if (!doc_) return;
  Vec3 c;
  double r;
  bounding_sphere(positions(), c, r);
  camera_.frame(to_glm(c), r);
}

void Editor::frame_selection() {
  if (!doc_) return;
  std::vector<int> faces = selected_faces(selection_as_faces());
  const EditState& s = doc_->state;
  if (faces.empty() && s.active >= 0 && s.active < int(s.handles.size())) faces = *s.handles[s.active].faces;
  if (faces.empty()) return frame_all();
  std::vector<Vec3> points;
  const MeshTopology& t = *doc_->topology;
  for (int f : faces)
    for (int k = t.face_begin[f]; k < t.face_begin[f + 1]; ++k) points.push_back(positions()[t.face_vertices[k]]);
  Vec3 c;
  double r;
  bounding_sphere(points, c, r);
  camera_.frame(to_glm(c), std::max(r, 0.02 * t.bbox_diagonal));
}

// --- Overlay queries --------------------------------------------------------------------

bool Editor::gizmo_visible(GizmoKind& kind, glm::dvec3& center) const {
  if (!doc_ || (tools.tool != Tool::Move && tools.tool != Tool::Rotate)) return false;
  const EditState& s = doc_->state;
  if (s.active < 0 || s.active >= int(s.handles.size())) return false;
  const HandleGroup& g = s.handles[s.active];
  if (!is_draggable(g.mode)) return false;
  kind = tools.tool == Tool::Move ? GizmoKind::Translate : GizmoKind::Rotate;
  if (!uses_rotation(g.mode)) kind = GizmoKind::Translate;
  if (!uses_translation(g.mode)) kind = GizmoKind::Rotate;
  center = handle_pivot(s.active);
  return true;
}

glm::dmat3 Editor::gizmo_axes() const {
  if (!doc_) return glm::dmat3(1.0);
  const EditState& s = doc_->state;
  if (s.active < 0 || s.active >= int(s.handles.size())) return glm::dmat3(1.0);
  return primo::editor::gizmo_axes(tools.gizmo_orientation, s.handles[size_t(s.active)],
                                   *doc_->topology, camera_);
}

bool Editor::brush_visible() const {
  return doc_ && (tools.tool == Tool::Paint ||
                  (tools.tool == Tool::Select && tools.shape == SelectShape::Brush));
}

glm::dvec3 Editor::handle_pivot(int index) const {
  const HandleGroup& g = doc_->state.handles[index];
  return to_glm(handle_motion(g, *doc_->topology, positions()).apply(g.center));
}

bool Editor::handle_window_position(const std::string& name, double& x, double& y) const {
  if (!doc_) return false;
  for (size_t i = 0; i < doc_->state.handles.size(); ++i) {
    const HandleGroup& g = doc_->state.handles[i];
    if (g.name != name) continue;
    // A point on the handle near its pivot: the centroid of the front-facing face closest to
    // the pivot on screen, so that pressing there grabs the handle.
    const glm::dvec3 pivot = camera_.project(handle_pivot(int(i)));
    glm::dvec3 best = pivot;
    double best_d = std::numeric_limits<double>::infinity();
    const MeshTopology& t = *doc_->topology;
    const std::vector<Vec3>& p = positions();
    const glm::dvec3 eye = camera_.eye();
    for (int f : *g.faces) {
      const Vec3 c = face_centroid(t, p, f);
      if (glm::dot(to_glm(face_vector_area(t, p, f, c)), to_glm(c) - eye) >= 0.0) continue;  // facing away
      const glm::dvec3 w = camera_.project(to_glm(c));
      const double d = glm::length(glm::dvec2(w.x - pivot.x, w.y - pivot.y));
      if (d < best_d) best_d = d, best = w;
    }
    x = viewport_.x + best.x / viewport_.scale;
    y = viewport_.y + best.y / viewport_.scale;
    return true;
  }
  return false;
}

// --- Messages ---------------------------------------------------------------------------

void Editor::info(const std::string& text) {
  messages_.push_back({text, false, clock_, ++message_serial_});
  if (messages_.size() > 200) messages_.erase(messages_.begin());
  std::printf("[primo edit] %s\n", text.c_str());
}

const Editor::Message* Editor::current_message() const {
  if (messages_.empty()) return nullptr;
  const Message& m = messages_.back();
  const double fresh = m.error ? 30.0 : 10.0;
  if (clock_ - m.time > fresh || m.serial <= stale_up_to_) return nullptr;
  return &m;
}

void Editor::error(const std::string& text) {
  error_in_status(text);
  error_popup_ = text;
}

void Editor::error_in_status(const std::string& text) {
  messages_.push_back({text, true, clock_, ++message_serial_});
  if (messages_.size() > 200) messages_.erase(messages_.begin());
  ++error_count_;
  std::fprintf(stderr, "[primo edit] error: %s\n", text.c_str());
}

std::string Editor::take_error_popup() { return std::exchange(error_popup_, std::string()); }

}  // namespace primo::editor
