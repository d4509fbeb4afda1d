#pragma once
// The heat map of joint energy: how much each face's joints are stretched or bent.

#include <vector>

#include "primo/model/constraints.h"
#include "primo/model/prism_layer.h"

namespace primo::editor {

// Per face, half the energy of each joint it takes part in (paper Eq. 2: w_ij times the
// squared L2 distance of the two side patches), with the faces moved by `motions` (rest
// coordinates, one per face, as Deformer::face_motions gives them). The values sum to the
// total joint energy.
std::vector<double> face_joint_energy(const PrismLayer& layer,
                                      const std::vector<RigidTransform>& motions);

// A colour-scale maximum for per-face densities: the 98th percentile of `values` (robust to a
// few extreme faces), at least a tiny positive number.
double robust_maximum(const std::vector<float>& values);

}  // namespace primo::editor
