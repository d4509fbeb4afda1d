#include "ground_grid.h"

#include <algorithm>
#include <cmath>

#include "document/model_orientation.h"

namespace primo::editor {
namespace {

constexpr double kMaxCellsAcross = 20.0;
constexpr int kMajorEvery = 10;
// How far below the lowest point the plane lies, in model sizes.
constexpr double kBelow = 1e-3;

// m x 10^k, correctly rounded (10^-k is exact, so 0.05 is 5 / 100, not 5 * 0.01).
double round_value(int mantissa, int exponent) {
  return exponent >= 0 ? mantissa * std::pow(10.0, exponent)
                       : mantissa / std::pow(10.0, -exponent);
}

long long floor_mod(long long a, long long b) { return ((a % b) + b) % b; }

}  // namespace

double round_grid_spacing(double size) {
  if (!(size > 0.0) || !std::isfinite(size)) return 1.0;
  const double smallest = size / kMaxCellsAcross;
  // Walk up from a power of ten at or below the smallest allowed step.
  int exponent = int(std::floor(std::log10(smallest))) - 1;
  for (;; ++exponent)
    for (const int mantissa : {1, 2, 5}) {
      const double step = round_value(mantissa, exponent);
      if (size / step <= kMaxCellsAcross * (1.0 + 1e-12)) return step;
    }
}

GroundGrid make_ground_grid(const std::vector<Vec3>& points, const ModelOrientation& orientation) {
  GroundGrid grid;
  const int up_axis = orientation.up.axis;
  const int a = up_axis == 0 ? 1 : 0, b = up_axis == 2 ? 1 : 2;  // the two axes in the plane
  grid.normal = axis_vector(orientation.up);
  grid.u = glm::dvec3(0.0);
  grid.v = glm::dvec3(0.0);
  grid.u[a] = 1.0;
  grid.v[b] = 1.0;
  if (points.empty()) return grid;

  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double size = (hi - lo).maxCoeff();
  grid.spacing = round_grid_spacing(size);
  const double s = grid.spacing;

  // Centred under the footprint, on a line of the grid (lines at round coordinates).
  grid.center_index_u = std::llround(0.5 * (lo[a] + hi[a]) / s);
  grid.center_index_v = std::llround(0.5 * (lo[b] + hi[b]) / s);
  const double cu = double(grid.center_index_u) * s, cv = double(grid.center_index_v) * s;
  // The model's lowest point along its up (the up may point along a negative axis).
  const double bottom = orientation.up.sign > 0 ? lo[up_axis] : -hi[up_axis];
  grid.center = cu * grid.u + cv * grid.v + (bottom - kBelow * size) * grid.normal;

  const double du = std::max(std::abs(lo[a] - cu), std::abs(hi[a] - cu));
  const double dv = std::max(std::abs(lo[b] - cv), std::abs(hi[b] - cv));
  const double reach = std::max(size, 2.0 * std::hypot(du, dv));
  grid.half_cells = std::max(1, int(std::ceil(reach / s - 1e-9)));
  return grid;
}

std::vector<GridLine> grid_lines(const GroundGrid& grid) {
  std::vector<GridLine> lines;
  const int n = grid.half_cells;
  const double h = grid.half_size();
  lines.reserve(size_t(2 * (2 * n + 1)));
  for (int k = -n; k <= n; ++k) {
    const glm::dvec3 at = grid.center + (k * grid.spacing) * grid.u;
    lines.push_back({at - h * grid.v, at + h * grid.v,
                     floor_mod(grid.center_index_u + k, kMajorEvery) == 0});
  }
  for (int k = -n; k <= n; ++k) {
    const glm::dvec3 at = grid.center + (k * grid.spacing) * grid.v;
    lines.push_back({at - h * grid.u, at + h * grid.u,
                     floor_mod(grid.center_index_v + k, kMajorEvery) == 0});
  }
  return lines;
}

}  // namespace primo::editor
