#pragma once
// Handle groups as the user sees them: a named set of faces with a mode and a pose. Every
// mode but Spring becomes a primo::Handle (one rigid group); Spring becomes a primo::Force
// pulling the faces towards their rest centroids moved by the handle's translation.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "document/selection/mesh_topology.h"
#include "primo/model/constraints.h"
#include "primo/model/turn.h"
#include "document/selection/soft_selection.h"

namespace primo::editor {

enum class HandleMode {
  Pose,         // position and orientation prescribed (scenario fix "all")
  Position,     // centroid prescribed, orientation follows (fix "position")
  Orientation,  // rotation prescribed, position follows (fix "orientation")
  Spring,       // a force with a stiffness (scenario "forces")
  Fixed,        // a fixed region: position and orientation prescribed, never dragged
};

const char* mode_label(HandleMode mode);
bool is_draggable(HandleMode mode);  // everything but Fixed
bool uses_rotation(HandleMode mode);     // Pose, Orientation
bool uses_translation(HandleMode mode);  // Pose, Position, Spring

// The rigid motion applied to a group's rest pose: x' = R (x - center) + center + translate.
struct Pose {
  Vec3 translate = Vec3::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  // The rotation with its whole turns (primo/model/turn.h): two turns of the gizmo's ring or 720
  // typed stay 720 degrees, and the solver follows all of them. rotation_of_turn(turn) is
  // `rotation`.
  Vec3 turn = Vec3::Zero();

  // `turn`, or where the rotation was set without it, the rotation's own turn.
  Vec3 whole_turn() const { return turn_of(rotation.toRotationMatrix(), turn); }
  // `turn` where it makes the rotation; nullopt where the rotation was set without it: the
  // solver then continues the turn it had, as for any rotation set alone.
  std::optional<Vec3> known_turn() const {
    return turn_makes(turn, rotation.toRotationMatrix()) ? std::optional<Vec3>(turn) : std::nullopt;
  }
  // Sets the rotation; its turn continues the one before (a drag's frames add up).
  void turn_to(const Eigen::Quaterniond& q);
  // Sets the turn and the rotation it makes.
  void set_turn(const Vec3& t);

  bool is_identity() const {
    return translate == Vec3::Zero() && whole_turn() == Vec3::Zero();
  }
  bool operator==(const Pose& o) const {
    return translate == o.translate && rotation.coeffs() == o.rotation.coeffs() &&
           whole_turn() == o.whole_turn();
  }
};

struct HandleGroup {
  std::string name;
  std::shared_ptr<const std::vector<int>> faces;  // sorted, never empty
  HandleMode mode = HandleMode::Pose;
  double stiffness = 10.0;     // a Spring's force, and the falloff's springs
  // Soft selection (soft_selection.h): the radius in rest-pose world units (0: none) and the
  // free faces it reached when it was set.
  double falloff_radius = 0.0;
  FalloffFaces falloff;
  // The pivot (pivot.h): a point of the rest pose, the faces' rest area-weighted centroid
  // unless placed elsewhere.
  Vec3 center = Vec3::Zero();
  Pose pose;
  int color = 0;               // palette slot, stable across edits
  // Symmetry: the index of the group that mirrors this one across the plane perpendicular to
  // `mirror_axis` (0 x, 1 y, 2 z), or -1. The editor keeps the pair's poses mirror images.
  int mirror_twin = -1;
  int mirror_axis = 0;

  RigidTransform transform() const;
  // Where the pivot is now: center + translate.
  Vec3 target_center() const { return center + pose.translate; }
};

// Builds a group for `faces` whose pose matches where those faces are now (`current`
// vertex positions; the rest points when undeformed), so making a handle never moves the
// mesh: the rigid motion that best fits the rest vertices onto the current ones, or for a
// spring the area-weighted displacement of the face centroids. Identity when nothing moved.
HandleGroup make_handle_group(std::string name, std::vector<int> faces, HandleMode mode,
                              const MeshTopology& topology, const std::vector<Vec3>& current);

}  // namespace primo::editor
