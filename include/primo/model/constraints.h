#pragma once
// What a user asks of a deformation: prism parameters, handles and forces, with faces already
// resolved to indices. Both the scenario loader and the editor produce these.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "primo/util/types.h"

namespace primo {

// x' = rotation * x + translation.
struct RigidTransform {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();

  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
  static RigidTransform identity() { return {}; }
};

// A rotation of `angle_deg` degrees (right-handed) about `axis` through `center`, followed by
// `translate`: x' = R (x - center) + center + translate. `axis` need not be unit length but
// must be non-zero when the angle is non-zero.
RigidTransform make_rigid_transform(const Vec3& translate, const Vec3& axis, double angle_deg,
                                    const Vec3& center);

// What a prism height is a multiple of (docs/scenario-format.md, "prisms").
enum class HeightUnit {
  // `prisms.height`: the format's and the paper's unit. The layer thins as the mesh is
  // refined, so the same model at 4x the faces bends more easily (a softer material).
  MeanEdgeLength,
  // `prisms.half_thickness`: a fraction of the bounding-box diagonal, so the material is the
  // same at every resolution.
  Diagonal,
};

// The half-thickness the editor gives a new mesh and the quality benchmark uses, as a
// fraction of the bounding-box diagonal; chosen by measurement (docs/quality.md, "Default
// material"). Scenario files that set neither key keep the format's `height` 1.
inline constexpr double kDefaultHalfThickness = 0.08;

struct PrismParameters {
  double height = 1.0;        // half-thickness as a multiple of `height_unit`
  HeightUnit height_unit = HeightUnit::MeanEdgeLength;
  double normal_blend = 0.0;  // beta: 0 thin shell, 1 thin plate, < 0 enhances detail
  double width = 1.0;         // scale of every prism about its face centroid
  // Per-face multipliers from regions (empty means all 1). Height factors act per vertex as
  // the minimum over the vertex's incident faces.
  std::vector<double> face_height_factor;
  std::vector<double> face_width_factor;

  // The product's default material (kDefaultHalfThickness), as opposed to the format's.
  static PrismParameters product_default() {
    PrismParameters p;
    p.height = kDefaultHalfThickness;
    p.height_unit = HeightUnit::Diagonal;
    return p;
  }
};

enum class Fix {
  All,          // position and orientation prescribed
  Position,     // area-weighted centroid prescribed, orientation optimized
  Orientation,  // rotation prescribed, translation optimized
};

// The scenario format's name of a mode: "all", "position" or "orientation".
const char* fix_name(Fix fix);
// The mode of that name; nullopt for any other.
std::optional<Fix> fix_from_name(std::string_view name);

// One rigid group of faces. `transform` moves the group from its rest pose to its target.
struct Handle {
  std::string name;
  std::vector<int> faces;
  Fix fix = Fix::All;
  RigidTransform transform;
  // The transform's rotation with its whole turns (turn.h): rotation_of_turn(*turn) is
  // transform.rotation. Absent: the principal one, at most half a turn.
  std::optional<Vec3> turn = std::nullopt;
};

// Zero-rest-length springs pulling each face's moved rest centroid towards centroid + offset.
// Energy: stiffness * sum_f |F_f| |x_f - target_f|^2 / sum_f |F_f|.
struct Force {
  std::string name;
  std::vector<int> faces;
  Vec3 target_offset = Vec3::Zero();
  double stiffness = 0.0;
};

}  // namespace primo
