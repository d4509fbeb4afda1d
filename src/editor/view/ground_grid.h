#pragma once
// The ground grid under the model, as the floor of Blender's and Maya's viewports: a square
// of lines in the plane perpendicular to the model's up, at the bottom of its rest bounding
// box (the model stands on it), centred under it. The spacing is a round number (1, 2 or 5
// times a power of ten) with at most 20 cells across the model's size; every tenth line
// (counted from the world origin, so lines sit at round coordinates) is a major line. The
// renderer fades the lines out towards the grid's rim. Geometry only: no GL.

#include <vector>

#include <glm/glm.hpp>

#include "primo/mesh/geometry.h"
#include "primo/scenario/scenario.h"

namespace primo::editor {

struct GroundGrid {
  glm::dvec3 center{0.0};                  // on the ground, under the model's footprint
  glm::dvec3 normal{0.0, 1.0, 0.0};        // the model's up
  glm::dvec3 u{1.0, 0.0, 0.0}, v{0.0, 0.0, 1.0};  // unit world axes along the lines
  double spacing = 1.0;                    // between neighbouring lines
  int half_cells = 10;                     // cells from the centre to the rim, each way
  // The index (in spacings from the world origin) of the line through the centre, along u
  // and along v: line k of u is major when (center_index_u + k) % 10 == 0.
  long long center_index_u = 0, center_index_v = 0;

  double half_size() const { return half_cells * spacing; }
};

// The smallest round step (1, 2 or 5 x 10^k) that cuts `size` into at most 20 cells (so 8 to
// 20 of them); 1 for a size that is zero or not finite.
double round_grid_spacing(double size);

// The grid under `points` (the rest shape) standing on the plane perpendicular to `up`. The
// plane lies a thousandth of the model's size below its lowest point, so that a flat base
// does not flicker against the lines. The grid reaches at least the model's size from its
// centre, and twice as far as the farthest corner of the footprint, so that the footprint
// stays inside the part that has not faded.
GroundGrid make_ground_grid(const std::vector<Vec3>& points, const ModelOrientation& orientation);

struct GridLine {
  glm::dvec3 a, b;
  bool major = false;
};
// Every line of the grid, first those along v (one per u position), then those along u.
std::vector<GridLine> grid_lines(const GroundGrid& grid);

}  // namespace primo::editor
