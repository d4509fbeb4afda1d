// The engine against the reference minima shipped with the specification
// (../shared/spec/examples): energy to 1e-6 relative, vertices to 1e-5 of the bounding-box
// diagonal, using the same path as `primo deform` (scenario -> mesh -> resolve -> solve).

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "primo/solve/deformer.h"
#include "primo/mesh/geometry.h"
#include "primo/io/mesh_io.h"
#include "primo/scenario/scenario.h"
#include "support/test_support.h"

using namespace primo;

namespace {

struct Reference {
  const char* scenario;
  const char* expected_mesh;
  double energy;
};

class ReferenceExample : public ::testing::TestWithParam<Reference> {};

struct Solved {
  Mesh mesh;
  Deformer deformer;
  SolveReport report;
};

Solved solve_scenario(const std::string& path, SolveMethod method) {
  const Scenario scenario = load_scenario(path);
  Mesh mesh = load_mesh(scenario.mesh_path);
  const ResolvedScenario resolved = resolve_scenario(scenario, mesh);
  Deformer deformer(mesh, resolved.prisms, resolved.handles, resolved.forces);
  SolveOptions options;
  options.method = method;
  options.tolerance = 1e-12;
  options.max_iterations = method == SolveMethod::Local ? 200000 : 200;
  const SolveReport report = deformer.solve(options);
  return {std::move(mesh), std::move(deformer), report};
}

}  // namespace

TEST_P(ReferenceExample, GlobalSolverReachesTheReferenceMinimum) {
  const Reference ref = GetParam();
  const std::string path = test::shared_path(std::string("spec/examples/") + ref.scenario);
  if (!test::exists(path)) GTEST_SKIP() << "skipped: " << path << " is not present";
  const Solved solved = solve_scenario(path, SolveMethod::Global);
  const Mesh& mesh = solved.mesh;
  const SolveReport& report = solved.report;
  std::cout << "[ metric   ] " << ref.scenario << ": " << report.iterations << " iterations, E = "
            << report.energy << " (reference " << ref.energy << ")\n";
  EXPECT_TRUE(report.converged);
  EXPECT_NEAR(report.energy, ref.energy, 1e-6 * ref.energy);

  const Mesh expected = load_mesh(test::shared_path(std::string("spec/examples/") + ref.expected_mesh));
  ASSERT_EQ(expected.n_vertices(), mesh.n_vertices());
  const double tolerance = 1e-5 * bounding_box_diagonal(mesh);
  const std::vector<Vec3> p = solved.deformer.vertex_positions();
  double worst = 0.0;
  for (auto v : expected.vertices()) worst = std::max(worst, (p[v.idx()] - expected.point(v)).norm());
  EXPECT_LT(worst, tolerance);
}

TEST_P(ReferenceExample, LocalSweepsReachTheSameMinimum) {
  const Reference ref = GetParam();
  const std::string path = test::shared_path(std::string("spec/examples/") + ref.scenario);
  if (!test::exists(path)) GTEST_SKIP() << "skipped: " << path << " is not present";
  const SolveReport report = solve_scenario(path, SolveMethod::Local).report;
  std::cout << "[ metric   ] " << ref.scenario << ": " << report.iterations << " local sweeps\n";
  EXPECT_NEAR(report.energy, ref.energy, 1e-5 * ref.energy);
}

INSTANTIATE_TEST_SUITE_P(
    Spec, ReferenceExample,
    ::testing::Values(Reference{"cylinder-small-bend-45.json", "cylinder-small-bend-45.expected.obj",
                                0.008368710955476165},
                      Reference{"hexsphere-orientation.json", "hexsphere-orientation.expected.obj",
                                0.1816661755903986}),
    [](const ::testing::TestParamInfo<Reference>& info) {
      return info.index == 0 ? std::string("CylinderSmallBend45") : std::string("HexsphereOrientation");
    });
