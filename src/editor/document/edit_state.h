#pragma once
// Everything a user edits, as one value: handle groups, global prism settings, painted
// per-face factors, the selection, hidden faces and the model's orientation. Undo keeps whole
// EditStates; the large arrays are shared between states until one changes (copy on write), so
// a step costs what it changed.
// The solver's input is derived from an EditState, never stored beside it.

#include <memory>
#include <string>
#include <vector>

#include "document/selection/face_visibility.h"
#include "handle_model.h"
#include "document/selection/mesh_topology.h"
#include "primo/model/constraints.h"
#include "primo/scenario/scenario.h"
#include "document/selection/selection.h"
#include "document/selection/vertex_selection.h"

namespace primo::editor {

// A new mesh gets the product's default material: a half-thickness that is a fraction of the
// bounding-box diagonal, the same at every resolution. A scenario that sets `prisms.height`
// keeps its unit (mean edge lengths), and the panel shows it as such.
struct PrismSettings {
  double height = kDefaultHalfThickness;          // half-thickness in `height_unit`
  HeightUnit height_unit = HeightUnit::Diagonal;  // prisms.half_thickness or prisms.height
  double width = 1.0;         // prisms.width
  double normal_blend = 0.0;  // prisms.normal_blend (shell 0 .. plate 1)
  bool operator==(const PrismSettings& o) const {
    return height == o.height && height_unit == o.height_unit && width == o.width &&
           normal_blend == o.normal_blend;
  }
};

using FactorArray = std::shared_ptr<const std::vector<double>>;  // null: every face 1

struct EditState {
  std::vector<HandleGroup> handles;
  PrismSettings prisms;
  FactorArray height_factor;
  FactorArray width_factor;
  std::shared_ptr<const FaceMask> selection;
  // Faces hidden from view and selection (face_visibility.h); null while none is. Undone with
  // the selection, and like it not saved in the scenario nor unsaved work.
  HiddenFaces hidden;
  // Vertex mode's selection (vertex_selection.h), null in face mode; `selection` then holds
  // the faces whose corners are all selected.
  std::shared_ptr<const VertexMask> vertex_selection;
  // The model's up and front (model_orientation.h): the views and the ground grid follow it.
  // Saved with the scenario, so setting it is an undo step and unsaved work.
  ModelOrientation orientation;
  int active = -1;       // index into handles, or -1
  int next_number = 1;   // for default handle names
  int next_color = 0;
};

EditState initial_edit_state(int n_faces);

// Deep equality (arrays by content when not shared). Which handle is active does not count:
// activating a handle is not an undo step of its own.
bool operator==(const EditState& a, const EditState& b);
inline bool operator!=(const EditState& a, const EditState& b) { return !(a == b); }

// What the engine needs, and which engine handle/force each group became.
struct DeformationInputs {
  PrismParameters params;
  std::vector<Handle> handles;
  std::vector<Force> forces;
  std::vector<int> group_handle;  // engine handle index per group, or -1
  std::vector<int> group_force;   // engine force index per group, or -1
};
DeformationInputs deformation_inputs(const EditState& state);
// The groups' falloff springs (soft_selection.h), one force a face, in group order: what
// deformation_inputs puts after the Spring groups' own forces.
std::vector<Force> falloff_forces(const EditState& state);

// True when the engine can keep its bodies: same groups, modes, stiffnesses, prism settings
// and factors; only poses may differ.
bool same_structure(const EditState& a, const EditState& b);

// True when at most one group holds the mesh (springs aside) and it is not a fixed region:
// the minimum then moves the whole mesh rigidly with that handle (PriMo's rest pose is only
// defined up to a rigid motion), which surprises a new user; the Handles panel says why.
bool moves_whole_mesh_rigidly(const EditState& state);

// Group index per face (-1 for free faces). A face in several groups shows the last.
std::vector<int> face_groups(const EditState& state, int n_faces);

// --- Operations behind the panels and shortcuts ----------------------------------------

// Makes a group of `faces` (taken away from any other group; groups left empty disappear)
// and makes it active. Returns its index.
int add_handle(EditState& state, const MeshTopology& topology, const std::vector<Vec3>& current,
               std::vector<int> faces, HandleMode mode);
void remove_handle(EditState& state, int index);
// Nothing selected, faces nor vertices (the mode stays).
void deselect_all(EditState& state);
// Links two groups as mirror twins across the plane perpendicular to `axis`.
void link_mirror_twins(EditState& state, int a, int b, int axis);
void set_handle_mode(EditState& state, int index, HandleMode mode);
// Back to the rest pose.
void reset_handle(EditState& state, int index);

// Sets a group's falloff radius and the faces it reaches now: the free faces, in no group.
void set_falloff(EditState& state, const MeshTopology& topology, int index, double radius);

// Per-face factor lookups (1 where null).
double factor_at(const FactorArray& factors, int face);

}  // namespace primo::editor
