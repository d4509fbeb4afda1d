// Pivots: where the active handle turns about, placed from the panel's fields, at the
// selection's centre, back at the rest centroid, or on the surface under the cursor (pivot.h).

#include <cmath>

#include "editor.h"
#include "document/pivot.h"

namespace primo::editor {
namespace {

Vec3 to_eigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

bool Editor::place_pivot(int index, const Vec3& rest_point) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return false;
  if (!rest_point.allFinite()) {
    info("The pivot needs three finite coordinates");
    return false;
  }
  EditState& s = doc_->state;
  HandleGroup& g = s.handles[size_t(index)];
  if (g.center == rest_point) return false;
  move_pivot(g, rest_point);
  // A mirror twin turns about the mirror image of the pivot, as a pair of arms about their
  // shoulders.
  if (g.mirror_twin >= 0 && g.mirror_twin < int(s.handles.size())) {
    if (const MirrorMap* map = mirror_map(g.mirror_axis)) {
      Vec3 mirrored = rest_point;
      mirrored[map->axis] = 2.0 * map->plane - mirrored[map->axis];
      move_pivot(s.handles[size_t(g.mirror_twin)], mirrored);
    }
  }
  return true;
}

bool Editor::set_pivot(int index, const Vec3& rest_point) {
  end_gesture_before_edit();
  if (!place_pivot(index, rest_point)) return false;
  commit("Pivot of '" + doc_->state.handles[size_t(index)].name + "'");
  return true;
}

bool Editor::set_pivot_at(int index, const Vec3& world) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return false;
  const HandleGroup& g = doc_->state.handles[size_t(index)];
  return set_pivot(index, rest_point_of(handle_motion(g, *doc_->topology, positions()), world));
}

bool Editor::pivot_to_selection(int index) {
  if (!doc_) return false;
  const std::vector<int> faces = selected_faces(selection_as_faces());
  if (faces.empty()) {
    info("Select faces first: the pivot goes to the centre of the selection");
    return false;
  }
  return set_pivot_at(index, weighted_centroid(*doc_->topology, positions(), faces));
}

bool Editor::pivot_to_rest_centroid(int index) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return false;
  return set_pivot(index, rest_centroid(doc_->state.handles[size_t(index)], *doc_->topology));
}

bool Editor::pivot_to_cursor() {
  if (!doc_) return false;
  const int active = doc_->state.active;
  if (active < 0 || active >= int(doc_->state.handles.size())) {
    info("No active handle: click a handle first, then place its pivot");
    return false;
  }
  const std::optional<Vec3> point = surface_point_at_cursor();
  if (!point) {
    info("Not on the surface: point at the mesh to place the pivot there");
    return false;
  }
  return set_pivot_at(active, *point);
}

std::optional<Vec3> Editor::surface_point_at_cursor() {
  if (!doc_ || !cursor_in_viewport()) return std::nullopt;
  if (picker_) {
    const PickImage image = picker_->read(int(cursor_.x), int(cursor_.y), 1, 1);
    const double depth = image.depth_at(int(cursor_.x), int(cursor_.y));
    if (std::isfinite(depth)) {
      // The eye depth from the pick buffer, back along the mouse ray.
      const Ray ray = camera_.ray(cursor_);
      const double along = glm::dot(ray.direction, camera_.forward());
      const double t = (depth - glm::dot(ray.origin - camera_.eye(), camera_.forward())) / along;
      return to_eigen(ray.origin + t * ray.direction);
    }
  }
  const int face = face_at_cursor();
  if (face < 0) return std::nullopt;
  return face_centroid(*doc_->topology, positions(), face);
}

}  // namespace primo::editor
