// The editor's solver thread gives what a direct solve gives, takes the latest targets, and
// reports setups it cannot build instead of failing.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "document/edit_state.h"
#include "view/energy_map.h"
#include "primo/solve/deformer.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_generators.h"
#include "solver_worker.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;

namespace {

// A quad tube along y, of radius 0.25, with its bottom band fixed and its top band a Pose handle
// (handles[1]) at rest.
struct Tube {
  std::shared_ptr<const Mesh> mesh;
  std::shared_ptr<const MeshTopology> topology;
  EditState state;
  Tube(double length, int segments, int bands) {
    mesh = std::make_shared<const Mesh>(
        make_cylinder(0.25, length, segments, bands, FaceShape::Quads));
    topology = std::make_shared<const MeshTopology>(build_topology(*mesh));
    state = initial_edit_state(int(mesh->n_faces()));
    const double band = length / bands;
    std::vector<int> bottom, top;
    for (int f = 0; f < topology->n_faces; ++f) {
      const double y = topology->rest_geometry.centroid[f].y();
      if (y < band) bottom.push_back(f);
      if (y > length - band) top.push_back(f);
    }
    add_handle(state, *topology, topology->rest_points, bottom, HandleMode::Fixed);
    add_handle(state, *topology, topology->rest_points, top, HandleMode::Pose);
  }
  std::shared_ptr<SolverProblem> problem() const {
    auto p = std::make_shared<SolverProblem>();
    p->mesh = mesh;
    p->topology = topology;
    p->inputs = deformation_inputs(state);
    return p;
  }
  SolverTargets targets() const {
    SolverTargets t;
    for (const HandleGroup& g : state.handles) t.handles.push_back(g.transform());
    return t;
  }
};

struct Bent : Tube {
  Bent() : Tube(1.0, 10, 12) {}
  std::vector<Vec3> direct() const {
    const DeformationInputs in = deformation_inputs(state);
    Deformer d(*mesh, in.params, in.handles, in.forces);
    SolveOptions o;
    d.solve(o);
    return d.vertex_positions();
  }
};

}  // namespace

TEST(EditorSolverWorker, SettlesWhereADirectSolveEnds) {
  Bent b;
  b.state.handles[1].pose.translate = Vec3(0.3, -0.1, 0.0);
  SolverWorker w;
  w.submit_problem(b.problem());
  ASSERT_TRUE(w.wait_idle(60));
  const SolverStatus s = w.status();
  EXPECT_EQ(s.phase, SolverPhase::Settled);
  ASSERT_TRUE(s.geometry);
  EXPECT_EQ(s.geometry->render_normals.size(), 3 * b.mesh->n_vertices());
  EXPECT_LT(largest_point_distance(s.geometry->positions, b.direct()),
            1e-6 * b.topology->bbox_diagonal);
}

TEST(EditorSolverWorker, LatestTargetsWinAndBackToRestRestoresTheMesh) {
  Bent b;
  SolverWorker w;
  w.submit_problem(b.problem());
  for (int i = 1; i <= 5; ++i) {
    b.state.handles[1].pose.translate = Vec3(0.05 * i, 0.0, 0.02 * i);
    w.submit_targets({{b.state.handles[0].transform(), b.state.handles[1].transform()}, {}});
  }
  ASSERT_TRUE(w.wait_idle(60));
  EXPECT_LT(largest_point_distance(w.status().geometry->positions, b.direct()),
            1e-6 * b.topology->bbox_diagonal);
  w.submit_targets({{RigidTransform{}, RigidTransform{}}, {}});
  ASSERT_TRUE(w.wait_idle(60));
  EXPECT_LT(largest_point_distance(w.status().geometry->positions, b.topology->rest_points),
            1e-6 * b.topology->bbox_diagonal);
}

