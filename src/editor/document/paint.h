#pragma once
// Stiffness and width painting: a brush sets the per-face height factor (softer joints where
// it is below 1: the prisms are thinner, so the surface bends more easily there) or the
// per-face width factor (prisms shrunk or grown about their centroids, so the surface shrinks
// or grows locally). The painted arrays become scenario regions grouped by value.

#include <vector>

#include "edit_state.h"

namespace primo::editor {

enum class PaintLayer { Height, Width };

// A copy of `factors` (null: all 1) with `faces` set to `value`. The result is null again
// when every face ends at 1, so an erased layer costs nothing.
FactorArray paint_factors(const FactorArray& factors, int n_faces, const std::vector<int>& faces,
                          double value);

// How a brush's effect fades from its centre (1) to its rim (0): Constant paints the whole disc
// alike, Linear fades evenly, Smooth as (1 - t^2)^2 (Blender's and ZBrush's soft brush).
enum class Falloff { Constant, Linear, Smooth };
double falloff_weight(Falloff falloff, double distance_over_radius);

// A soft dab: each face of `faces` moves from its factor towards `value` by its `weights`
// entry (0 none, 1 all the way). Blended values are rounded to 0.01, so that a soft stroke
// still saves as a few regions (one per distinct value) and not one per face.
FactorArray blend_factors(const FactorArray& factors, int n_faces, const std::vector<int>& faces,
                          const std::vector<double>& weights, double value);

// One pass of smoothing: every face takes the mean of its own factor and those of the faces
// sharing a vertex with it (rounded to 0.01, as soft dabs are), which softens the edges of a
// painted region.
FactorArray smooth_factors(const FactorArray& factors, const MeshTopology& topology);

FactorArray& layer_factors(EditState& state, PaintLayer layer);
const FactorArray& layer_factors(const EditState& state, PaintLayer layer);

// Faces with the same factor value (exactly), for every value other than 1, by ascending value.
struct FactorGroup {
  double value = 1.0;
  std::vector<int> faces;
};
std::vector<FactorGroup> group_factors(const FactorArray& factors);

}  // namespace primo::editor
