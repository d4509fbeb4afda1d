#pragma once
// The scenario format, version 1 (docs/scenario-format.md): parsing with strict validation,
// writing, and resolving selections against a mesh.

#include <optional>
#include <string>
#include <vector>

#include "primo/model/constraints.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh.h"

namespace primo {

// Every number of a scenario or session file is at most this in magnitude: values beyond it
// (a stiffness of 1e308) are finite but overflow the energy.
inline constexpr double kMaxScenarioMagnitude = 1e15;

// Exactly one kind is set, as in the file.
struct Selection {
  enum class Kind { Faces, Vertices, Box, Sphere, All };
  Kind kind = Kind::All;
  std::vector<int> indices;  // Faces / Vertices
  Vec3 min = Vec3::Zero();   // Box
  Vec3 max = Vec3::Zero();   // Box
  Vec3 center = Vec3::Zero();  // Sphere
  double radius = 0.0;         // Sphere
};

struct TransformSpec {
  Vec3 translate = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();
  double angle_deg = 0.0;
  std::optional<Vec3> center;  // default: the group's area-weighted centroid
};

struct RegionSpec {
  std::string name;   // may be empty
  std::string where;  // JSON path, e.g. "regions[0]"
  Selection select;
  std::optional<double> height;
  std::optional<double> width;
};

struct HandleSpec {
  std::string name;
  std::string where;
  Selection select;
  Fix fix = Fix::All;
  TransformSpec transform;
};

struct ForceSpec {
  std::string name;
  std::string where;
  Selection select;
  Vec3 target_offset = Vec3::Zero();
  double stiffness = 0.0;
};

enum class SolverMethod { Default, Global, Local, Hierarchical };

struct SolverSpec {
  int max_iterations = 100;
  double tolerance = 1e-8;
  SolverMethod method = SolverMethod::Default;  // our documented extension: solver.method
};

// Our extension `solved_state` (docs/scenario-format.md): the per-face rigid motions of a
// solved pose, x -> R x + t in rest coordinates, which a solve starts from instead of rest, so
// that a pose saved from the editor is reproduced exactly (the format allows it from version 1
// on). Free prisms take their motion; a `position` handle its rotation, an `orientation`
// handle its translation; `fix: "all"` handles keep their transform.
struct SolvedStateSpec {
  std::vector<RigidTransform> face_motions;  // one per face of the mesh, in its order
};

// Our extension `editor`: what the format cannot say about the editor's handles. A fixed
// region and a posable handle are both `fix: "all"`; these indices into `handles` are the
// fixed regions, so they come back as regions that cannot be dragged.
// `mirror_pairs` are the editor's mirrored handles: two `handles` (or two `forces`) whose poses
// the editor keeps mirror images across the plane perpendicular to `axis` through the mesh's
// bounding-box centre. The solver does not read them: each handle's transform is in the file.
struct MirrorPairSpec {
  bool forces = false;  // indices into `forces` rather than `handles`
  int first = 0, second = 0;
  int axis = 0;         // 0 x, 1 y, 2 z
};

// A world axis with its direction: "+x" is {0, +1}, "-z" is {2, -1}.
struct SignedAxis {
  int axis = 1;  // 0 x, 1 y, 2 z
  int sign = 1;  // +1 or -1
  bool operator==(const SignedAxis& o) const { return axis == o.axis && sign == o.sign; }
};

// Which way the model's up and its front point (`editor.orientation`): the editor's views
// (front, top, ...) and its ground grid follow it; the solver does not read it. The two axes
// are perpendicular. The default is the convention of OBJ and glTF: up +y, front +z.
struct ModelOrientation {
  SignedAxis up{1, 1};
  SignedAxis front{2, 1};
  bool operator==(const ModelOrientation& o) const { return up == o.up && front == o.front; }
};

struct EditorSpec {
  std::vector<int> fixed_regions;
  std::vector<MirrorPairSpec> mirror_pairs;
  std::optional<ModelOrientation> orientation;
};

struct Scenario {
  std::string source;     // the scenario file's path ("" when parsed from text)
  std::string mesh;       // as written in the file
  std::string mesh_path;  // resolved against the scenario file's folder
  PrismParameters prisms; // global values; factors are filled by resolve_scenario
  std::vector<RegionSpec> regions;
  std::vector<HandleSpec> handles;
  std::vector<ForceSpec> forces;
  SolverSpec solver;
  std::optional<SolvedStateSpec> solved_state;
  std::optional<EditorSpec> editor;
};

// Throws Error "<source>: <json path>: <problem>" for malformed JSON (with line/column),
// unknown keys, wrong types, missing required keys and out-of-range values.
Scenario parse_scenario(const std::string& json_text, const std::string& source);
Scenario load_scenario(const std::string& path);

// Serializes a scenario (all keys written explicitly). Parsing the result gives back an
// equal scenario.
std::string scenario_to_json(const Scenario& scenario);

// "+x", "-y", ... as the file writes a signed axis.
std::string signed_axis_name(const SignedAxis& axis);

// An orientation object on its own, `{"up": "+y", "front": "-z"}`: what `editor.orientation`
// holds, and what a mesh's orientation file beside it holds (docs/editor.md). Throws Error
// "<source>: <key>: <problem>" as parse_scenario does.
ModelOrientation parse_model_orientation(const std::string& json_text, const std::string& source);

// Faces selected, sorted ascending. Throws Error naming `owner` ("handle 'top'",
// "forces[2]", ...) when an index is out of range or nothing is selected.
std::vector<int> resolve_selection(const Selection& selection, const Mesh& mesh,
                                   const FaceGeometry& geometry, const std::string& owner);

// Everything the solver needs, with selections resolved on `mesh`.
struct ResolvedScenario {
  PrismParameters prisms;  // with per-face factors from the regions
  std::vector<Handle> handles;
  std::vector<Force> forces;
  SolverSpec solver;
  std::vector<RigidTransform> start_motions;  // the solved state's, checked: one per face
};

// Applies regions in order (a later region wins per key), resolves handles (a face in two
// handles is an error naming both) and forces, and turns transforms into rigid motions
// (default center: the group's area-weighted centroid). Throws Error on every violation.
ResolvedScenario resolve_scenario(const Scenario& scenario, const Mesh& mesh);

}  // namespace primo
