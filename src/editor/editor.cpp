#include "editor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>

#include "primo/output_files.h"
#include "primo/error.h"
#include "primo/mesh_io.h"
#include "scenario_bridge.h"

namespace primo::editor {
namespace {

glm::dvec3 to_glm(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

// Seconds between solver rebuilds while a paint stroke is under way.
constexpr double kPaintSyncSeconds = 0.3;
// Seconds between hover picks (each may need a pick-buffer render).
constexpr double kHoverSeconds = 0.08;

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
  if (task_.valid()) return error("Still busy with " + task_label_ + "; try again when it is done");
  task_label_ = (recovered ? "Recovering " : "Opening ") + file_name(path);
  task_started_ = clock_;
  task_ = std::async(std::launch::async, [this, path, recovered]() -> std::function<void()> {
    std::shared_ptr<Document> doc = load_document(path);
    return [this, doc, path, recovered]() mutable {
      if (recovered) {
        // Unsaved work with no file of its own: Save asks where, and it counts as changed.
        doc->scenario_path.clear();
        doc->saved_state = initial_edit_state(doc->n_faces());
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
  if (!doc_) return error("Nothing to save: open a mesh first");
  if (task_.valid()) return error("Still busy with " + task_label_ + "; try again when it is done");
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
  task_label_ = "Saving " + file_name(path);
  task_started_ = clock_;
  task_ = std::async(std::launch::async, [this, mesh, path, caveat]() -> std::function<void()> {
    primo::save_mesh(*mesh, path);
    return [this, path, caveat] { info("Saved the deformed mesh to " + path + caveat); };
  });
}

std::string Editor::scenario_text(const std::string& path) const {
  // The pose shown, when the solver has finished with the current state: reopening the
  // scenario or `primo deform` then starts there (docs/editor.md).
  const SolverGeometry* shown = geometry_.get();
  const bool solved = !status_.busy() && shown && shown->face_motions &&
                      int(shown->face_motions->size()) == doc_->n_faces();
  const Scenario s = export_scenario(doc_->state, doc_->mesh_path, path, doc_->solver,
                                     solved ? shown->face_motions.get() : nullptr);
  return scenario_to_json(s);
}

bool Editor::save_scenario(const std::string& path) {
  if (!doc_) {
    error("Nothing to save: open a mesh first");
    return false;
  }
  try {
    write_text_atomically(path, scenario_text(path));
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

// --- Per frame --------------------------------------------------------------------------

void Editor::update(double seconds) {
  clock_ += seconds;
  idle_ = std::exchange(idle_wait_, false);
  if (!idle_) frame_ms_ = frame_ms_ == 0.0 ? 1000.0 * seconds : 0.9 * frame_ms_ + 100.0 * seconds;
  if (gesture_ != Gesture::None && !idle_) {
    ++current_gesture_.frames;
    current_gesture_.total_ms += 1000.0 * seconds;
    current_gesture_.max_ms = std::max(current_gesture_.max_ms, 1000.0 * seconds);
  }

  if (task_.valid() &&
      task_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      std::function<void()> finish = task_.get();
      finish();
    } catch (const std::exception& e) {
      error(e.what());
    }
  }
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
    if (gesture_ != Gesture::None) ++current_gesture_.mesh_updates;
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
    else
      targets.handles.push_back(g.transform());
  }
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
  sync_solver();
}

void Editor::commit(const std::string& label) {
  if (!doc_) return;
  follow_mirror();
  overlay_changed_ = true;
  sync_solver();
  doc_->commit(label);
}

// --- Input ------------------------------------------------------------------------------

void Editor::set_viewport(const ViewportRect& rect) {
  viewport_ = rect;
  camera_.set_viewport(int(std::lround(rect.width * rect.scale)),
                       int(std::lround(rect.height * rect.scale)));
}

bool Editor::cursor_in_viewport() const {
  return cursor_.x >= 0 && cursor_.y >= 0 && cursor_.x < camera_.width() &&
         cursor_.y < camera_.height();
}

void Editor::handle_event(const InputEvent& e, bool ui_mouse, bool ui_keyboard) {
  switch (e.type) {
    case InputEvent::Type::CursorMove: on_cursor(e); break;
    case InputEvent::Type::MouseButton: on_mouse_button(e, ui_mouse); break;
    case InputEvent::Type::Scroll: on_scroll(e, ui_mouse); break;
    case InputEvent::Type::Key:
      if (const int bit = modifier_bit(e.key)) {
        if (e.action == GLFW_RELEASE)
          held_mods_ &= ~bit;
        else
          held_mods_ |= bit;
      }
      if (!ui_keyboard && e.action != GLFW_RELEASE) on_key(e);
      break;
    case InputEvent::Type::Char: break;
    case InputEvent::Type::Drop:
      if (!e.paths.empty()) request_open(e.paths.front());
      break;
  }
}

void Editor::on_cursor(const InputEvent& e) {
  cursor_ = {(e.x - viewport_.x) * viewport_.scale, (e.y - viewport_.y) * viewport_.scale};
  if (gesture_ != Gesture::None)
    update_gesture();
  else
    update_hover();
}

void Editor::on_scroll(const InputEvent& e, bool ui_mouse) {
  if (ui_mouse || !cursor_in_viewport()) return;
  if ((held_mods_ & GLFW_MOD_CONTROL) &&
      (tools.tool == Tool::Paint || (tools.tool == Tool::Select && tools.shape == SelectShape::Brush))) {
    tools.brush_radius = std::clamp(tools.brush_radius * std::pow(1.15, e.y), 2.0, 400.0);
    return;
  }
  camera_.dolly(e.y, cursor_);
}

void Editor::on_mouse_button(const InputEvent& e, bool ui_mouse) {
  held_mods_ = e.mods | (held_mods_ & ~(GLFW_MOD_SHIFT | GLFW_MOD_CONTROL | GLFW_MOD_ALT));
  if (e.action == GLFW_RELEASE) {
    if (gesture_ != Gesture::None && e.button == gesture_button_) end_gesture();
    return;
  }
  if (gesture_ != Gesture::None) {
    // Right button during a tool gesture cancels it (as in Blender).
    if (e.button == GLFW_MOUSE_BUTTON_RIGHT && gesture_button_ == GLFW_MOUSE_BUTTON_LEFT)
      cancel_gesture();
    return;
  }
  if (ui_mouse || !cursor_in_viewport()) return;
  const bool shift = e.mods & GLFW_MOD_SHIFT, ctrl = e.mods & GLFW_MOD_CONTROL,
             alt = e.mods & GLFW_MOD_ALT;
  press_ = last_ = cursor_;
  gesture_button_ = e.button;
  switch (e.button) {
    case GLFW_MOUSE_BUTTON_MIDDLE:
      gesture_ = (shift || alt) ? Gesture::Pan : ctrl ? Gesture::Zoom : Gesture::Orbit;
      break;
    case GLFW_MOUSE_BUTTON_RIGHT:
      gesture_ = (alt || ctrl) ? Gesture::Zoom : shift ? Gesture::Pan : Gesture::Orbit;
      break;
    case GLFW_MOUSE_BUTTON_LEFT:
      if (alt)
        gesture_ = shift ? Gesture::Pan : Gesture::Orbit;
      else
        begin_tool_gesture(e.mods);
      break;
    default: break;
  }
  if (gesture_ == Gesture::None)
    gesture_button_ = -1;
  else
    current_gesture_ = {};
}

void Editor::begin_tool_gesture(int mods) {
  if (!doc_) return;
  const bool shift = mods & GLFW_MOD_SHIFT, ctrl = mods & GLFW_MOD_CONTROL;
  gesture_start_state_ = doc_->state;
  EditState& s = doc_->state;
  switch (tools.tool) {
    case Tool::Select:
      if (tools.shape == SelectShape::Brush) {
        select_op_ = ctrl ? SelectOp::Subtract : SelectOp::Add;
        gesture_ = Gesture::SelectBrush;
        brush_dab();
      } else {
        select_op_ = shift ? SelectOp::Add : ctrl ? SelectOp::Subtract : SelectOp::Replace;
        gesture_ = tools.shape == SelectShape::Box ? Gesture::SelectBox : Gesture::SelectLasso;
        lasso_ = {cursor_};
      }
      return;
    case Tool::Paint:
      paint_erase_ = ctrl;
      gesture_ = Gesture::Paint;
      brush_dab();
      return;
    case Tool::Move:
    case Tool::Rotate: {
      GizmoKind kind;
      glm::dvec3 center;
      if (gizmo_visible(kind, center)) {
        const GizmoPart part = gizmo_hit(kind, camera_, center, cursor_);
        if (part != GizmoPart::None) {
          gizmo_ = std::make_unique<GizmoDrag>(kind, part, camera_, center, cursor_);
          drag_group_ = s.active;
          drag_start_pose_ = s.handles[s.active].pose;
          gesture_ = Gesture::Gizmo;
          return;
        }
      }
      break;  // a click elsewhere picks the handle to put the gizmo on
    }
    case Tool::Drag: break;
  }

  const int face = face_at_cursor();
  const std::vector<int> groups = face_groups(s, doc_->n_faces());
  const int g = face >= 0 ? groups[face] : -1;
  if (g < 0) {
    if (tools.tool == Tool::Drag)
      info(s.handles.empty() ? "No handles yet: select faces (Q) and press Ctrl+G to make one"
                             : "Not on a handle: click a coloured region to drag it");
    return;
  }
  s.active = g;
  overlay_changed_ = true;
  if (tools.tool != Tool::Drag) return;
  if (!is_draggable(s.handles[g].mode)) {
    info("'" + s.handles[g].name + "' is a fixed region; change its mode to drag it");
    return;
  }
  drag_group_ = g;
  drag_start_pose_ = s.handles[g].pose;
  // The grabbed point: where the cursor meets the surface (eye depth from the pick buffer).
  drag_anchor_ = handle_pivot(g);
  if (picker_) {
    const PickImage image = picker_->read(int(cursor_.x), int(cursor_.y), 1, 1);
    const double depth = image.depth_at(int(cursor_.x), int(cursor_.y));
    if (std::isfinite(depth)) {
      const Ray ray = camera_.ray(cursor_);
      const double along = glm::dot(ray.direction, camera_.forward());
      const double t = (depth - glm::dot(ray.origin - camera_.eye(), camera_.forward())) / along;
      drag_anchor_ = ray.origin + t * ray.direction;
    }
  }
  gesture_ = Gesture::DragHandle;
}

void Editor::update_gesture() {
  const glm::dvec2 d = cursor_ - last_;
  EditState* s = doc_ ? &doc_->state : nullptr;
  switch (gesture_) {
    case Gesture::Orbit: camera_.orbit(d.x, d.y); break;
    case Gesture::Pan: camera_.pan(d.x, d.y); break;
    case Gesture::Zoom: camera_.dolly_drag(d.y); break;
    case Gesture::SelectBrush:
    case Gesture::Paint: brush_dab(); break;
    case Gesture::SelectBox: break;
    case Gesture::SelectLasso:
      if (glm::length(cursor_ - lasso_.back()) >= 3.0) lasso_.push_back(cursor_);
      break;
    case Gesture::DragHandle: {
      HandleGroup& g = s->handles[drag_group_];
      if (g.mode == HandleMode::Orientation) {
        g.pose.rotation = (drag_rotation(camera_, press_, cursor_) * drag_start_pose_.rotation).normalized();
      } else {
        const glm::dvec3 delta = view_plane_point(camera_, drag_anchor_, cursor_) - drag_anchor_;
        g.pose.translate = drag_start_pose_.translate + Vec3(delta.x, delta.y, delta.z);
      }
      live_edit();
      break;
    }
    case Gesture::Gizmo: {
      HandleGroup& g = s->handles[drag_group_];
      const bool snap = held_mods_ & GLFW_MOD_CONTROL;
      if (gizmo_->kind() == GizmoKind::Translate)
        g.pose.translate = drag_start_pose_.translate +
                           gizmo_->translation(camera_, cursor_, snap,
                                               snap_step_for(doc_->topology->bbox_diagonal));
      else
        g.pose.rotation = (gizmo_->rotation(camera_, cursor_, snap) * drag_start_pose_.rotation).normalized();
      live_edit();
      break;
    }
    case Gesture::None: break;
  }
  last_ = cursor_;
}

void Editor::end_gesture() {
  const Gesture g = gesture_;
  gesture_ = Gesture::None;
  gesture_button_ = -1;
  std::string what;
  switch (g) {
    case Gesture::Orbit: what = "orbit"; break;
    case Gesture::Pan: what = "pan"; break;
    case Gesture::Zoom: what = "zoom"; break;
    default: break;
  }
  if (doc_) {
    switch (g) {
      case Gesture::SelectBox:
      case Gesture::SelectLasso: {
        std::vector<int> faces;
        // A click when the pointer never left the press point; a lasso closed back near its
        // start is still a lasso (it used to select nothing and clear the selection).
        double reach = glm::length(cursor_ - press_);
        if (g == Gesture::SelectLasso)
          for (const glm::dvec2& p : lasso_) reach = std::max(reach, glm::length(p - press_));
        if (reach < 3.0) {
          const int f = face_at_cursor();  // a click: the face under the cursor
          if (f >= 0) faces.push_back(f);
        } else if (g == Gesture::SelectBox) {
          faces = faces_under(ScreenShape::box(press_, cursor_));
        } else {
          lasso_.push_back(cursor_);
          faces = faces_under(ScreenShape::lasso(lasso_));
        }
        FaceMask mask = *doc_->state.selection;
        apply_selection(mask, faces, select_op_);
        mirror_selection(*doc_->state.selection, mask);
        doc_->state.selection = std::make_shared<const FaceMask>(std::move(mask));
        lasso_.clear();
        what = g == Gesture::SelectBox ? "box select" : "lasso select";
        commit(g == Gesture::SelectBox ? "Box select" : "Lasso select");
        break;
      }
      case Gesture::SelectBrush:
        what = "brush select";
        commit("Brush select");
        break;
      case Gesture::Paint:
        what = "paint";
        commit(tools.paint_layer == PaintLayer::Height ? "Paint stiffness" : "Paint width");
        break;
      case Gesture::DragHandle:
      case Gesture::Gizmo: {
        const std::string name = doc_->state.handles[drag_group_].name;
        const char* verb = g == Gesture::DragHandle                ? "Drag"
                           : gizmo_->kind() == GizmoKind::Translate ? "Move"
                                                                    : "Rotate";
        commit(std::string(verb) + " '" + name + "'");
        what = std::string(g == Gesture::DragHandle ? "drag" : "gizmo") + " '" + name + "'";
        break;
      }
      default: break;
    }
  }
  gizmo_.reset();
  drag_group_ = -1;
  if (what.empty()) return;
  current_gesture_.what = what;
  gesture_stats_ = current_gesture_;
  if (gesture_stats_.frames > 0)
    std::printf("[primo edit] %s: %d frames, %.1f ms mean, %.1f ms max per frame; solver %.1f ms "
                "per iteration; the mesh changed %d times (%.1f a second)\n",
                what.c_str(), gesture_stats_.frames, gesture_stats_.total_ms / gesture_stats_.frames,
                gesture_stats_.max_ms, 1000.0 * status_.seconds_per_iteration,
                gesture_stats_.mesh_updates, gesture_stats_.updates_per_second());
}

void Editor::cancel_gesture() {
  const Gesture g = gesture_;
  gesture_ = Gesture::None;
  gesture_button_ = -1;
  gizmo_.reset();
  drag_group_ = -1;
  lasso_.clear();
  if (!doc_) return;
  if (g == Gesture::SelectBrush || g == Gesture::Paint || g == Gesture::DragHandle ||
      g == Gesture::Gizmo) {
    doc_->state = gesture_start_state_;
    overlay_changed_ = true;
    sync_solver();
  }
}

void Editor::brush_dab() {
  const double r = tools.brush_radius * viewport_.scale;
  const std::vector<int> faces = faces_under(ScreenShape::circle(cursor_, r));
  EditState& s = doc_->state;
  if (gesture_ == Gesture::SelectBrush) {
    FaceMask mask = *s.selection;
    apply_selection(mask, faces, select_op_);
    mirror_selection(*s.selection, mask);
    if (mask != *s.selection) s.selection = std::make_shared<const FaceMask>(std::move(mask));
    overlay_changed_ = true;
    return;
  }
  const double value = paint_erase_ ? 1.0
                       : tools.paint_layer == PaintLayer::Height ? tools.paint_height
                                                                 : tools.paint_width;
  FactorArray& layer = layer_factors(s, tools.paint_layer);
  // Each face's weight: the strength, faded by its centroid's distance from the cursor.
  std::vector<double> weights(faces.size(), tools.paint_strength);
  if (tools.paint_falloff != Falloff::Constant) {
    const std::vector<Vec3>& points = positions();
    for (size_t i = 0; i < faces.size(); ++i) {
      const glm::dvec3 p = camera_.project(to_glm(face_centroid(*doc_->topology, points, faces[i])));
      weights[i] *= falloff_weight(tools.paint_falloff, glm::length(glm::dvec2(p) - cursor_) / r);
    }
  }
  FactorArray next =
      mirror_paint(layer, blend_factors(layer, doc_->n_faces(), faces, weights, value));
  const bool changes = next ? !layer || *next != *layer : layer != nullptr;
  if (!changes) return;
  layer = std::move(next);
  overlay_changed_ = true;
  live_edit();
}

std::vector<int> Editor::faces_under(const ScreenShape& shape) {
  int x0, y0, x1, y1;
  shape.bounds(x0, y0, x1, y1);
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, camera_.width());
  y1 = std::min(y1, camera_.height());
  PickImage image;
  if (picker_ && x1 > x0 && y1 > y0) image = picker_->read(x0, y0, x1 - x0, y1 - y0);
  const std::vector<Vec3> centroids = face_centroids(*doc_->topology, positions());
  std::vector<ProjectedPoint> projected(centroids.size());
  const glm::dmat4 m = camera_.projection() * camera_.view();
  const glm::dvec3 eye = camera_.eye(), forward = camera_.forward();
  for (size_t f = 0; f < centroids.size(); ++f) {
    const glm::dvec3 c = to_glm(centroids[f]);
    const glm::dvec4 clip = m * glm::dvec4(c, 1.0);
    projected[f].depth = glm::dot(c - eye, forward);
    if (clip.w <= 0) continue;
    projected[f].x = (clip.x / clip.w * 0.5 + 0.5) * camera_.width();
    projected[f].y = (0.5 - clip.y / clip.w * 0.5) * camera_.height();
  }
  return faces_in_shape(shape, image, projected, tools.xray,
                        0.01 * doc_->topology->bbox_diagonal);
}

int Editor::face_at_cursor() {
  if (!doc_ || !cursor_in_viewport()) return -1;
  if (picker_) return picker_->read(int(cursor_.x), int(cursor_.y), 1, 1).face_at(int(cursor_.x), int(cursor_.y));
  const std::vector<int> near = faces_under(ScreenShape::circle(cursor_, 4.0));
  return near.empty() ? -1 : near.front();
}

void Editor::update_hover() {
  if (!doc_) return;
  GizmoKind kind;
  glm::dvec3 center;
  const GizmoPart part = gizmo_visible(kind, center) ? gizmo_hit(kind, camera_, center, cursor_)
                                                     : GizmoPart::None;
  gizmo_hover_ = part;
  if (tools.tool == Tool::Select || tools.tool == Tool::Paint) {
    if (hovered_handle_ != -1) overlay_changed_ = true;
    hovered_handle_ = -1;
    return;
  }
  if (clock_ - last_hover_pick_ < kHoverSeconds || (picker_ && !picker_->cheap_to_read())) return;
  last_hover_pick_ = clock_;
  const int face = part == GizmoPart::None ? face_at_cursor() : -1;
  int g = -1;
  if (face >= 0)
    for (size_t i = 0; i < doc_->state.handles.size() && g < 0; ++i) {
      const auto& faces = *doc_->state.handles[i].faces;
      if (std::binary_search(faces.begin(), faces.end(), face)) g = int(i);
    }
  if (g != hovered_handle_) overlay_changed_ = true;
  hovered_handle_ = g;
}

// --- Keyboard ---------------------------------------------------------------------------

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
  FaceMask mirrored = mask;
  mirror_selection(*doc_->state.selection, mirrored);
  doc_->state.selection = std::make_shared<const FaceMask>(std::move(mirrored));
  commit(label);
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
  FaceMask m = *doc_->state.selection;
  primo::editor::invert_selection(m);
  set_selection(m, "Invert selection");
}

void Editor::grow_selection() {
  if (!doc_) return;
  FaceMask m = *doc_->state.selection;
  primo::editor::grow_selection(m, *doc_->topology);
  set_selection(m, "Grow selection");
}

void Editor::select_linked(bool by_angle) {
  if (!doc_) return;
  FaceMask m = *doc_->state.selection;
  if (count_selected(m) == 0) return info("Select a face first: Select Linked grows from it");
  primo::editor::select_linked(m, *doc_->topology, by_angle ? tools.linked_angle_deg : 180.0);
  set_selection(m, by_angle ? "Select linked by angle" : "Select linked");
}

void Editor::shrink_selection() {
  if (!doc_) return;
  FaceMask m = *doc_->state.selection;
  primo::editor::shrink_selection(m, *doc_->topology);
  set_selection(m, "Shrink selection");
}

void Editor::make_handle(HandleMode mode) {
  if (!doc_) return;
  std::vector<int> faces = selected_faces(*doc_->state.selection);
  if (faces.empty())
    return error("Select faces first: press Q and brush over the surface, then make the handle");
  if (int(faces.size()) == doc_->n_faces() && mode != HandleMode::Spring)
    info("Every face is in this handle: the whole mesh will move rigidly");
  if (make_mirrored_handles(faces, mode)) return;
  EditState& s = doc_->state;
  const int g = add_handle(s, *doc_->topology, positions(), std::move(faces), mode);
  FaceMask none = *s.selection;
  primo::editor::clear_selection(none);
  s.selection = std::make_shared<const FaceMask>(std::move(none));
  commit("New " + std::string(mode_label(mode)) + " '" + s.handles[g].name + "'");
  if (tools.tool == Tool::Select && is_draggable(mode)) set_tool(Tool::Drag);
  info("Made '" + s.handles[g].name + "' (" + mode_label(mode) + ") from " +
       std::to_string(s.handles[g].faces->size()) + " faces");
}

void Editor::delete_handle(int index) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return;
  const std::string name = doc_->state.handles[index].name;
  remove_handle(doc_->state, index);
  hovered_handle_ = -1;
  commit("Delete '" + name + "'");
}

void Editor::reset_handle(int index) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return;
  primo::editor::reset_handle(doc_->state, index);
  primo::editor::reset_handle(doc_->state, doc_->state.handles[size_t(index)].mirror_twin);
  commit("Reset '" + doc_->state.handles[index].name + "'");
}

void Editor::reset_all_handles() {
  if (!doc_) return;
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
  std::vector<int> faces = selected_faces(*doc_->state.selection);
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

bool Editor::brush_visible() const {
  return doc_ && (tools.tool == Tool::Paint ||
                  (tools.tool == Tool::Select && tools.shape == SelectShape::Brush));
}

glm::dvec3 Editor::handle_pivot(int index) const {
  const HandleGroup& g = doc_->state.handles[index];
  if (g.mode != HandleMode::Orientation) return to_glm(g.target_center());
  // Orientation-only groups translate freely: measure where they are.
  return to_glm(weighted_centroid(*doc_->topology, positions(), *g.faces));
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
  messages_.push_back({text, true, clock_, ++message_serial_});
  if (messages_.size() > 200) messages_.erase(messages_.begin());
  error_popup_ = text;
  ++error_count_;
  std::fprintf(stderr, "[primo edit] error: %s\n", text.c_str());
}

std::string Editor::take_error_popup() { return std::exchange(error_popup_, std::string()); }

}  // namespace primo::editor
