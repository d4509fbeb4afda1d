#include "scenario_bridge.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "model_orientation.h"
#include "primo/model/turn.h"
#include "paint.h"

namespace primo::editor {
namespace fs = std::filesystem;
namespace {

Selection faces_selection(const std::vector<int>& faces) {
  Selection s;
  s.kind = Selection::Kind::Faces;
  s.indices = faces;
  return s;
}

std::string mesh_reference(const std::string& mesh_path, const std::string& scenario_path) {
  std::error_code ec;
  const fs::path mesh = fs::absolute(mesh_path, ec);
  if (ec) return mesh_path;
  const fs::path folder = fs::absolute(scenario_path, ec).parent_path();
  if (ec) return mesh.string();
  const fs::path rel = mesh.lexically_normal().lexically_relative(folder.lexically_normal());
  return rel.empty() ? mesh.string() : rel.generic_string();
}

std::string value_label(const char* what, double v) {
  std::ostringstream s;
  s << what << " x" << v;
  return s.str();
}

FactorArray factor_array(const std::vector<double>& factors) {
  for (double v : factors)
    if (v != 1.0) return std::make_shared<const std::vector<double>>(factors);
  return nullptr;
}

}  // namespace

Scenario export_scenario(const EditState& state, const std::string& mesh_path,
                         const std::string& scenario_path, const SolverSpec& solver,
                         const std::vector<RigidTransform>* motions) {
  Scenario s;
  s.mesh = mesh_reference(mesh_path, scenario_path);
  s.prisms.height = state.prisms.height;
  s.prisms.height_unit = state.prisms.height_unit;
  s.prisms.width = state.prisms.width;
  s.prisms.normal_blend = state.prisms.normal_blend;
  s.solver = solver;

  for (PaintLayer layer : {PaintLayer::Height, PaintLayer::Width})
    for (const FactorGroup& g : group_factors(layer_factors(state, layer))) {
      RegionSpec r;
      r.name = value_label(layer == PaintLayer::Height ? "height" : "width", g.value);
      r.select = faces_selection(g.faces);
      (layer == PaintLayer::Height ? r.height : r.width) = g.value;
      s.regions.push_back(std::move(r));
    }

  // Where each group went: an index into forces or into handles.
  std::vector<int> spec_index(state.handles.size(), -1);
  for (size_t i = 0; i < state.handles.size(); ++i) {
    const HandleGroup& g = state.handles[i];
    spec_index[i] = int(g.mode == HandleMode::Spring ? s.forces.size() : s.handles.size());
    if (g.mode == HandleMode::Spring) {
      ForceSpec f;
      f.name = g.name;
      f.select = faces_selection(*g.faces);
      f.target_offset = g.pose.translate;
      f.stiffness = g.stiffness;
      s.forces.push_back(std::move(f));
      continue;
    }
    HandleSpec h;
    h.name = g.name;
    h.select = faces_selection(*g.faces);
    h.fix = g.mode == HandleMode::Position      ? Fix::Position
            : g.mode == HandleMode::Orientation ? Fix::Orientation
                                                : Fix::All;
    h.transform.translate = g.pose.translate;
    // The turn, whole turns included: angle_deg is kept as written (720 is two turns).
    if (const Vec3 turn = g.pose.whole_turn(); turn != Vec3::Zero()) {
      const AxisAngle a = axis_angle_of_turn(turn);
      h.transform.axis = a.axis;
      h.transform.angle_deg = a.angle_deg;
    }
    h.transform.center = g.center;
    if (g.mode == HandleMode::Fixed) {
      if (!s.editor) s.editor = EditorSpec{};
      s.editor->fixed_regions.push_back(int(s.handles.size()));
    }
    s.handles.push_back(std::move(h));
  }
  // The falloffs' springs (soft_selection.h), one force a face, as the editor solves them.
  for (const Force& force : falloff_forces(state)) {
    ForceSpec f;
    f.name = force.name;
    f.select = faces_selection(force.faces);
    f.target_offset = force.target_offset;
    f.stiffness = force.stiffness;
    s.forces.push_back(std::move(f));
  }
  for (size_t i = 0; i < state.handles.size(); ++i) {
    const HandleGroup& g = state.handles[i];
    const int j = g.mirror_twin;
    if (j <= int(i) || j >= int(state.handles.size())) continue;  // each pair once
    const bool forces = g.mode == HandleMode::Spring;
    if (forces != (state.handles[size_t(j)].mode == HandleMode::Spring)) continue;
    if (!s.editor) s.editor = EditorSpec{};
    s.editor->mirror_pairs.push_back({forces, spec_index[i], spec_index[size_t(j)], g.mirror_axis});
  }
  // The orientation goes into the file unless opening the mesh alone gives it anyway: it is
  // the format's convention and no orientation file beside the mesh could say otherwise.
  std::error_code ec;
  if (!(state.orientation == format_orientation(mesh_path)) ||
      fs::exists(orientation_file_path(mesh_path), ec)) {
    if (!s.editor) s.editor = EditorSpec{};
    s.editor->orientation = state.orientation;
  }
  if (motions) s.solved_state = SolvedStateSpec{*motions};
  return s;
}

EditState import_scenario(const Scenario& scenario, const ResolvedScenario& resolved,
                          const MeshTopology& topology) {
  EditState state = initial_edit_state(topology.n_faces);
  state.prisms.height = scenario.prisms.height;
  state.prisms.height_unit = scenario.prisms.height_unit;
  state.prisms.width = scenario.prisms.width;
  state.prisms.normal_blend = scenario.prisms.normal_blend;
  state.height_factor = factor_array(resolved.prisms.face_height_factor);
  state.width_factor = factor_array(resolved.prisms.face_width_factor);

  auto add = [&](HandleGroup g, const std::string& name) {
    g.name = name.empty() ? "Handle " + std::to_string(state.next_number) : name;
    ++state.next_number;
    g.color = state.next_color++;
    state.handles.push_back(std::move(g));
  };
  for (size_t i = 0; i < resolved.handles.size(); ++i) {
    const Handle& h = resolved.handles[i];
    const TransformSpec& t = scenario.handles[i].transform;
    HandleGroup g;
    g.faces = std::make_shared<const std::vector<int>>(h.faces);
    // The file's centre is the pivot; without one, the format's default, the rest centroid.
    g.center = t.center ? *t.center : area_weighted_centroid(topology.rest_geometry, h.faces);
    g.pose.set_turn(turn_about(t.axis, t.angle_deg));
    g.pose.translate = t.translate;
    switch (h.fix) {
      case Fix::All: {
        const bool fixed =
            scenario.editor ? std::count(scenario.editor->fixed_regions.begin(),
                                         scenario.editor->fixed_regions.end(), int(i)) > 0
                            : g.pose.is_identity();
        g.mode = fixed ? HandleMode::Fixed : HandleMode::Pose;
        break;
      }
      case Fix::Position: g.mode = HandleMode::Position; break;
      case Fix::Orientation: g.mode = HandleMode::Orientation; break;
    }
    add(std::move(g), h.name);
  }
  for (const Force& f : resolved.forces) {
    HandleGroup g;
    g.faces = std::make_shared<const std::vector<int>>(f.faces);
    g.center = area_weighted_centroid(topology.rest_geometry, f.faces);
    g.mode = HandleMode::Spring;
    g.stiffness = f.stiffness;
    g.pose.translate = f.target_offset;
    add(std::move(g), f.name.empty() ? "Spring " + std::to_string(state.next_number) : f.name);
  }
  if (scenario.editor)
    for (const MirrorPairSpec& p : scenario.editor->mirror_pairs) {
      // Forces come after the handles in the editor's list.
      const int offset = p.forces ? int(resolved.handles.size()) : 0;
      link_mirror_twins(state, offset + p.first, offset + p.second, p.axis);
    }
  if (scenario.editor && scenario.editor->orientation) state.orientation = *scenario.editor->orientation;
  state.active = state.handles.empty() ? -1 : 0;
  return state;
}

}  // namespace primo::editor
