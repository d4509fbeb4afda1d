#include "edit_state.h"

#include <algorithm>

#include "pivot.h"
#include "primo/sessions/session_state.h"

namespace primo::editor {
namespace {

bool same_group_structure(const HandleGroup& a, const HandleGroup& b) {
  return same_contents(a.faces, b.faces) && a.mode == b.mode &&
         ((a.mode != HandleMode::Spring && !a.falloff) || a.stiffness == b.stiffness) &&
         same_contents(a.falloff, b.falloff);
}

const char* default_prefix(HandleMode mode) {
  switch (mode) {
    case HandleMode::Fixed: return "Fixed";
    case HandleMode::Spring: return "Spring";
    default: return "Handle";
  }
}

}  // namespace

EditState initial_edit_state(int n_faces) {
  EditState s;
  s.selection = std::make_shared<const FaceMask>(size_t(n_faces), 0);
  return s;
}

bool operator==(const EditState& a, const EditState& b) {
  if (a.handles.size() != b.handles.size() || !(a.prisms == b.prisms) ||
      !same_factors(a.height_factor, b.height_factor) ||
      !same_factors(a.width_factor, b.width_factor) || !same_contents(a.selection, b.selection) ||
      !same_hidden(a.hidden, b.hidden) ||
      !same_contents(a.vertex_selection, b.vertex_selection) ||
      !(a.orientation == b.orientation))
    return false;
  for (size_t i = 0; i < a.handles.size(); ++i) {
    const HandleGroup &x = a.handles[i], &y = b.handles[i];
    if (x.name != y.name || !same_group_structure(x, y) || x.stiffness != y.stiffness ||
        !(x.pose == y.pose) || x.center != y.center || x.mirror_twin != y.mirror_twin ||
        x.mirror_axis != y.mirror_axis || x.falloff_radius != y.falloff_radius)
      return false;
  }
  return true;
}

DeformationInputs deformation_inputs(const EditState& state) {
  DeformationInputs in;
  in.params.height = state.prisms.height;
  in.params.height_unit = state.prisms.height_unit;
  in.params.width = state.prisms.width;
  in.params.normal_blend = state.prisms.normal_blend;
  if (state.height_factor) in.params.face_height_factor = *state.height_factor;
  if (state.width_factor) in.params.face_width_factor = *state.width_factor;
  for (const HandleGroup& g : state.handles) {
    in.group_handle.push_back(-1);
    in.group_force.push_back(-1);
    if (g.mode == HandleMode::Spring) {
      in.group_force.back() = int(in.forces.size());
      in.forces.push_back({g.name, *g.faces, g.pose.translate, g.stiffness});
    } else {
      in.group_handle.back() = int(in.handles.size());
      Fix fix = Fix::All;
      if (g.mode == HandleMode::Position) fix = Fix::Position;
      if (g.mode == HandleMode::Orientation) fix = Fix::Orientation;
      in.handles.push_back({g.name, *g.faces, fix, g.transform(), g.pose.known_turn()});
    }
  }
  for (Force& f : falloff_forces(state)) in.forces.push_back(std::move(f));
  return in;
}

bool same_structure(const EditState& a, const EditState& b) {
  if (a.handles.size() != b.handles.size() || !(a.prisms == b.prisms) ||
      !same_factors(a.height_factor, b.height_factor) ||
      !same_factors(a.width_factor, b.width_factor))
    return false;
  for (size_t i = 0; i < a.handles.size(); ++i)
    if (!same_group_structure(a.handles[i], b.handles[i])) return false;
  return true;
}

std::vector<int> face_groups(const EditState& state, int n_faces) {
  std::vector<int> group(n_faces, -1);
  for (size_t g = 0; g < state.handles.size(); ++g)
    for (int f : *state.handles[g].faces)
      if (f >= 0 && f < n_faces) group[f] = int(g);
  return group;
}

int add_handle(EditState& state, const MeshTopology& topology, const std::vector<Vec3>& current,
               std::vector<int> faces, HandleMode mode) {
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  // 1. Take the faces away from the other groups.
  std::vector<HandleGroup> kept;
  std::vector<int> new_index(state.handles.size(), -1);
  for (size_t g = 0; g < state.handles.size(); ++g) {
    HandleGroup h = state.handles[g];
    std::vector<int> rest;
    std::set_difference(h.faces->begin(), h.faces->end(), faces.begin(), faces.end(),
                        std::back_inserter(rest));
    if (rest.empty()) continue;
    new_index[g] = int(kept.size());
    if (rest.size() != h.faces->size()) {
      // A pivot at the rest centroid stays the rest centroid of what is left; one placed
      // elsewhere (a joint) stays there. The rigid motion is kept either way.
      if (h.center == area_weighted_centroid(topology.rest_geometry, *h.faces))
        move_pivot(h, area_weighted_centroid(topology.rest_geometry, rest));
      h.faces = std::make_shared<const std::vector<int>>(std::move(rest));
    }
    kept.push_back(std::move(h));
  }
  for (HandleGroup& h : kept)
    if (h.mirror_twin >= 0) h.mirror_twin = new_index[size_t(h.mirror_twin)];
  state.handles = std::move(kept);
  // 2. The new group, posed where its faces are now.
  HandleGroup group = make_handle_group(
      std::string(default_prefix(mode)) + " " + std::to_string(state.next_number++),
      std::move(faces), mode, topology, current);
  group.color = state.next_color++;
  state.handles.push_back(std::move(group));
  state.active = int(state.handles.size()) - 1;
  return state.active;
}

void remove_handle(EditState& state, int index) {
  if (index < 0 || index >= int(state.handles.size())) return;
  state.handles.erase(state.handles.begin() + index);
  for (HandleGroup& h : state.handles) {
    if (h.mirror_twin == index) h.mirror_twin = -1;  // the twin stays, on its own
    else if (h.mirror_twin > index) --h.mirror_twin;
  }
  if (state.active == index)
    state.active = std::min(index, int(state.handles.size()) - 1);
  else if (state.active > index)
    --state.active;
}

void link_mirror_twins(EditState& state, int a, int b, int axis) {
  const int n = int(state.handles.size());
  if (a < 0 || b < 0 || a >= n || b >= n || a == b) return;
  for (const int i : {a, b}) {
    const int old = state.handles[size_t(i)].mirror_twin;
    if (old >= 0) state.handles[size_t(old)].mirror_twin = -1;
  }
  state.handles[size_t(a)].mirror_twin = b;
  state.handles[size_t(b)].mirror_twin = a;
  state.handles[size_t(a)].mirror_axis = state.handles[size_t(b)].mirror_axis = axis;
}

void set_handle_mode(EditState& state, int index, HandleMode mode) {
  if (index < 0 || index >= int(state.handles.size())) return;
  HandleGroup& g = state.handles[index];
  // A spring pulls by translation only; other modes keep the pose they had.
  if (mode == HandleMode::Spring) g.pose.set_turn(Vec3::Zero());
  g.mode = mode;
}

void reset_handle(EditState& state, int index) {
  if (index < 0 || index >= int(state.handles.size())) return;
  state.handles[index].pose = Pose{};
}

bool moves_whole_mesh_rigidly(const EditState& state) {
  int holding = 0;
  for (const HandleGroup& g : state.handles) {
    if (g.mode == HandleMode::Spring) continue;
    if (g.mode == HandleMode::Fixed) return false;
    ++holding;
  }
  return holding == 1;
}

double factor_at(const FactorArray& factors, int face) {
  return factors ? (*factors)[face] : 1.0;
}

void deselect_all(EditState& state) {
  if (state.selection)
    state.selection = std::make_shared<const FaceMask>(state.selection->size(), 0);
  if (state.vertex_selection)
    state.vertex_selection = std::make_shared<const VertexMask>(state.vertex_selection->size(), 0);
}

std::vector<Force> falloff_forces(const EditState& state) {
  std::vector<Force> forces;
  for (const HandleGroup& g : state.handles) {
    if (!g.falloff) continue;
    const RigidTransform motion =
        falloff_motion(g.transform(), g.pose.translate, g.mode == HandleMode::Spring);
    for (Force& f : primo::falloff_forces(g.name, *g.falloff, motion, g.stiffness))
      forces.push_back(std::move(f));
  }
  return forces;
}

void set_falloff(EditState& state, const MeshTopology& topology, int index, double radius) {
  HandleGroup& g = state.handles[size_t(index)];
  g.falloff_radius = std::max(0.0, radius);
  FaceMask taken(size_t(topology.n_faces), 0);
  for (const HandleGroup& other : state.handles) apply_selection(taken, *other.faces, SelectOp::Add);
  std::vector<FalloffFace> faces = falloff_faces(topology, *g.faces, g.falloff_radius, taken);
  g.falloff = faces.empty() ? nullptr : std::make_shared<const std::vector<FalloffFace>>(std::move(faces));
}

}  // namespace primo::editor