TEST(EditorSolverWorker, RebuildKeepsThePoseAndEnergyMapSumsToTheEnergy) {
  Bent b;
  // A move below the path's sub-step (PathOptions: 10% of the diagonal), so that the first
  // solve's iterations are all counted in `iterations`, as the rebuild's are.
  b.state.handles[1].pose.translate = Vec3(0.1, 0.0, 0.0);
  SolverWorker w;
  w.set_outputs(true, true);
  w.submit_problem(b.problem());
  ASSERT_TRUE(w.wait_idle(60));
  const SolverStatus first = w.status();
  // The energy map adds up to the total joint energy (no springs here).
  double sum = 0;
  for (int f = 0; f < b.topology->n_faces; ++f)
    sum += first.geometry->face_energy[f] * b.topology->rest_geometry.area[f];
  EXPECT_NEAR(sum, first.energy, 1e-6 * first.energy);
  EXPECT_EQ(first.geometry->prism_corners.size(), 6 * b.topology->face_vertices.size());
  // A change of stiffness rebuilds the prisms; the solve starts from the current pose, so it
  // needs few iterations.
  b.state.prisms.height *= 0.9;
  w.submit_problem(b.problem());
  ASSERT_TRUE(w.wait_idle(60));
  EXPECT_EQ(w.status().phase, SolverPhase::Settled);
  EXPECT_LT(w.status().iterations, first.iterations);
}

TEST(EditorSolverWorker, ABadSetupFailsWithAMessage) {
  Bent b;
  auto p = b.problem();
  p->inputs.params.face_height_factor = {1.0, 2.0};  // wrong size
  SolverWorker w;
  w.submit_problem(p);
  ASSERT_TRUE(w.wait_idle(60));
  EXPECT_EQ(w.status().phase, SolverPhase::Failed);
  EXPECT_FALSE(w.status().error.empty());
  // A good setup afterwards works.
  w.submit_problem(b.problem());
  ASSERT_TRUE(w.wait_idle(60));
  EXPECT_EQ(w.status().phase, SolverPhase::Settled);
}

TEST(EditorEnergyMap, SumsToTheDeformerEnergy) {
  Bent b;
  b.state.handles[1].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Vec3::UnitZ()));
  const DeformationInputs in = deformation_inputs(b.state);
  Deformer d(*b.mesh, in.params, in.handles, in.forces);
  SolveOptions o;
  o.max_iterations = 3;
  d.solve(o);
  // The prisms are in the solver's numbering, the motions in the file's.
  const std::vector<double> e =
      face_joint_energy(d.prisms(), d.order().faces_to_solver(d.face_motions()));
  double sum = 0;
  for (double v : e) sum += v;
  EXPECT_NEAR(sum, d.energy(), 1e-9 * d.energy());
  EXPECT_GT(d.energy(), 0.0);
}

TEST(EditorSolverWorker, NewHandlesAtRestSetUpTheSolverBeforeTheDrag) {
  // Nothing to solve yet, but the solver is set up while the user has not started dragging:
  // the hierarchy and the coarse analysis would otherwise pause the drag's first frame.
  for (SolverMethod method : {SolverMethod::Hierarchical, SolverMethod::Global}) {
    Bent b;
    auto problem = b.problem();
    auto with_method = std::make_shared<SolverProblem>(*problem);
    with_method->spec.method = method;
    SolverWorker w;
    w.submit_problem(with_method);
    ASSERT_TRUE(w.wait_idle(60));
    const SolverStatus s = w.status();
    EXPECT_EQ(s.phase, SolverPhase::Settled);
    EXPECT_EQ(s.iterations, 0);
    EXPECT_TRUE(s.solver_ready) << (method == SolverMethod::Global ? "global" : "hierarchical");
  }
}

TEST(EditorSolverWorker, StopEndsASolveWhereItIsAndTheSameTargetsSolveOn) {
  // A tube of 1,728 quads twisted far: long enough to stop in the middle.
  Tube t(2.0, 36, 48);
  EditState& state = t.state;
  state.handles[1].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(2.8, Vec3::UnitY()));
  auto p = t.problem();
  p->spec.max_iterations = 1;  // no limit applies without set_iteration_limit(true)
  // The format's thin layer (height 1 in mean edge lengths) converges slowly on this twist.
  p->inputs.params.height = 1.0;
  p->inputs.params.height_unit = HeightUnit::MeanEdgeLength;
  SolverWorker w;
  w.set_iteration_limit(false);
  w.submit_problem(p);
  for (int i = 0; i < 2000 && w.status().total_iterations < 1 &&
                  w.status().phase != SolverPhase::Settled;
       ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  w.stop();
  ASSERT_TRUE(w.wait_idle(60));
  const SolverStatus stopped = w.status();
  ASSERT_EQ(stopped.phase, SolverPhase::Stopped);
  EXPECT_TRUE(stopped.stopped_by_user);
  ASSERT_TRUE(stopped.geometry && stopped.geometry->face_motions);  // the shape shown is kept
  // The same targets again: solves on, to convergence (past the limit of 1).
  w.submit_targets(t.targets());
  ASSERT_TRUE(w.wait_idle(120));
  EXPECT_EQ(w.status().phase, SolverPhase::Settled);
  EXPECT_FALSE(w.status().stopped_by_user);
  EXPECT_LE(w.status().energy, stopped.energy);
}

