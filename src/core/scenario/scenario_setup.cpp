// Turning a parsed scenario into solver input: selections become face indices, regions become
// per-face factors and handle transforms become rigid motions.

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "primo/util/error.h"
#include "primo/model/turn.h"
#include "primo/scenario/scenario.h"

namespace primo {
namespace {

std::string source_label(const std::string& source) {
  return source.empty() ? "(text)" : source;
}

// How errors refer to a region, handle or force: "handle 'top' (handles[1])" when it has a
// name, else its JSON path alone.
std::string owner_name(const char* kind, const std::string& name, const std::string& where,
                       const char* list, size_t index) {
  const std::string path =
      where.empty() ? std::string(list) + "[" + std::to_string(index) + "]" : where;
  if (name.empty()) return path;
  return std::string(kind) + " '" + name + "' (" + path + ")";
}

bool in_closed_box(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

// resolve_selection's messages name the owner but not the file; the scenario knows the file.
std::vector<int> resolve_in_scenario(const Selection& selection, const Mesh& mesh,
                                     const FaceGeometry& geometry, const std::string& owner,
                                     const std::string& label) {
  try {
    return resolve_selection(selection, mesh, geometry, owner);
  } catch (const Error& e) {
    throw Error(label + ": " + e.what());
  }
}

}  // namespace

std::vector<int> resolve_selection(const Selection& selection, const Mesh& mesh,
                                   const FaceGeometry& geometry, const std::string& owner) {
  const int n_faces = int(mesh.n_faces());
  if (geometry.centroid.size() != size_t(n_faces))
    throw std::invalid_argument("resolve_selection: face geometry does not match the mesh");

  std::vector<int> faces;
  switch (selection.kind) {
    case Selection::Kind::Faces:
      for (int f : selection.indices) {
        if (f < 0 || f >= n_faces)
          throw Error(owner + ": face index " + std::to_string(f) +
                      " is out of range (the mesh has " + std::to_string(n_faces) + " faces)");
        faces.push_back(f);
      }
      break;
    case Selection::Kind::Vertices: {
      const int n_vertices = int(mesh.n_vertices());
      std::vector<bool> listed(size_t(n_vertices), false);
      for (int v : selection.indices) {
        if (v < 0 || v >= n_vertices)
          throw Error(owner + ": vertex index " + std::to_string(v) +
                      " is out of range (the mesh has " + std::to_string(n_vertices) +
                      " vertices)");
        listed[size_t(v)] = true;
      }
      for (auto f : mesh.faces()) {
        for (auto v : f.vertices()) {
          if (listed[size_t(v.idx())]) {
            faces.push_back(f.idx());
            break;
          }
        }
      }
      break;
    }
    case Selection::Kind::Box:
      for (int f = 0; f < n_faces; ++f)
        if (in_closed_box(geometry.centroid[size_t(f)], selection.min, selection.max))
          faces.push_back(f);
      break;
    case Selection::Kind::Sphere: {
      // Squared distances, so a centroid exactly on the sphere counts as inside.
      const double radius_squared = selection.radius * selection.radius;
      for (int f = 0; f < n_faces; ++f)
        if ((geometry.centroid[size_t(f)] - selection.center).squaredNorm() <= radius_squared)
          faces.push_back(f);
      break;
    }
    case Selection::Kind::All:
      for (int f = 0; f < n_faces; ++f) faces.push_back(f);
      break;
  }

  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  if (faces.empty()) throw Error(owner + " selects no face");
  return faces;
}

ResolvedScenario resolve_scenario(const Scenario& scenario, const Mesh& mesh) {
  const std::string label = source_label(scenario.source);
  const FaceGeometry geometry = compute_face_geometry(mesh);
  const size_t n_faces = mesh.n_faces();

  ResolvedScenario resolved;
  resolved.prisms = scenario.prisms;
  resolved.prisms.face_height_factor.assign(n_faces, 1.0);
  resolved.prisms.face_width_factor.assign(n_faces, 1.0);
  for (size_t i = 0; i < scenario.regions.size(); ++i) {
    const RegionSpec& region = scenario.regions[i];
    const std::string owner = owner_name("region", region.name, region.where, "regions", i);
    for (int f : resolve_in_scenario(region.select, mesh, geometry, owner, label)) {
      if (region.height) resolved.prisms.face_height_factor[size_t(f)] = *region.height;
      if (region.width) resolved.prisms.face_width_factor[size_t(f)] = *region.width;
    }
  }

  // Which handle owns each face, to report a face claimed twice with both handles named.
  std::vector<int> handle_of_face(n_faces, -1);
  std::vector<std::string> handle_owners;
  for (size_t i = 0; i < scenario.handles.size(); ++i) {
    const HandleSpec& spec = scenario.handles[i];
    const std::string owner = owner_name("handle", spec.name, spec.where, "handles", i);
    handle_owners.push_back(owner);

    Handle handle;
    handle.name = spec.name;
    handle.fix = spec.fix;
    handle.faces = resolve_in_scenario(spec.select, mesh, geometry, owner, label);
    for (int f : handle.faces) {
      int& claimed_by = handle_of_face[size_t(f)];
      if (claimed_by >= 0)
        throw Error(label + ": " + owner + ": face " + std::to_string(f) + " is also in " +
                    handle_owners[size_t(claimed_by)] + "; a face may be in one handle only");
      claimed_by = int(i);
    }

    const TransformSpec& t = spec.transform;
    if (t.angle_deg != 0.0 && !(t.axis.norm() > 0.0))
      throw Error(label + ": " + owner +
                  ": transform.axis must be non-zero when angle_deg is not 0");
    const Vec3 center = t.center ? *t.center : area_weighted_centroid(geometry, handle.faces);
    handle.transform = make_rigid_transform(t.translate, t.axis, t.angle_deg, center);
    handle.turn = turn_about(t.axis, t.angle_deg);  // kept as written: 360 is a whole turn
    resolved.handles.push_back(std::move(handle));
  }

  for (size_t i = 0; i < scenario.forces.size(); ++i) {
    const ForceSpec& spec = scenario.forces[i];
    const std::string owner = owner_name("force", spec.name, spec.where, "forces", i);
    Force force;
    force.name = spec.name;
    force.faces = resolve_in_scenario(spec.select, mesh, geometry, owner, label);
    force.target_offset = spec.target_offset;
    force.stiffness = spec.stiffness;
    resolved.forces.push_back(std::move(force));
  }

  resolved.solver = scenario.solver;
  if (scenario.solved_state) {
    const auto& motions = scenario.solved_state->face_motions;
    if (motions.size() != n_faces)
      throw Error(label + ": solved_state.face_motions: has " + std::to_string(motions.size()) +
                  " motions but the mesh has " + std::to_string(n_faces) +
                  " faces; the solved state belongs to another mesh");
    resolved.start_motions = motions;
  }
  if (scenario.editor)
    for (int h : scenario.editor->fixed_regions)
      if (scenario.handles[size_t(h)].fix != Fix::All)
        throw Error(label + ": editor.fixed_regions: handle " + std::to_string(h) +
                    " is a fixed region but not fix \"all\"");
  return resolved;
}

}  // namespace primo
