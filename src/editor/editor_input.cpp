// Mouse input: hovering, the viewport's camera gestures, selecting by brush, box and lasso,
// dragging handles and the gizmo, painting, and the end of each gesture as one undo step
// (keys are in editor_keys.cpp).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "editor.h"

namespace primo::editor {
namespace {

glm::dvec3 to_glm(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Seconds between hover picks (each may need a pick-buffer render).
constexpr double kHoverSeconds = 0.08;

}  // namespace

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
  // Alt + wheel: the active handle's falloff radius, as Blender's proportional size.
  if ((held_mods_ & GLFW_MOD_ALT) && doc_ && doc_->state.active >= 0 &&
      doc_->state.active < int(doc_->state.handles.size())) {
    const double r = doc_->state.handles[size_t(doc_->state.active)].falloff_radius;
    const double from = r > 0 ? r : tools.falloff_radius > 0 ? tools.falloff_radius
                                                              : 0.1 * doc_->topology->bbox_diagonal;
    set_falloff_radius(doc_->state.active, r > 0 ? from * std::pow(1.15, e.y) : from);
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
      // Ctrl+Shift+right-click places the active handle's pivot on the surface (Blender puts
      // its cursor with Shift+right-click, which pans here).
      if (ctrl && shift && !alt) {
        pivot_to_cursor();
        break;
      }
      gesture_ = (alt || ctrl) ? Gesture::Zoom : shift ? Gesture::Pan : Gesture::Orbit;
      break;
    case GLFW_MOUSE_BUTTON_LEFT:
      if (alt) {
        gesture_ = shift ? Gesture::Pan : Gesture::Orbit;
        loop_click_ = tools.tool == Tool::Select && !ctrl;
        loop_click_adds_ = shift;
      } else
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
        const glm::dmat3 axes = gizmo_axes();
        const GizmoPart part = gizmo_hit(kind, camera_, center, cursor_, axes);
        if (part != GizmoPart::None) {
          gizmo_ = std::make_unique<GizmoDrag>(kind, part, camera_, center, cursor_, axes);
          drag_group_ = s.active;
          drag_faces_ = s.handles[s.active].faces;
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
  drag_faces_ = s.handles[g].faces;
  drag_start_pose_ = s.handles[g].pose;
  // The grabbed point: where the cursor meets the surface (eye depth from the pick buffer).
  drag_anchor_ = handle_pivot(g);
  if (picker_)
    if (const std::optional<Vec3> point = surface_point_at_cursor()) drag_anchor_ = to_glm(*point);
  gesture_ = Gesture::DragHandle;
}

void Editor::update_gesture() {
  if ((gesture_ == Gesture::DragHandle || gesture_ == Gesture::Gizmo) && !dragged_handle_intact())
    return drop_gesture();
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
        g.pose.turn_to((drag_rotation(camera_, press_, cursor_) * drag_start_pose_.rotation).normalized());
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
        g.pose.turn_to((gizmo_->rotation(camera_, cursor_, snap) * drag_start_pose_.rotation).normalized());
      live_edit();
      break;
    }
    case Gesture::None: break;
  }
  last_ = cursor_;
}

void Editor::end_gesture() {
  if ((gesture_ == Gesture::DragHandle || gesture_ == Gesture::Gizmo) && !dragged_handle_intact())
    return drop_gesture();
  const Gesture g = gesture_;
  gesture_ = Gesture::None;
  gesture_button_ = -1;
  std::string what;
  if (loop_click_ && (g == Gesture::Orbit || g == Gesture::Pan) &&
      glm::length(cursor_ - press_) < 3.0) {
    loop_click_ = false;
    select_loop_at_cursor(loop_click_adds_);
    return;
  }
  loop_click_ = false;
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
        // Faces, or vertices in vertex mode.
        const bool vertices = selection_mode() == SelectionMode::Vertices;
        std::vector<int> items;
        // A click when the pointer never left the press point; a lasso closed back near its
        // start is still a lasso (it used to select nothing and clear the selection).
        double reach = glm::length(cursor_ - press_);
        if (g == Gesture::SelectLasso)
          for (const glm::dvec2& p : lasso_) reach = std::max(reach, glm::length(p - press_));
        if (reach < 3.0) {
          // A click: the face under the cursor, or its corner nearest the cursor.
          const int item = vertices ? vertex_at_cursor() : face_at_cursor();
          if (item >= 0) items.push_back(item);
        } else {
          if (g == Gesture::SelectLasso) lasso_.push_back(cursor_);
          const ScreenShape shape = g == Gesture::SelectBox ? ScreenShape::box(press_, cursor_)
                                                            : ScreenShape::lasso(lasso_);
          items = vertices ? vertices_under(shape) : faces_under(shape);
        }
        select_picked(items);
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
  drag_faces_.reset();
  if (what.empty()) return;
  current_gesture_.what = what;
  gesture_stats_ = current_gesture_;
  if (gesture_stats_.frames > 0)
    std::printf("[primo edit] %s: %d frames, %.1f ms mean, %.1f ms max per frame; solver %.1f ms "
                "per iteration; the mesh changed %d times (%.1f a second, %d of them previews); "
                "%.1f frames a second, %.1f ms median and %.1f ms 90th percentile per frame, "
                "%d drawn (%.1f a second)\n",
                what.c_str(), gesture_stats_.frames, gesture_stats_.total_ms / gesture_stats_.frames,
                gesture_stats_.max_ms, 1000.0 * status_.seconds_per_iteration,
                gesture_stats_.mesh_updates, gesture_stats_.updates_per_second(),
                gesture_stats_.preview_updates, gesture_stats_.times.per_second(),
                gesture_stats_.times.quantile(0.5), gesture_stats_.times.quantile(0.9),
                gesture_stats_.drawn_frames,
                gesture_stats_.times.total_ms() > 0
                    ? 1000.0 * gesture_stats_.drawn_frames / gesture_stats_.times.total_ms()
                    : 0.0);
}

void Editor::end_gesture_before_edit() {
  if (gesture_ != Gesture::None) end_gesture();
}

bool Editor::dragged_handle_intact() const {
  if (!doc_ || drag_group_ < 0 || drag_group_ >= int(doc_->state.handles.size())) return false;
  const HandleGroup& g = doc_->state.handles[size_t(drag_group_)];
  return g.faces == drag_faces_ && is_draggable(g.mode);
}

void Editor::drop_gesture() {
  gesture_ = Gesture::None;
  loop_click_ = false;
  gesture_button_ = -1;
  gizmo_.reset();
  drag_group_ = -1;
  drag_faces_.reset();
  lasso_.clear();
}

void Editor::cancel_gesture() {
  const Gesture g = gesture_;
  drop_gesture();
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
  const ScreenShape circle = ScreenShape::circle(cursor_, r);
  if (gesture_ == Gesture::SelectBrush)
    return select_picked(selection_mode() == SelectionMode::Vertices ? vertices_under(circle)
                                                                     : faces_under(circle));
  const std::vector<int> faces = faces_under(circle);
  EditState& s = doc_->state;
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

PickImage Editor::pick_image_under(const ScreenShape& shape) {
  int x0, y0, x1, y1;
  shape.bounds(x0, y0, x1, y1);
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, camera_.width());
  y1 = std::min(y1, camera_.height());
  PickImage image;
  if (picker_ && x1 > x0 && y1 > y0) image = picker_->read(x0, y0, x1 - x0, y1 - y0);
  return image;
}

std::vector<ProjectedPoint> Editor::project_points(const std::vector<Vec3>& points) const {
  std::vector<ProjectedPoint> projected(points.size());
  const glm::dmat4 m = camera_.projection() * camera_.view();
  const glm::dvec3 eye = camera_.eye(), forward = camera_.forward();
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 c = to_glm(points[i]);
    const glm::dvec4 clip = m * glm::dvec4(c, 1.0);
    projected[i].depth = glm::dot(c - eye, forward);
    if (clip.w <= 0) continue;
    projected[i].x = (clip.x / clip.w * 0.5 + 0.5) * camera_.width();
    projected[i].y = (0.5 - clip.y / clip.w * 0.5) * camera_.height();
  }
  return projected;
}

std::vector<int> Editor::faces_under(const ScreenShape& shape) {
  std::vector<int> faces =
      faces_in_shape(shape, pick_image_under(shape),
                     project_points(face_centroids(*doc_->topology, positions())), tools.xray,
                     0.01 * doc_->topology->bbox_diagonal);
  drop_hidden(faces, doc_->state.hidden);
  return faces;
}

int Editor::face_at_cursor() {
  if (!doc_ || !cursor_in_viewport()) return -1;
  if (picker_) {
    // The window's pick pass draws no hidden face; a picker that does, finds none here.
    const int f = picker_->read(int(cursor_.x), int(cursor_.y), 1, 1).face_at(int(cursor_.x), int(cursor_.y));
    return is_hidden(doc_->state.hidden, f) ? -1 : f;
  }
  const std::vector<int> near = faces_under(ScreenShape::circle(cursor_, 4.0));
  return near.empty() ? -1 : near.front();
}

void Editor::update_hover() {
  if (!doc_) return;
  GizmoKind kind;
  glm::dvec3 center;
  const GizmoPart part = gizmo_visible(kind, center) ? gizmo_hit(kind, camera_, center, cursor_, gizmo_axes())
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

}  // namespace primo::editor