TEST(EditorSolverWorker, AJumpOnTheHierarchicalSolverSettlesWhereADirectSolveEnds) {
  // After a jump the hierarchical solver's settle is Newton-Krylov steps, which the worker
  // interrupts for newer requests (SolveOptions::interrupt): a new pose given during the
  // settle is solved, and the worker ends where a direct solve of it ends.
  Tube t(2.0, 40, 60);
  EditState& state = t.state;
  state.handles[1].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Vec3::UnitZ()));
  state.handles[1].pose.translate = Vec3(0.6, -0.3, 0.0);
  auto p = t.problem();
  p->spec.method = SolverMethod::Hierarchical;
  SolverWorker w;
  w.set_iteration_limit(false);
  w.submit_problem(p);
  for (int i = 0; i < 2000 && w.status().total_iterations < 6; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  // A second jump, while the first settles.
  state.handles[1].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.9, Vec3::UnitZ()));
  w.submit_targets(t.targets());
  ASSERT_TRUE(w.wait_idle(120));
  ASSERT_EQ(w.status().phase, SolverPhase::Settled);

  const DeformationInputs in = deformation_inputs(state);
  Deformer direct(*t.mesh, in.params, in.handles, in.forces);
  SolveOptions o;
  o.method = SolveMethod::Hierarchical;
  ASSERT_TRUE(direct.solve(o).converged);
  EXPECT_GT(direct.hierarchical_solver()->timings().newton_krylov_steps, 0);
  EXPECT_LT(largest_point_distance(w.status().geometry->positions, direct.vertex_positions()),
            1e-4 * t.topology->bbox_diagonal);
}

TEST(EditorSolverWorker, ADragOfSlowFramesShowsPreviewsAndThenTheFullResolution) {
  // Frames at full resolution count as slow from any length here: after the drag's first
  // frame (measured at full resolution) the pictures are previews, and once the hand stops
  // the full resolution catches up to where a direct solve ends.
  Tube t(2.0, 40, 60);
  auto p = t.problem();
  p->spec.method = SolverMethod::Hierarchical;
  SolverWorker w;
  w.set_iteration_limit(false);
  w.set_preview_above(0.0);
  w.submit_problem(p);
  ASSERT_TRUE(w.wait_idle(60));
  EXPECT_FALSE(w.status().previews);
  int previews = 0;
  std::uint64_t last = 0;
  for (int k = 1; k <= 30; ++k) {
    t.state.handles[1].pose.translate = Vec3(0.02 * k, -0.005 * k, 0.0);
    w.submit_targets(t.targets());
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
    const SolverStatus s = w.status();
    if (s.geometry && s.geometry->serial != last) {
      last = s.geometry->serial;
      previews += s.geometry->preview ? 1 : 0;
    }
  }
  EXPECT_GT(previews, 0) << "the drag showed previews";
  ASSERT_TRUE(w.wait_idle(120));
  const SolverStatus settled = w.status();
  ASSERT_EQ(settled.phase, SolverPhase::Settled);
  EXPECT_TRUE(settled.previews);
  ASSERT_TRUE(settled.geometry);
  EXPECT_FALSE(settled.geometry->preview) << "the settled picture is the full resolution";

  const DeformationInputs in = deformation_inputs(t.state);
  Deformer direct(*t.mesh, in.params, in.handles, in.forces);
  SolveOptions o;
  o.method = SolveMethod::Hierarchical;
  ASSERT_TRUE(direct.solve(o).converged);
  EXPECT_LT(largest_point_distance(settled.geometry->positions, direct.vertex_positions()),
            1e-4 * t.topology->bbox_diagonal);
}
