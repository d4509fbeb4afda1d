#pragma once
// A handle's falloff (the editor's soft selection, docs/editor.md) as the springs the solver
// sees. PriMo's handles move their faces rigidly, so a fading handle is a handle plus springs on
// free faces around it, each pulled towards where the handle's motion takes it with a weight w
// in (0, 1]. The springs are the scenario format's zero-rest-length forces, one a face: the
// face's stiffness is k w |F| / sum |F| (the rest areas over the falloff's faces), which makes
// their energy k times the weighted mean of the squared distances, independent of the mesh's
// resolution as a force's is. The editor, a scenario it exports and a replayed session all
// build their springs here, so they solve the same thing.

#include <string>
#include <vector>

#include "primo/mesh/geometry.h"
#include "primo/model/constraints.h"

namespace primo {

struct FalloffSpring {
  int face = -1;
  double weight = 0.0;  // 0 < weight <= 1
  // w |F| / sum |F|: the face's force stiffness is the handle's stiffness k times this.
  double share = 0.0;
  Vec3 rest_centroid = Vec3::Zero();
  bool operator==(const FalloffSpring& o) const {
    return face == o.face && weight == o.weight && share == o.share &&
           rest_centroid == o.rest_centroid;
  }
};

// The springs of `faces` with their `weights` (as many), their shares summed in the order given.
std::vector<FalloffSpring> falloff_springs(const FaceGeometry& rest, const std::vector<int>& faces,
                                           const std::vector<double>& weights);

// How a handle moves its falloff's faces: a spring handle (a force on its own faces) by its
// translation alone, as its own faces are pulled; any other handle by its rigid motion.
RigidTransform falloff_motion(const RigidTransform& handle_motion, const Vec3& translate,
                              bool spring_handle);

// One force a spring, named "<handle> falloff", towards where `motion` takes its rest centroid,
// with stiffness `stiffness` times its share.
std::vector<Force> falloff_forces(const std::string& handle_name,
                                  const std::vector<FalloffSpring>& springs,
                                  const RigidTransform& motion, double stiffness);

}  // namespace primo
