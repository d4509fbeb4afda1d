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

FactorArray& layer_factors(EditState& state, PaintLayer layer);
const FactorArray& layer_factors(const EditState& state, PaintLayer layer);

// Faces with the same factor value (exactly), for every value other than 1, by ascending value.
struct FactorGroup {
  double value = 1.0;
  std::vector<int> faces;
};
std::vector<FactorGroup> group_factors(const FactorArray& factors);

}  // namespace primo::editor
