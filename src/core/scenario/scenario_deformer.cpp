#include "primo/scenario/scenario_deformer.h"

namespace primo {

Deformer make_scenario_deformer(const Mesh& mesh, const ResolvedScenario& resolved) {
  Deformer deformer(mesh, resolved.prisms, resolved.handles, resolved.forces);
  if (!resolved.start_motions.empty()) deformer.set_face_motions(resolved.start_motions);
  return deformer;
}

}  // namespace primo
