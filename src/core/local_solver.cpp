#include "primo/local_solver.h"

#include "primo/horn.h"

namespace primo {

BodyState local_match(const RigidSystem& system, const std::vector<BodyState>& state, int body) {
  const RigidSystem::Body& b = system.bodies[body];
  const BodyState& current = state[body];
  if (b.kind == BodyKind::Fixed) return current;

  // Point pairs (source in body coordinates, target in world) and vector pairs, weighted.
  // Accumulate raw moments so that one pass serves every constraint variant.
  double point_weight = 0.0;
  Vec3 source_sum = Vec3::Zero(), target_sum = Vec3::Zero();
  Mat3 points_st = Mat3::Zero();   // sum w s t^T over point pairs
  Mat3 vectors_st = Mat3::Zero();  // sum w s t^T over vector pairs

  auto add_point = [&](const Vec3& s, const Vec3& t, double w) {
    point_weight += w;
    source_sum += w * s;
    target_sum += w * t;
    points_st.noalias() += w * s * t.transpose();
  };
  auto add_vector = [&](const Vec3& s, const Vec3& t, double w) {
    vectors_st.noalias() += w * s * t.transpose();
  };

  for (int k = system.coupling_begin[body]; k < system.coupling_begin[body + 1]; ++k) {
    const auto [ci, side] = system.body_couplings[k];
    const RigidSystem::Coupling& c = system.couplings[ci];
    const PatchModes& own = c.local[side];
    const PatchModes& other = c.local[1 - side];
    const BodyState& os = state[c.body[1 - side]];
    const double w = c.weight;
    add_point(own.mean, world_point(os, other.mean), w);
    add_vector(own.du, os.rotation * other.du, w * kModeWeightDu);
    add_vector(own.dv, os.rotation * other.dv, w * kModeWeightDv);
    add_vector(own.duv, os.rotation * other.duv, w * kModeWeightDuv);
  }
  for (int k = system.spring_begin[body]; k < system.spring_begin[body + 1]; ++k) {
    const RigidSystem::Spring& s = system.springs[system.body_springs[k]];
    add_point(s.local, s.target, s.weight);
  }
  if (point_weight <= 0.0) return current;

  BodyState next = current;
  const Vec3 source_mean = source_sum / point_weight;
  const Vec3 target_mean = target_sum / point_weight;
  switch (b.kind) {
    case BodyKind::Free: {
      // Centred cross-covariance: sum w (s - s̄)(t - t̄)^T = sum w s t^T - W s̄ t̄^T.
      const Mat3 S = points_st - point_weight * source_mean * target_mean.transpose() + vectors_st;
      next.rotation = horn_rotation(S, current.rotation);
      next.position = target_mean - next.rotation * source_mean;
      break;
    }
    case BodyKind::PinnedPosition: {
      // Rotation about the pinned rest_center, which stays at `position`.
      const Mat3 S = points_st - source_sum * current.position.transpose() + vectors_st;
      next.rotation = horn_rotation(S, current.rotation);
      break;
    }
    case BodyKind::FixedRotation:
      next.position = target_mean - current.rotation * source_mean;
      break;
    case BodyKind::Fixed:
      break;
  }
  return next;
}

void local_sweep(const RigidSystem& system, std::vector<BodyState>& state) {
  for (int b = 0; b < system.n_bodies(); ++b) state[b] = local_match(system, state, b);
}

BodyColoring color_bodies(const RigidSystem& system) {
  const int n = system.n_bodies();
  std::vector<int> color(n, -1);
  std::vector<int> used;  // used[c] == b when colour c is taken by a neighbour of body b
  int n_colors = 0;
  for (int b = 0; b < n; ++b) {
    if (system.bodies[b].kind == BodyKind::Fixed) continue;  // never matched
    for (int k = system.coupling_begin[b]; k < system.coupling_begin[b + 1]; ++k) {
      const auto& c = system.couplings[system.body_couplings[k].first];
      const int other = c.body[1 - system.body_couplings[k].second];
      if (color[other] >= 0) used[color[other]] = b;
    }
    int c = 0;
    while (c < n_colors && used[c] == b) ++c;
    if (c == n_colors) {
      ++n_colors;
      used.push_back(-1);
    }
    color[b] = c;
  }
  BodyColoring groups(n_colors);
  for (int b = 0; b < n; ++b)
    if (color[b] >= 0) groups[color[b]].push_back(b);
  return groups;
}

void colored_sweep(const RigidSystem& system, const BodyColoring& coloring,
                   std::vector<BodyState>& state) {
  for (const std::vector<int>& group : coloring) {
    const int n = int(group.size());
#pragma omp parallel for schedule(static) if (n > 256)
    for (int i = 0; i < n; ++i) state[group[i]] = local_match(system, state, group[i]);
  }
}

}  // namespace primo
