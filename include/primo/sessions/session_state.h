#pragma once
// The state a recorded posing session keeps (docs/sessions.md): the handles with their faces,
// modes and poses, the prism settings and the painted per-face factors. That is everything
// the solver sees and nothing else (no selection, camera or tool settings), as plain values,
// so that sessions are read, validated and replayed without the editor. The editor's
// EditState holds these and more; src/editor/recording/session_bridge.h maps one to the other.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "primo/mesh/geometry.h"
#include "primo/model/constraints.h"
#include "primo/model/turn.h"

namespace primo {

// How a handle holds its faces. In the file: "pose", "position", "orientation", "spring",
// "fixed".
enum class SessionHandleMode {
  Pose,         // position and orientation prescribed (scenario fix "all")
  Position,     // centroid prescribed, orientation follows (fix "position")
  Orientation,  // rotation prescribed, position follows (fix "orientation")
  Spring,       // a force with a stiffness (scenario "forces")
  Fixed,        // a fixed region: position and orientation prescribed, never dragged
};

// The rigid motion applied to a handle's rest pose: x' = R (x - center) + center + translate.
struct SessionPose {
  Vec3 translate = Vec3::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  // The rotation with its whole turns (primo/model/turn.h; rotation_of_turn(turn) is `rotation`):
  // a handle turned 720 degrees replays as two turns.
  Vec3 turn = Vec3::Zero();

  // `turn`, or where the rotation was set without it, the rotation's own turn.
  Vec3 whole_turn() const { return turn_of(rotation.toRotationMatrix(), turn); }
  // `turn` where it makes the rotation; nullopt where the rotation was set without it (a file
  // written before turns were kept): the solver then continues the turn it had.
  std::optional<Vec3> known_turn() const {
    return turn_makes(turn, rotation.toRotationMatrix()) ? std::optional<Vec3>(turn) : std::nullopt;
  }

  bool operator==(const SessionPose& o) const {
    return translate == o.translate && rotation.coeffs() == o.rotation.coeffs() &&
           whole_turn() == o.whole_turn();
  }
};

// A handle's falloff (the editor's soft selection, primo/model/falloff_springs.h) as the editor
// froze it when its radius was set: the radius, and the free faces it reached (sorted, distinct,
// none of the handle's own) with their weights in (0, 1]. A replay makes the same springs from
// them without searching the mesh again.
struct SessionFalloff {
  double radius = 0.0;
  std::vector<int> faces;
  std::vector<double> weights;
  bool operator==(const SessionFalloff& o) const {
    return radius == o.radius && faces == o.faces && weights == o.weights;
  }
};

struct SessionHandle {
  std::string name;
  std::shared_ptr<const std::vector<int>> faces;  // sorted, distinct, never empty
  SessionHandleMode mode = SessionHandleMode::Pose;
  double stiffness = 10.0;     // Spring only: the force's stiffness
  Vec3 center = Vec3::Zero();  // the pivot, a rest point (the centroid unless placed elsewhere)
  SessionPose pose;
  int color = 0;               // the editor's palette slot (not seen by the solver)
  std::shared_ptr<const SessionFalloff> falloff;  // null: none

  RigidTransform transform() const;
};

// The global prism settings. The height keeps the unit it was given in: `half_thickness`
// (a fraction of the bounding-box diagonal, the editor's default material) or the scenario
// format's `height` (mean edge lengths).
struct SessionPrisms {
  double height = kDefaultHalfThickness;
  HeightUnit height_unit = HeightUnit::Diagonal;
  double width = 1.0;
  double normal_blend = 0.0;

  bool operator==(const SessionPrisms& o) const {
    return height == o.height && height_unit == o.height_unit && width == o.width &&
           normal_blend == o.normal_blend;
  }
};

// One painted layer's per-face factors; null means every face 1. Shared between states until
// one of them changes (the editor's undo steps share them the same way).
using FaceFactors = std::shared_ptr<const std::vector<double>>;

// Shared arrays compared by content: both null, or equal elements.
template <class T>
bool same_contents(const std::shared_ptr<const T>& a, const std::shared_ptr<const T>& b) {
  if (a == b) return true;
  if (!a || !b) return false;
  return *a == *b;
}
// Per-face factors compared by content, a null array equal to one of all 1s (the editor's
// edit states compare theirs the same way).
bool same_factors(const FaceFactors& a, const FaceFactors& b);

struct SessionState {
  std::vector<SessionHandle> handles;
  SessionPrisms prisms;
  FaceFactors height_factor;
  FaceFactors width_factor;
};

// Deep equality: faces and factors by content (a null factor array equals one of all 1s).
// Handle colours do not count: they change nothing the solver sees.
bool operator==(const SessionState& a, const SessionState& b);
inline bool operator!=(const SessionState& a, const SessionState& b) { return !(a == b); }

// What the engine needs for a state: every handle but the springs becomes a primo::Handle
// (one rigid group), every spring a primo::Force pulling its faces towards their rest
// centroids moved by the handle's translation; both in the order of `state.handles`. Then the
// handles' falloffs, one force a face (primo/model/falloff_springs.h), their shares from the
// mesh's `rest` face geometry.
struct SessionSolverInputs {
  PrismParameters params;
  std::vector<Handle> handles;
  std::vector<Force> forces;
};
SessionSolverInputs solver_inputs(const SessionState& state, const FaceGeometry& rest);

// True when a Deformer made for `a` also serves `b` once its targets are moved: the same
// handles, modes, spring stiffnesses, falloffs, prism settings and factors; only poses may
// differ.
bool same_solver_structure(const SessionState& a, const SessionState& b);

}  // namespace primo
