#pragma once
// The optimization problem on rigid bodies: each body is a group of prisms moving together
// (one free prism, a handle group, or later a cluster of the hierarchy). Joints between
// prisms of different bodies couple them; joints inside one body have constant energy.

#include <vector>

#include "primo/model/bilinear_inner_product.h"
#include "primo/model/prism_layer.h"

namespace primo {

enum class BodyKind {
  Free,           // 6 degrees of freedom
  Fixed,          // prescribed rigid motion
  PinnedPosition, // rest_center prescribed, rotation free (3 dof)
  FixedRotation,  // rotation prescribed, translation free (3 dof)
};

// A body's rigid motion: world(p) = rotation * (p - rest_center) + position, for p in rest
// coordinates. At rest: rotation = I, position = rest_center.
struct BodyState {
  Mat3 rotation = Mat3::Identity();
  Vec3 position = Vec3::Zero();
};

struct RigidSystem {
  struct Body {
    BodyKind kind = BodyKind::Free;
    std::vector<int> faces;
    Vec3 rest_center = Vec3::Zero();  // area-weighted mean of the faces' centroids
    // The body's own side faces (boundary ones too), unweighted: the metric in which the
    // closest rigid motion to an affine update is measured (paper Eq. 7).
    Vec3 metric_mean = Vec3::Zero();      // mean of side-patch means, relative to rest_center
    Mat3 metric_centered = Mat3::Zero();  // second moment about metric_mean
    Mat3 metric_pinned = Mat3::Zero();    // second moment about rest_center
    double metric_weight = 0.0;           // number of side patches
  };

  // A joint between prisms of two different bodies, with its side modes in body coordinates
  // (points relative to the body's rest_center).
  struct Coupling {
    int body[2];
    double weight;
    PatchModes local[2];
    // cross = weight * sum over modes of (mode weight) local[0] local[1]^T: the constant part
    // of Horn's covariance for side 0; side 1's is its transpose (cross_of). Kept in step
    // with `local` by update_cross().
    Mat3 cross;
    void update_cross();
    Mat3 cross_of(int side) const { return side == 0 ? cross : Mat3(cross.transpose()); }
  };

  // A zero-rest-length spring on a point of a body.
  struct Spring {
    int body;
    Vec3 local;   // rest point relative to the body's rest_center
    Vec3 target;  // world position it is pulled towards
    double weight;
  };

  std::vector<Body> bodies;
  std::vector<int> face_body;
  std::vector<Coupling> couplings;
  std::vector<Spring> springs;
  double internal_energy = 0.0;  // joints inside one body: invariant under its motion

  // For each body, the couplings it takes part in and on which side (CSR).
  std::vector<int> coupling_begin;
  std::vector<std::pair<int, int>> body_couplings;  // (coupling index, side)
  std::vector<int> spring_begin;
  std::vector<int> body_springs;

  int n_bodies() const { return int(bodies.size()); }
  double energy(const std::vector<BodyState>& state) const;
  double coupling_energy(const Coupling& c, const BodyState& s0, const BodyState& s1) const;
  static double spring_energy(const Spring& s, const BodyState& state) {
    return s.weight * (state.rotation * s.local + state.position - s.target).squaredNorm();
  }
};

// A spring on a face: the prism's rest centroid is pulled to `target`, with `weight` already
// including stiffness and the area normalization of its force.
struct FaceSpring {
  int face;
  Vec3 target;
  double weight;
};

// Groups faces into bodies (face_body[f] in [0, kinds.size())) and precomputes couplings.
RigidSystem build_rigid_system(const PrismLayer& layer, const std::vector<int>& face_body,
                               const std::vector<BodyKind>& kinds,
                               const std::vector<FaceSpring>& springs);

// Replaces the system's springs (their targets or weights changed).
void set_springs(RigidSystem& system, const PrismLayer& layer,
                 const std::vector<FaceSpring>& springs);
// Rebuild the per-body indices after `system.couplings` or `system.springs` was replaced.
void index_couplings(RigidSystem& system);
void index_springs(RigidSystem& system);

// World position of a rest-coordinate point of a body, and of a body-local offset.
inline Vec3 world_point(const BodyState& s, const Vec3& local) {
  return s.rotation * local + s.position;
}

}  // namespace primo
