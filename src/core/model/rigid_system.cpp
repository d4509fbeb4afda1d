#include "primo/model/rigid_system.h"

#include "primo/util/error.h"
#include "primo/util/parallel.h"

namespace primo {
namespace {

PatchModes relative_to(const PatchModes& m, const Vec3& origin) {
  return {m.mean - origin, m.du, m.dv, m.duv};
}

// Energy of a mode pair already in world coordinates.
double mode_distance2(const PatchModes& a, const PatchModes& b) {
  return (a.mean - b.mean).squaredNorm() + kModeWeightDu * (a.du - b.du).squaredNorm() +
         kModeWeightDv * (a.dv - b.dv).squaredNorm() +
         kModeWeightDuv * (a.duv - b.duv).squaredNorm();
}

PatchModes to_world(const PatchModes& local, const BodyState& s) {
  return {s.rotation * local.mean + s.position, s.rotation * local.du, s.rotation * local.dv,
          s.rotation * local.duv};
}

void add_outer(Mat3& m, const Vec3& a, double w) { m.noalias() += w * a * a.transpose(); }

}  // namespace

void RigidSystem::Coupling::update_cross() {
  const PatchModes& own = local[0];
  const PatchModes& other = local[1];
  cross.noalias() = own.mean * other.mean.transpose();
  cross.noalias() += kModeWeightDu * own.du * other.du.transpose();
  cross.noalias() += kModeWeightDv * own.dv * other.dv.transpose();
  cross.noalias() += kModeWeightDuv * own.duv * other.duv.transpose();
  cross *= weight;
}

double RigidSystem::coupling_energy(const Coupling& c, const BodyState& s0,
                                    const BodyState& s1) const {
  return c.weight * mode_distance2(to_world(c.local[0], s0), to_world(c.local[1], s1));
}

double RigidSystem::energy(const std::vector<BodyState>& state) const {
  auto sum = [&](size_t begin, size_t end) {
    double e = 0.0;
    for (size_t i = begin; i < end; ++i)
      e += coupling_energy(couplings[i], state[couplings[i].body[0]], state[couplings[i].body[1]]);
    return e;
  };
  // Chunks fixed by the size, summed in order: the same bits on any number of threads.
  double e = internal_energy + parallel_sum(couplings.size(), 2 * kParallelGrain, 0.0, sum);
  for (const Spring& s : springs)
    e += spring_energy(s, state[s.body]);
  return e;
}

RigidSystem build_rigid_system(const PrismLayer& layer, const std::vector<int>& face_body,
                               const std::vector<BodyKind>& kinds,
                               const std::vector<FaceSpring>& springs) {
  const int n_faces = layer.n_faces();
  const int n_bodies = int(kinds.size());
  if (int(face_body.size()) != n_faces) throw Error("face_body must have one entry per face");

  RigidSystem sys;
  sys.face_body = face_body;
  sys.bodies.resize(n_bodies);
  std::vector<double> body_area(n_bodies, 0.0);
  for (int b = 0; b < n_bodies; ++b) sys.bodies[b].kind = kinds[b];
  for (int f = 0; f < n_faces; ++f) {
    const int b = face_body[f];
    if (b < 0 || b >= n_bodies) throw Error("face_body entry out of range");
    RigidSystem::Body& body = sys.bodies[b];
    body.faces.push_back(f);
    body.rest_center += layer.face_area[f] * layer.face_centroid[f];
    body_area[b] += layer.face_area[f];
  }
  for (int b = 0; b < n_bodies; ++b) {
    RigidSystem::Body& body = sys.bodies[b];
    if (body.faces.empty()) throw Error("every body needs at least one face");
    body.rest_center /= body_area[b];
  }

  // Projection metric from every side patch of every prism of the body.
  std::vector<PatchModes> sides;  // of one body; kept across bodies, not allocated per body
  for (int b = 0; b < n_bodies; ++b) {
    RigidSystem::Body& body = sys.bodies[b];
    Vec3 sum = Vec3::Zero();
    sides.clear();
    for (int f : body.faces)
      for (int k = 0; k < layer.degree(f); ++k)
        sides.push_back(relative_to(patch_modes(layer.side_patch(f, k)), body.rest_center));
    for (const PatchModes& m : sides) sum += m.mean;
    body.metric_weight = double(sides.size());
    body.metric_mean = sum / body.metric_weight;
    Mat3 vectors = Mat3::Zero();
    for (const PatchModes& m : sides) {
      add_outer(body.metric_centered, m.mean - body.metric_mean, 1.0);
      add_outer(body.metric_pinned, m.mean, 1.0);
      add_outer(vectors, m.du, kModeWeightDu);
      add_outer(vectors, m.dv, kModeWeightDv);
      add_outer(vectors, m.duv, kModeWeightDuv);
    }
    body.metric_centered += vectors;
    body.metric_pinned += vectors;
  }

  sys.couplings.reserve(layer.joints.size());  // at most one per joint (a coupling is 280 bytes)
  for (const Joint& j : layer.joints) {
    const int b0 = face_body[j.face[0]], b1 = face_body[j.face[1]];
    const PatchModes side0 = layer.joint_side(j, 0), side1 = layer.joint_side(j, 1);
    if (b0 == b1) {
      sys.internal_energy += j.weight * mode_distance2(side0, side1);
      continue;
    }
    RigidSystem::Coupling c;
    c.body[0] = b0;
    c.body[1] = b1;
    c.weight = j.weight;
    c.local[0] = relative_to(side0, sys.bodies[b0].rest_center);
    c.local[1] = relative_to(side1, sys.bodies[b1].rest_center);
    c.update_cross();
    sys.couplings.push_back(c);
  }

  index_couplings(sys);
  set_springs(sys, layer, springs);
  return sys;
}

void set_springs(RigidSystem& sys, const PrismLayer& layer,
                 const std::vector<FaceSpring>& springs) {
  sys.springs.clear();
  for (const FaceSpring& s : springs) {
    const int b = sys.face_body[s.face];
    sys.springs.push_back({b, layer.face_centroid[s.face] - sys.bodies[b].rest_center, s.target,
                           s.weight});
  }
  index_springs(sys);
}

void index_couplings(RigidSystem& sys) {
  const int n_bodies = sys.n_bodies();
  sys.coupling_begin.assign(n_bodies + 1, 0);
  for (const auto& c : sys.couplings) {
    ++sys.coupling_begin[c.body[0] + 1];
    ++sys.coupling_begin[c.body[1] + 1];
  }
  for (int b = 0; b < n_bodies; ++b) sys.coupling_begin[b + 1] += sys.coupling_begin[b];
  sys.body_couplings.resize(sys.coupling_begin[n_bodies]);
  std::vector<int> fill(sys.coupling_begin.begin(), sys.coupling_begin.end() - 1);
  for (int i = 0; i < int(sys.couplings.size()); ++i)
    for (int s = 0; s < 2; ++s) sys.body_couplings[fill[sys.couplings[i].body[s]]++] = {i, s};
}

void index_springs(RigidSystem& sys) {
  const int n_bodies = sys.n_bodies();
  sys.spring_begin.assign(n_bodies + 1, 0);
  for (const auto& s : sys.springs) ++sys.spring_begin[s.body + 1];
  for (int b = 0; b < n_bodies; ++b) sys.spring_begin[b + 1] += sys.spring_begin[b];
  sys.body_springs.resize(sys.springs.size());
  std::vector<int> fill(sys.spring_begin.begin(), sys.spring_begin.end() - 1);
  for (int i = 0; i < int(sys.springs.size()); ++i) sys.body_springs[fill[sys.springs[i].body]++] = i;
}

}  // namespace primo
