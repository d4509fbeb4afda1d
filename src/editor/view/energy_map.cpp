#include "energy_map.h"

#include <algorithm>

#include "primo/model/bilinear_inner_product.h"

namespace primo::editor {

std::vector<double> face_joint_energy(const PrismLayer& layer,
                                      const std::vector<RigidTransform>& motions) {
  std::vector<double> energy(layer.n_faces(), 0.0);
  for (const Joint& j : layer.joints) {
    const RigidTransform& a = motions[j.face[0]];
    const RigidTransform& b = motions[j.face[1]];
    const PatchModes p = layer.joint_side(j, 0), q = layer.joint_side(j, 1);
    const double e =
        j.weight * ((a.apply(p.mean) - b.apply(q.mean)).squaredNorm() +
                    kModeWeightDu * (a.rotation * p.du - b.rotation * q.du).squaredNorm() +
                    kModeWeightDv * (a.rotation * p.dv - b.rotation * q.dv).squaredNorm() +
                    kModeWeightDuv * (a.rotation * p.duv - b.rotation * q.duv).squaredNorm());
    energy[j.face[0]] += 0.5 * e;
    energy[j.face[1]] += 0.5 * e;
  }
  return energy;
}

double robust_maximum(const std::vector<float>& values) {
  if (values.empty()) return 1e-30;
  std::vector<float> v(values);
  const size_t k = std::min(v.size() - 1, size_t(0.98 * double(v.size())));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return std::max(double(v[k]), 1e-30);
}

}  // namespace primo::editor
