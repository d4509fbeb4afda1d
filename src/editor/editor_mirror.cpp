// Symmetry in the editor: mirror maps per axis, and the hooks that make selecting, painting
// and posing act on both sides (mirror.h has the model).

#include <algorithm>
#include <cmath>

#include "editor.h"

namespace primo::editor {

void Editor::set_mirror(int axis, bool on) {
  if (axis < 0 || axis > 2) return;
  tools.mirror[size_t(axis)] = on;
  overlay_changed_ = true;  // the faces without a twin are shaded while a mirror is on
  if (!on) return info(std::string("Mirror ") + axis_name(axis) + " off");
  if (!doc_) return;
  mirror_map(axis);
  info(mirror_summary(axis));
}

const MirrorMap* Editor::mirror_map(int axis) {
  if (!doc_ || axis < 0 || axis > 2) return nullptr;
  auto& map = mirror_maps_[size_t(axis)];
  if (!map) map = std::make_shared<const MirrorMap>(match_mirror(*doc_->topology, axis));
  return map.get();
}

std::string Editor::mirror_summary(int axis) const {
  if (!doc_ || axis < 0 || axis > 2 || !tools.mirror[size_t(axis)]) return "";
  const auto& map = mirror_maps_[size_t(axis)];
  if (!map) return std::string("Mirror ") + axis_name(axis) + " on";
  const int n = doc_->n_faces();
  std::string text = std::string("Mirror ") + axis_name(axis) + ": " +
                     std::to_string(map->matched) + " of " + std::to_string(n) +
                     " faces have a twin (" + (map->by_topology ? "by topology" : "by position") +
                     ")";
  if (map->matched < n)
    text += map->matched == 0
                ? "; the mesh is not symmetric across this plane"
                : "; the " + std::to_string(n - map->matched) +
                      " without one are shaded darker and edited on one side only";
  return text;
}

std::vector<char> Editor::faces_without_twin() {
  if (!doc_) return {};
  std::vector<char> without;
  for (int axis = 0; axis < 3; ++axis) {
    if (!tools.mirror[size_t(axis)]) continue;
    const MirrorMap* map = mirror_map(axis);
    const std::vector<char> here = primo::editor::faces_without_twin(*map);
    if (without.empty()) without.assign(here.size(), 0);
    for (size_t f = 0; f < here.size(); ++f) without[f] |= here[f];
  }
  return without;
}

void Editor::mirror_selection(const FaceMask& before, FaceMask& after) {
  if (!doc_) return;
  for (int axis = 0; axis < 3; ++axis) {
    if (!tools.mirror[size_t(axis)]) continue;
    // Each axis mirrors what the ones before it added, so X and Y together fill 4 quadrants.
    mirror_changes(before, after, *mirror_map(axis));
  }
}

FactorArray Editor::mirror_paint(const FactorArray& before, FactorArray after) {
  if (!doc_) return after;
  for (int axis = 0; axis < 3; ++axis)
    if (tools.mirror[size_t(axis)])
      after = mirror_changes(before, after, doc_->n_faces(), *mirror_map(axis));
  return after;
}

void Editor::follow_mirror() {
  if (!doc_) return;
  EditState& s = doc_->state;
  const int leader = (gesture_ == Gesture::DragHandle || gesture_ == Gesture::Gizmo) &&
                             drag_group_ >= 0
                         ? drag_group_
                         : s.active;
  if (leader < 0 || leader >= int(s.handles.size())) return;
  const HandleGroup& g = s.handles[size_t(leader)];
  if (g.mirror_twin < 0 || g.mirror_twin >= int(s.handles.size())) return;
  HandleGroup& twin = s.handles[size_t(g.mirror_twin)];
  if (g.mode == HandleMode::Fixed || twin.mode == HandleMode::Fixed) return;
  const Pose pose = mirrored_pose(g, twin, *mirror_map(g.mirror_axis));
  // Only what the twin's mode uses: a position-only twin keeps a rotation of identity.
  if (uses_translation(twin.mode)) twin.pose.translate = pose.translate;
  if (uses_rotation(twin.mode)) twin.pose.set_turn(pose.whole_turn());
  if (twin.mode == HandleMode::Spring) twin.stiffness = g.stiffness;
}

bool Editor::make_mirrored_handles(const std::vector<int>& faces, HandleMode mode) {
  int axis = -1;
  for (int a = 0; a < 3 && axis < 0; ++a)
    if (tools.mirror[size_t(a)]) axis = a;
  if (axis < 0) return false;
  const MirrorMap& map = *mirror_map(axis);
  const FaceGeometry& rest = doc_->topology->rest_geometry;
  auto side = [&](int f) { return rest.centroid[size_t(f)][axis] - map.plane; };
  // Faces within half their own size of the plane belong to both sides: a selection that
  // crosses the plane (a head, a tail) is one handle, posed freely.
  for (const int f : faces)
    if (std::abs(side(f)) < 0.5 * std::sqrt(rest.area[size_t(f)])) return false;
  // Each selected face and its twin go to the group of their own side. A face without a twin
  // (a scan's two sides differ) stays in its side's group all the same: the selection is what
  // the user marked, and its twin group is only as complete as the match.
  std::vector<int> plus, minus;
  int without_twin = 0;
  for (const int f : faces) {
    (side(f) > 0 ? plus : minus).push_back(f);
    const int twin = map.twin(f);
    if (twin < 0)
      ++without_twin;
    else
      (side(twin) > 0 ? plus : minus).push_back(twin);
  }
  for (std::vector<int>* group : {&plus, &minus}) {
    std::sort(group->begin(), group->end());
    group->erase(std::unique(group->begin(), group->end()), group->end());
  }
  if (plus.empty() || minus.empty()) return false;

  EditState& s = doc_->state;
  const std::string plus_suffix = std::string(" +") + axis_name(axis);
  const std::string minus_suffix = std::string(" -") + axis_name(axis);
  const int a = add_handle(s, *doc_->topology, positions(), plus, mode);
  const std::string base = s.handles[size_t(a)].name;
  const auto a_faces = s.handles[size_t(a)].faces;
  const int b = add_handle(s, *doc_->topology, positions(), minus, mode);
  --s.next_number;  // one name for the pair
  int a_now = -1;   // making b may have emptied (and dropped) groups before a
  for (size_t i = 0; i < s.handles.size(); ++i)
    if (s.handles[i].faces == a_faces) a_now = int(i);
  s.handles[size_t(a_now)].name = base + plus_suffix;
  s.handles[size_t(b)].name = base + minus_suffix;
  link_mirror_twins(s, a_now, b, axis);
  s.active = a_now;
  deselect_all(s);
  commit("New mirrored " + std::string(mode_label(mode)) + " '" + base + "'");
  const std::string tool_note = drag_tool_after_making(mode);
  std::string text = "Made '" + base + plus_suffix + "' (" + std::to_string(plus.size()) +
                     " faces) and its twin '" + base + minus_suffix + "' (" +
                     std::to_string(minus.size()) + " faces), " + mode_label(mode);
  if (without_twin > 0)
    text += "; " + std::to_string(without_twin) + " of the " + std::to_string(faces.size()) +
            " faces have no twin across " + axis_name(axis);
  info(text + tool_note);
  return true;
}

}  // namespace primo::editor
