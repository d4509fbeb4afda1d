// The ground grid's geometry: a round spacing with 8 to 20 cells across the model, in the
// plane perpendicular to the model's up at the bottom of its rest bounding box, centred under
// it and covering its footprint, majors every tenth line at round coordinates.

#include <gtest/gtest.h>

#include <cmath>

#include "view/ground_grid.h"
#include "document/model_orientation.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;

namespace {

// 1, 2 or 5 times a power of ten.
bool is_round(double step) {
  const double power = std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  const double mantissa = step / power;
  for (const double m : {1.0, 2.0, 5.0})
    if (std::abs(mantissa - m) < 1e-9) return true;
  return false;
}

std::vector<Vec3> points_of(const Mesh& mesh) {
  std::vector<Vec3> points;
  for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
  return points;
}

glm::dvec3 to_glm(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

ModelOrientation up_front(SignedAxis up, SignedAxis front) { return {up, front}; }

// Every check that does not depend on the model: the plane, the footprint, the majors.
void expect_grid_under(const std::vector<Vec3>& points, const ModelOrientation& o) {
  const GroundGrid g = make_ground_grid(points, o);
  const glm::dvec3 up = axis_vector(o.up);
  EXPECT_EQ(g.normal, up);
  EXPECT_EQ(glm::dot(g.u, up), 0.0);
  EXPECT_EQ(glm::dot(g.v, up), 0.0);
  // The model's size and lowest point along its up.
  Vec3 lo = points.front(), hi = points.front();
  double bottom = 1e300;
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    bottom = std::min(bottom, glm::dot(to_glm(p), up));
  }
  const double size = (hi - lo).maxCoeff();
  EXPECT_TRUE(is_round(g.spacing)) << g.spacing;
  EXPECT_GT(size / g.spacing, 8.0);
  EXPECT_LE(size / g.spacing, 20.0 + 1e-9);

  const std::vector<GridLine> lines = grid_lines(g);
  ASSERT_EQ(lines.size(), size_t(2 * (2 * g.half_cells + 1)));
  for (const GridLine& l : lines)
    for (const glm::dvec3& p : {l.a, l.b}) {
      // Just under the model: a thousandth of its size below its lowest point.
      EXPECT_NEAR(glm::dot(p, up), bottom - 1e-3 * size, 1e-12 * size);
    }
  // Majors are every tenth line, at world coordinates that are multiples of ten spacings.
  int majors = 0;
  for (const GridLine& l : lines) {
    const glm::dvec3 mid = 0.5 * (l.a + l.b);
    const bool along_v = glm::length(glm::cross(l.b - l.a, g.v)) < 1e-12 * size;
    const double c = glm::dot(mid, along_v ? g.u : g.v) / g.spacing;
    EXPECT_NEAR(c, std::round(c), 1e-6) << "lines at round coordinates";
    EXPECT_EQ(l.major, std::llround(c) % 10 == 0) << c;
    majors += l.major;
  }
  EXPECT_GE(majors, 2) << "at least one major line each way";

  // Centred under the footprint (within half a cell), which lies well inside the grid (in the
  // inner half, where the lines have not faded).
  const glm::dvec3 footprint_center = 0.5 * to_glm(lo + hi);
  EXPECT_LE(std::abs(glm::dot(footprint_center - g.center, g.u)), 0.5 * g.spacing + 1e-12);
  EXPECT_LE(std::abs(glm::dot(footprint_center - g.center, g.v)), 0.5 * g.spacing + 1e-12);
  for (const Vec3& p : points) {
    const glm::dvec3 d = to_glm(p) - g.center;
    const double radial = std::hypot(glm::dot(d, g.u), glm::dot(d, g.v));
    EXPECT_LE(radial, 0.5 * g.half_size() + 1e-12);
  }
  EXPECT_GE(g.half_size(), size) << "reaches at least the model's size";
}

}  // namespace

TEST(EditorGroundGrid, SpacingIsRoundWithTenToTwentyCells) {
  EXPECT_DOUBLE_EQ(round_grid_spacing(1.0), 0.05);
  EXPECT_DOUBLE_EQ(round_grid_spacing(2.0), 0.1);
  EXPECT_DOUBLE_EQ(round_grid_spacing(1.718), 0.1);
  EXPECT_DOUBLE_EQ(round_grid_spacing(35.0), 2.0);
  EXPECT_DOUBLE_EQ(round_grid_spacing(0.0), 1.0);
  for (double size = 1e-4; size < 1e5; size *= 1.37) {
    const double s = round_grid_spacing(size);
    EXPECT_TRUE(is_round(s)) << size << " -> " << s;
    EXPECT_GT(size / s, 8.0) << size;
    EXPECT_LE(size / s, 20.0 + 1e-9) << size;
  }
}

TEST(EditorGroundGrid, LiesUnderTheModelForEveryUp) {
  // A 0.2 x 1 x 0.2 bar along y from y = 0, moved away from the origin.
  std::vector<Vec3> bar = points_of(make_bar(0.2, 1.0, 2, 10));
  for (Vec3& p : bar) p += Vec3(3.03, -0.4, 1.5);
  expect_grid_under(bar, ModelOrientation{});
  const GroundGrid g = make_ground_grid(bar, ModelOrientation{});
  EXPECT_NEAR(g.center.y, -0.4 - 1e-3, 1e-12) << "the bar stands on it";
  EXPECT_DOUBLE_EQ(g.spacing, 0.05);
  EXPECT_NEAR(g.center.x, 3.05, 1e-12) << "on a line of the grid near the footprint's centre";
  EXPECT_NEAR(g.center.z, 1.5, 1e-12);
  // Upside down in the file (up -y): it stands on its top end.
  expect_grid_under(bar, up_front({1, -1}, {2, 1}));
  EXPECT_NEAR(make_ground_grid(bar, up_front({1, -1}, {2, 1})).center.y, 0.6 + 1e-3, 1e-12);
  // Lying along x, z up or x up.
  expect_grid_under(bar, up_front({2, 1}, {1, -1}));
  expect_grid_under(bar, up_front({0, 1}, {1, 1}));
  EXPECT_NEAR(make_ground_grid(bar, up_front({0, 1}, {1, 1})).center.x, 2.93 - 1e-3, 1e-12);
}

TEST(EditorGroundGrid, SpotStandsOnIt) {
  const std::string spot = test::source_path("assets/meshes/spot_quadrangulated.obj");
  const std::vector<Vec3> points = points_of(load_mesh(spot));
  expect_grid_under(points, mesh_orientation(spot));
  const GroundGrid g = make_ground_grid(points, mesh_orientation(spot));
  EXPECT_DOUBLE_EQ(g.spacing, 0.1) << "17 cells along Spot's 1.72 length";
  EXPECT_NEAR(g.center.y, -0.737, 0.003);
}
