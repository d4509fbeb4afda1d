// The hierarchical solver: its clusters, and its results against the flat global solver.

#include "primo/solve/hierarchical_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>
#include <numeric>
#include <tuple>
#include <random>
#include <set>

#include "bench/reach_pose.h"
#include "primo/solve/deformer.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::faces_where;

namespace {

struct PosedMesh {
  Mesh mesh;
  std::vector<Handle> handles;
};

// A cylinder (2,400 quads by default) bent 90 degrees between its fixed bottom band and its
// top band.
PosedMesh bent_cylinder(int around = 40, int rings = 60) {
  const test::BentCylinder c = test::bent_cylinder(around, rings, 90.0);
  return {c.mesh, c.handles};
}

// Spot (assets/meshes): feet fixed, head moved by a position-only handle.
PosedMesh posed_spot() {
  PosedMesh s;
  s.mesh = load_mesh(test::source_path("assets/meshes/spot_quadrangulated.obj"));
  Handle feet{"feet", faces_where(s.mesh, [](const Vec3& p) { return p.y() < -0.6; }), Fix::All, {}};
  Handle head{"head", faces_where(s.mesh, [](const Vec3& p) { return (p - Vec3(0, 0.2, 0.95)).norm() < 0.2; }),
              Fix::Position, {}};
  head.transform.translation = Vec3(0.25, 0.2, -0.05);
  s.handles = {feet, head};
  return s;
}

SolveOptions hierarchical(int max_cycles, double tolerance, int coarsest_max_bodies = 150) {
  SolveOptions o;
  o.method = SolveMethod::Hierarchical;
  o.max_iterations = max_cycles;
  o.tolerance = tolerance;
  // The default coarsest size would leave small test meshes with one coarse level; 150 gives
  // several, so that intermediate levels are exercised too.
  o.hierarchical.hierarchy.coarsest_max_bodies = coarsest_max_bodies;
  return o;
}

std::vector<Vec3> rest_points(const Mesh& mesh) {
  std::vector<Vec3> p;
  for (auto v : mesh.vertices()) p.push_back(mesh.point(v));
  return p;
}

void expect_close_to_flat(const PosedMesh& s, const char* name, int coarsest_max_bodies) {
  Deformer flat(s.mesh, PrismParameters{}, s.handles);
  SolveOptions g;
  g.tolerance = 1e-10;
  const SolveReport rg = flat.solve(g);
  ASSERT_TRUE(rg.converged);
  Deformer hier(s.mesh, PrismParameters{}, s.handles);
  const SolveReport rh = hier.solve(hierarchical(400, 1e-7, coarsest_max_bodies));
  const double diagonal = bounding_box_diagonal(s.mesh);
  const double position_error =
      largest_point_distance(hier.vertex_positions(), flat.vertex_positions()) / diagonal;
  std::cout << "[ metric   ] " << name << ": hierarchical " << rh.iterations << " cycles ("
            << hier.hierarchical_solver()->levels() << " levels), energy " << rh.energy
            << " vs flat " << rg.energy << " (" << 100 * (rh.energy / rg.energy - 1)
            << "%), max vertex difference " << 100 * position_error << "% of the diagonal\n";
  EXPECT_LT(std::abs(rh.energy / rg.energy - 1), 0.01);
  EXPECT_LT(position_error, 0.005);
  double previous = rh.initial_energy;
  for (double e : rh.energies) {
    EXPECT_LE(e, previous * (1 + 1e-12));
    previous = e;
  }
}

}  // namespace

TEST(ClusterHierarchy, HandlesStayWholeAndLevelsShrink) {
  const PosedMesh s = bent_cylinder();
  Deformer d(s.mesh, PrismParameters{}, s.handles);
  HierarchyOptions options;
  options.coarsest_max_bodies = 100;
  const ClusterHierarchy h = build_cluster_hierarchy(d.system(), options);
  ASSERT_GE(h.coarse_levels(), 2);
  int previous = d.system().n_bodies();
  for (int l = 0; l < h.coarse_levels(); ++l) {
    EXPECT_LT(h.cluster_count[l] * 4, previous) << "level " << l;  // about 8x per level
    previous = h.cluster_count[l];
    // A handle body (bodies 0 and 1) is alone in its cluster.
    for (int handle = 0; handle < 2; ++handle) {
      for (int b = 0; b < d.system().n_bodies(); ++b) {
        if (b != handle) {
          EXPECT_NE(h.cluster_of[l][b], h.cluster_of[l][handle]);
        }
      }
    }
    // Every cluster is non-empty and of bounded size.
    std::vector<int> size(h.cluster_count[l], 0);
    for (int c : h.cluster_of[l]) ++size[c];
    for (int c = 0; c < h.cluster_count[l]; ++c) EXPECT_GT(size[c], 0);
  }
  EXPECT_LE(previous, 100);
}

TEST(ClusterHierarchy, EachLevelAggregatesTheGraphTheFineCouplingsMakeOfItsNodes) {
  // The hierarchy builds a coarse level's graph from the level before it; by definition it
  // is the graph of the fine couplings between the nodes (clusters) of that level: each level
  // rebuilt so, with the nodes' face-weighted centres, must aggregate the same way.
  const PosedMesh s = bent_cylinder();
  Deformer d(s.mesh, PrismParameters{}, s.handles);
  const RigidSystem& fine = d.system();
  HierarchyOptions options;
  options.coarsest_max_bodies = 20;
  const ClusterHierarchy h = build_cluster_hierarchy(fine, options);
  ASSERT_GE(h.coarse_levels(), 3);
  const int n_fine = fine.n_bodies();
  std::vector<int> node_of(static_cast<size_t>(n_fine));
  std::iota(node_of.begin(), node_of.end(), 0);
  int n_nodes = n_fine;
  for (int l = 0; l < h.coarse_levels(); ++l) {
    std::vector<Vec3> position(static_cast<size_t>(n_nodes), Vec3::Zero());
    std::vector<double> weight(static_cast<size_t>(n_nodes), 0.0);
    std::vector<bool> locked(static_cast<size_t>(n_nodes), false);
    for (int b = 0; b < n_fine; ++b) {
      const double w = double(fine.bodies[size_t(b)].faces.size());
      position[size_t(node_of[size_t(b)])] += w * fine.bodies[size_t(b)].rest_center;
      weight[size_t(node_of[size_t(b)])] += w;
      if (fine.bodies[size_t(b)].kind != BodyKind::Free) locked[size_t(node_of[size_t(b)])] = true;
    }
    for (int v = 0; v < n_nodes; ++v) position[size_t(v)] /= weight[size_t(v)];
    std::vector<std::set<int>> neighbours(static_cast<size_t>(n_nodes));
    for (const RigidSystem::Coupling& c : fine.couplings) {
      const int a = node_of[size_t(c.body[0])], b = node_of[size_t(c.body[1])];
      if (a == b) continue;
      neighbours[size_t(a)].insert(b);
      neighbours[size_t(b)].insert(a);
    }
    Groups adjacency;
    adjacency.begin.push_back(0);
    for (const std::set<int>& list : neighbours) {
      adjacency.items.insert(adjacency.items.end(), list.begin(), list.end());
      adjacency.begin.push_back(int(adjacency.items.size()));
    }
    const std::vector<int> aggregate =
        aggregate_nodes(adjacency, position, locked, options.cluster_size);
    for (int b = 0; b < n_fine; ++b) node_of[size_t(b)] = aggregate[size_t(node_of[size_t(b)])];
    ASSERT_EQ(node_of, h.cluster_of[size_t(l)]) << "level " << l + 1;
    n_nodes = h.cluster_count[size_t(l)];
  }
}

TEST(ClusterHierarchy, AggregatesAreConnectedAndCompact) {
  // A 30x30 grid graph: aggregates of 8 must be connected and no wider than a few cells.
  const int n = 30;
  std::vector<std::vector<int>> adjacency(n * n);
  std::vector<Vec3> position(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v = j * n + i;
      position[v] = Vec3(i, j, 0);
      if (i + 1 < n) adjacency[v].push_back(v + 1), adjacency[v + 1].push_back(v);
      if (j + 1 < n) adjacency[v].push_back(v + n), adjacency[v + n].push_back(v);
    }
  for (auto& list : adjacency) std::sort(list.begin(), list.end());
  Groups rows;  // the same lists as compressed rows
  rows.begin.push_back(0);
  for (const auto& list : adjacency) {
    rows.items.insert(rows.items.end(), list.begin(), list.end());
    rows.begin.push_back(int(rows.items.size()));
  }
  const std::vector<int> agg = aggregate_nodes(rows, position, std::vector<bool>(n * n, false), 8);
  const int count = *std::max_element(agg.begin(), agg.end()) + 1;
  EXPECT_GT(count, n * n / 16);
  EXPECT_LT(count, n * n / 4);
  for (int a = 0; a < count; ++a) {
    std::vector<int> members;
    for (int v = 0; v < n * n; ++v)
      if (agg[v] == a) members.push_back(v);
    // Connected: a flood fill inside the aggregate reaches every member.
    std::set<int> seen{members[0]};
    std::vector<int> stack{members[0]};
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int w : adjacency[v])
        if (agg[w] == a && seen.insert(w).second) stack.push_back(w);
    }
    EXPECT_EQ(seen.size(), members.size()) << "aggregate " << a;
    double extent = 0;
    for (int v : members)
      for (int w : members) extent = std::max(extent, (position[v] - position[w]).norm());
    EXPECT_LT(extent, 7.0) << "aggregate " << a;
  }
}

TEST(SweepPlan, PartsOfAColourDoNotTouchAndCoverEveryMovableBody) {
  const PosedMesh s = bent_cylinder();
  Deformer d(s.mesh, PrismParameters{}, s.handles);
  SweepPlan plan = plan_sweep(d.system());
  // 2,400 faces is below the size for parts: a single serial list.
  EXPECT_EQ(plan.parts.size(), 1u);
  const Mesh big = make_cylinder(0.25, 2.0, 80, 120, FaceShape::Quads);  // 9,600 bodies
  Deformer db(big, PrismParameters{}, {});
  const RigidSystem& sys = db.system();
  plan = plan_sweep(sys);
  ASSERT_EQ(plan.parts.size(), 4u) << "about 2,000 bodies a part";
  std::vector<int> part_of(sys.n_bodies(), -1), colour_of(plan.parts.size(), -1);
  size_t bodies = 0;
  for (size_t p = 0; p < plan.parts.size(); ++p) {
    bodies += plan.parts[p].size();
    EXPECT_TRUE(std::is_sorted(plan.parts[p].begin(), plan.parts[p].end()));
    for (int b : plan.parts[p]) {
      EXPECT_EQ(part_of[b], -1) << "body " << b << " in two parts";
      part_of[b] = int(p);
    }
  }
  EXPECT_EQ(bodies, size_t(sys.n_bodies()));
  for (size_t c = 0; c < plan.colours.size(); ++c)
    for (int p : plan.colours[c]) colour_of[p] = int(c);
  EXPECT_LE(plan.colours.size(), 3u) << "a tube cut in four rings needs two colours";
  for (const auto& c : sys.couplings) {
    const int p0 = part_of[c.body[0]], p1 = part_of[c.body[1]];
    if (p0 != p1) {
      EXPECT_NE(colour_of[p0], colour_of[p1]) << "coupled parts of one colour";
    }
  }
  // Not parallel: one part.
  EXPECT_EQ(plan_sweep(sys, false).parts.size(), 1u);
}

TEST(HierarchicalSolver, MatchesTheFlatSolverOnABentCylinder) {
  expect_close_to_flat(bent_cylinder(), "cylinder bend 90, 2400 quads",
                       HierarchyOptions{}.coarsest_max_bodies);
}

TEST(HierarchicalSolver, MatchesTheFlatSolverOnARealMesh) {
  expect_close_to_flat(posed_spot(), "spot, 2928 quads", 150);
}

TEST(HierarchicalSolver, DraggingBackRestoresTheInput) {
  const PosedMesh s = bent_cylinder();
  Deformer d(s.mesh, PrismParameters{}, s.handles);
  d.solve(hierarchical(50, 1e-8));
  const std::vector<Vec3> rest = rest_points(s.mesh);
  const double diagonal = bounding_box_diagonal(s.mesh);
  ASSERT_GT(largest_point_distance(d.vertex_positions(), rest), 0.1 * diagonal);
  d.set_handle_transform(1, RigidTransform::identity());
  const SolveReport back = d.solve(hierarchical(500, 1e-12));
  std::cout << "[ metric   ] hierarchical drag back: " << back.iterations << " cycles\n";
  EXPECT_LT(largest_point_distance(d.vertex_positions(), rest), 1e-6 * diagonal);
}

TEST(HierarchicalSolver, RecoversFromACollapse) {
  const Mesh mesh = make_cylinder(0.3, 1.0, 24, 16, FaceShape::Quads);
  const int n = int(mesh.n_faces());
  Deformer d(mesh, PrismParameters{}, {Handle{"a", {0}, Fix::All, {}}, Handle{"b", {n - 13}, Fix::All, {}}});
  std::mt19937 rng(2);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const FaceGeometry g = compute_face_geometry(mesh);
  std::vector<RigidTransform> motions(n);
  for (int f = 0; f < n; ++f) {
    const Vec3 axis = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    motions[f].rotation = Eigen::AngleAxisd(M_PI / 2 * uniform(rng), axis).toRotationMatrix();
    motions[f].translation = Vec3(0.1, 0.5, 0) - motions[f].rotation * g.centroid[f];
  }
  d.set_face_motions(motions);
  SolveOptions o = hierarchical(3000, 1e-13);
  o.hierarchical.hierarchy.coarsest_max_bodies = 60;
  const SolveReport r = d.solve(o);
  const double error =
      largest_point_distance(d.vertex_positions(), rest_points(mesh)) / bounding_box_diagonal(mesh);
  std::cout << "[ metric   ] hierarchical collapse recovery: " << r.iterations << " cycles, max error "
            << error << " of the diagonal\n";
  EXPECT_LT(error, 1e-4);
}

// The coarsest level holds one coupling per pair of neighbouring clusters (coupling_moments.h):
// its energy under any motions of the clusters must be the fine energy of the fine bodies
// moved with them, less the joints inside the clusters (which no cluster motion changes).
// With one coarse level its couplings come from the fine ones; with several, from the level
// next finer, which writes them as it is restricted.
TEST(HierarchicalSolver, TheCoarsestLevelHasTheEnergyOfTheFineBodiesItMoves) {
  const PosedMesh s = posed_spot();
  for (const int coarsest_max_bodies : {HierarchyOptions{}.coarsest_max_bodies, 60}) {
    Deformer d(s.mesh, PrismParameters{}, s.handles);
    d.solve(hierarchical(3, 0.0, coarsest_max_bodies));  // a state that is not the minimum
    const RigidSystem& fine = d.system();
    HierarchicalOptions options;
    options.hierarchy.coarsest_max_bodies = coarsest_max_bodies;
    HierarchicalSolver solver(fine, options);
    const int coarsest = solver.levels() - 1;
    if (coarsest_max_bodies == 60)
      ASSERT_GE(solver.levels(), 3);
    else
      ASSERT_EQ(solver.levels(), 2);
    const std::vector<BodyState> state = d.body_states();
    solver.prepare(state);
    const RigidSystem& coarse = solver.system(coarsest);
    std::vector<int> cluster(size_t(fine.n_bodies()));
    for (int b = 0; b < fine.n_bodies(); ++b)
      cluster[size_t(b)] = coarse.face_body[size_t(fine.bodies[size_t(b)].faces[0])];
    double inside = 0.0;
    for (const RigidSystem::Coupling& c : fine.couplings)
      if (cluster[size_t(c.body[0])] == cluster[size_t(c.body[1])])
        inside += fine.coupling_energy(c, state[size_t(c.body[0])], state[size_t(c.body[1])]);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    for (int trial = 0; trial < 4; ++trial) {
      // Trial 0: every cluster where it is; then random turns and shifts of every free one.
      std::vector<BodyState> correction(size_t(coarse.n_bodies()));
      for (int c = 0; c < coarse.n_bodies(); ++c) {
        const RigidSystem::Body& body = coarse.bodies[size_t(c)];
        const bool moved = trial > 0 && body.kind == BodyKind::Free;
        correction[size_t(c)] = {
            moved ? rotation_from_vector(Vec3(u(rng), u(rng), u(rng))) : Mat3::Identity(),
            body.rest_center + (moved ? Vec3(u(rng), u(rng), u(rng)) : Vec3::Zero())};
      }
      std::vector<BodyState> moved = state;
      for (int b = 0; b < fine.n_bodies(); ++b) {
        const int c = cluster[size_t(b)];
        const BodyState& k = correction[size_t(c)];
        BodyState& m = moved[size_t(b)];
        m.position = k.rotation * (m.position - coarse.bodies[size_t(c)].rest_center) + k.position;
        m.rotation = k.rotation * m.rotation;
      }
      const double expected = fine.energy(moved) - inside;
      EXPECT_NEAR(coarse.energy(correction), expected, 1e-9 * fine.energy(moved))
          << solver.levels() << " levels, trial " << trial;
    }
    // Fewer couplings than the fine joints crossing the clusters' borders: one per pair.
    std::set<std::pair<int, int>> pairs;
    for (const RigidSystem::Coupling& c : fine.couplings) {
      const int a = cluster[size_t(c.body[0])], b = cluster[size_t(c.body[1])];
      if (a != b) pairs.insert({std::min(a, b), std::max(a, b)});
    }
    EXPECT_EQ(coarse.couplings.size(), pairs.size());
  }
}

// Accelerated cycles combine the states their own cycles left: an iteration of another
// method in between (the Python module's solve() takes a method per call) starts their
// history again, as a state set from outside does. (The two then differ only in the energy they know: with it, a
// proposal is kept when it lies below the energy before its cycle, without it below the
// cycle's; about 1e-7 of the diagonal here after three cycles, 2e-5 when the accelerated
// cycles took the local sweep's result for their own.)
TEST(HierarchicalSolver, AnotherMethodsIterationRestartsTheAcceleration) {
  const PosedMesh s = posed_spot();
  Deformer a(s.mesh, PrismParameters{}, s.handles), b(s.mesh, PrismParameters{}, s.handles);
  SolveOptions local;
  local.method = SolveMethod::Local;
  local.max_iterations = 1;
  for (Deformer* d : {&a, &b}) {
    d->solve(hierarchical(6, 0.0));
    d->solve(local);
  }
  b.set_face_motions(b.face_motions());  // the same state, set from outside
  for (Deformer* d : {&a, &b}) d->solve(hierarchical(3, 0.0));
  EXPECT_LT(largest_point_distance(a.vertex_positions(), b.vertex_positions()),
            1e-6 * bounding_box_diagonal(s.mesh));
}

TEST(HierarchicalSolver, AConvergedStateCostsNothing) {
  const PosedMesh s = bent_cylinder();
  Deformer d(s.mesh, PrismParameters{}, s.handles);
  ASSERT_TRUE(d.solve(hierarchical(2000, 1e-6)).converged);
  const SolveReport again = d.solve(hierarchical(2000, 1e-6));
  EXPECT_EQ(again.iterations, 0);
  EXPECT_TRUE(again.converged);
  // A change of target starts it again.
  d.set_handle_transform(1, make_rigid_transform(Vec3(1.0, -0.6, 0), Vec3::UnitZ(), -80.0, Vec3(0, 2, 0)));
  EXPECT_GT(d.solve(hierarchical(5, 1e-6)).iterations, 0);
}

TEST(HierarchicalSolver, PreparedAtRestTheFirstCycleReusesTheCoarseFactor) {
  // New handles not moved yet: a solve returns at once, before the hierarchy is built.
  // prepare() builds it then, with a coarse factor of the rest state, so the first cycle of
  // the drag makes none; the state is untouched and the minimum is the same.
  const PosedMesh s = bent_cylinder();
  std::vector<Handle> at_rest = s.handles;
  for (Handle& h : at_rest) h.transform = RigidTransform{};
  Deformer prepared(s.mesh, PrismParameters{}, at_rest), lazy(s.mesh, PrismParameters{}, at_rest);
  SolveOptions o = hierarchical(1, 1e-9);
  EXPECT_EQ(prepared.solve(o).iterations, 0);
  EXPECT_EQ(prepared.hierarchical_solver(), nullptr);
  const std::vector<BodyState> before = prepared.body_states();
  prepared.prepare(o);
  ASSERT_NE(prepared.hierarchical_solver(), nullptr);
  EXPECT_EQ(prepared.global_solver(), nullptr);
  EXPECT_EQ(prepared.hierarchical_solver()->coarse_solver()->timings().factorizations, 1);
  EXPECT_EQ(test::max_difference(prepared.body_states(), before), 0.0);

  // The first frame of a drag: a tenth of the way.
  for (int h = 0; h < int(s.handles.size()); ++h) {
    const RigidTransform& to = s.handles[h].transform;
    const Eigen::AngleAxisd turn(to.rotation);
    const RigidTransform step{Eigen::AngleAxisd(0.1 * turn.angle(), turn.axis()).toRotationMatrix(),
                              0.1 * to.translation};
    prepared.set_handle_transform(h, step);
    lazy.set_handle_transform(h, step);
  }
  EXPECT_EQ(prepared.solve(o).iterations, 1);
  EXPECT_EQ(lazy.solve(o).iterations, 1);
  EXPECT_EQ(prepared.hierarchical_solver()->coarse_solver()->timings().factorizations, 1);
  EXPECT_EQ(lazy.hierarchical_solver()->coarse_solver()->timings().factorizations, 1);

  // The rest of the drag in one go: the same minimum.
  for (int h = 0; h < int(s.handles.size()); ++h) {
    prepared.set_handle_transform(h, s.handles[h].transform);
    lazy.set_handle_transform(h, s.handles[h].transform);
  }
  o.max_iterations = 2000;
  const SolveReport a = prepared.solve(o), b = lazy.solve(o);
  ASSERT_TRUE(a.converged && b.converged);
  EXPECT_NEAR(a.energy, b.energy, 1e-6 * b.energy);
  EXPECT_LT(largest_point_distance(prepared.vertex_positions(), lazy.vertex_positions()),
            1e-4 * prepared.prisms().bounding_box_diagonal);

  Deformer global(s.mesh, PrismParameters{}, at_rest);
  global.prepare(SolveOptions{});
  EXPECT_NE(global.global_solver(), nullptr);
}

TEST(HierarchicalSolver, VCycleAndWCycleReachTheSameMinimum) {
  // Both cycle shapes, with and without reusing the coarse factorization, are descent methods
  // for the same energy: run to convergence they must agree with the flat solve.
  const PosedMesh s = posed_spot();
  Deformer flat(s.mesh, PrismParameters{}, s.handles);
  SolveOptions g;
  g.tolerance = 1e-10;
  const SolveReport rg = flat.solve(g);
  ASSERT_TRUE(rg.converged);
  const double diagonal = bounding_box_diagonal(s.mesh);
  for (int cycles : {1, 2}) {
    for (int reuse : {0, 8}) {
      SolveOptions o = hierarchical(1500, 1e-9, 150);
      o.hierarchical.newton_krylov_above = 0.0;  // every iteration a cycle
      o.hierarchical.newton_krylov_below = 0.0;
      o.hierarchical.intermediate_cycles = cycles;
      o.hierarchical.coarse_factor_reuse = reuse;
      Deformer d(s.mesh, PrismParameters{}, s.handles);
      const SolveReport r = d.solve(o);
      const double error =
          largest_point_distance(d.vertex_positions(), flat.vertex_positions()) / diagonal;
      const GlobalSolverTimings& t = d.hierarchical_solver()->coarse_solver()->timings();
      std::cout << "[ metric   ] spot, " << (cycles == 1 ? "V" : "W") << "-cycle, factor reused "
                << reuse << "x: " << r.iterations << " cycles, " << t.factorizations
                << " coarse factorizations, energy " << 100 * (r.energy / rg.energy - 1)
                << "% off, vertices " << error << " of the diagonal\n";
      ASSERT_GE(d.hierarchical_solver()->levels(), 3);
      EXPECT_LT(std::abs(r.energy / rg.energy - 1), 1e-4);
      EXPECT_LT(error, 1e-3);
      if (reuse > 0) {
        EXPECT_LT(t.factorizations * 2, r.iterations * cycles);
      } else {
        EXPECT_GE(t.factorizations, r.iterations);
      }
      double previous = r.initial_energy;
      for (double e : r.energies) {
        EXPECT_LE(e, previous * (1 + 1e-12));
        previous = e;
      }
    }
  }
}

TEST(GlobalSolver, ReusedFactorizationsStillDescendToTheMinimum) {
  const PosedMesh s = bent_cylinder(16, 24);
  Deformer reference(s.mesh, PrismParameters{}, s.handles);
  SolveOptions g;
  g.tolerance = 1e-12;
  g.max_iterations = 200;
  const SolveReport rg = reference.solve(g);
  ASSERT_TRUE(rg.converged);

  Deformer d(s.mesh, PrismParameters{}, s.handles);
  std::vector<BodyState> state = d.body_states();
  GlobalSolver solver(d.system());
  double energy = d.system().energy(state);
  int reused = 0, steps = 0;
  for (; steps < 400 && energy > rg.energy * (1 + 1e-9); ++steps) {
    // A fresh factor every fifth step, as the hierarchical solver does on its coarse level.
    const GlobalStep step = solver.iterate(state, false, /*reuse_factorization=*/steps % 5 != 0);
    ASSERT_TRUE(step.decreased) << "step " << steps;
    EXPECT_LT(step.energy_after, energy);
    energy = step.energy_after;
    reused += step.reused_factorization;
  }
  std::cout << "[ metric   ] cylinder bend (384 quads), Gauss-Newton with reused factors: " << steps << " steps, "
            << reused << " reused, " << solver.timings().factorizations << " factorizations\n";
  EXPECT_LT(energy, rg.energy * (1 + 1e-9));
  EXPECT_GT(reused, steps / 2);
  EXPECT_EQ(solver.timings().factorizations + reused, steps);
}

TEST(HierarchicalSolver, AccelerationCutsCyclesAndKeepsTheMinimum) {
  const PosedMesh s = bent_cylinder();
  int cycles[2];
  std::vector<Vec3> result[2];
  for (int accelerated : {0, 1}) {
    SolveOptions o = hierarchical(3000, 1e-9, 300);
    o.hierarchical.newton_krylov_above = 0.0;  // cycles to the end
    o.hierarchical.newton_krylov_below = 0.0;
    o.hierarchical.acceleration_history = accelerated ? 5 : 0;
    Deformer d(s.mesh, PrismParameters{}, s.handles);
    const SolveReport r = d.solve(o);
    EXPECT_TRUE(r.converged);
    cycles[accelerated] = r.iterations;
    result[accelerated] = d.vertex_positions();
    if (accelerated) {
      EXPECT_GT(d.hierarchical_solver()->timings().accepted_accelerations, 0);
    }
  }
  std::cout << "[ metric   ] cylinder bend 90, 2400 quads: " << cycles[0] << " plain cycles, "
            << cycles[1] << " accelerated\n";
  EXPECT_LT(cycles[1] * 2, cycles[0]);
  // Both at the flat global minimum (plain cycles converge slowly, so the stopping rule leaves
  // them a little further from it).
  Deformer flat(s.mesh, PrismParameters{}, s.handles);
  SolveOptions exact;
  exact.tolerance = 1e-12;
  flat.solve(exact);
  for (int accelerated : {0, 1})
    EXPECT_LT(largest_point_distance(result[accelerated], flat.vertex_positions()),
              1e-4 * bounding_box_diagonal(s.mesh))
        << (accelerated ? "accelerated" : "plain");
}

// Given the energy on entry, an accelerated cycle skips the energy of its plain result when the
// proposal is kept: what it returns must still be the energy of the state it leaves, and below
// the entry energy; and it ends where cycles that compare against the plain result end.
TEST(HierarchicalSolver, CyclesGivenTheEntryEnergyReturnTheTrueEnergy) {
  const PosedMesh s = bent_cylinder();
  Deformer d(s.mesh, PrismParameters{}, s.handles);
  const RigidSystem& sys = d.system();
  HierarchicalOptions options;
  options.hierarchy.coarsest_max_bodies = 300;
  options.newton_krylov_above = 0.0;  // cycles, not Newton-Krylov steps, from rest
  options.newton_krylov_below = 0.0;  // nor near the minimum
  HierarchicalSolver told(sys, options), untold(sys, options);
  std::vector<BodyState> a = d.body_states(), b = a;
  double energy = sys.energy(a);
  for (int cycle = 0; cycle < 60; ++cycle) {
    const double returned = told.cycle(a, energy);
    EXPECT_NEAR(returned, sys.energy(a), 1e-12 * returned) << "cycle " << cycle;
    EXPECT_LT(returned, energy) << "cycle " << cycle;
    energy = returned;
    untold.cycle(b);
  }
  EXPECT_GT(told.timings().accepted_accelerations, 10);
  EXPECT_NEAR(energy, sys.energy(b), 1e-6 * energy);
}

TEST(HierarchicalSolver, SpringsAndOrientationHandlesReachTheFlatMinimum) {
  // Springs and every handle kind pass through three levels of restriction: feet fixed, an
  // orientation-only handle on the head, and a spring pulling the tail region sideways.
  PosedMesh s = posed_spot();
  s.handles[1].fix = Fix::Orientation;
  s.handles[1].transform = make_rigid_transform(Vec3::Zero(), Vec3::UnitY(), 25.0,
                                                Vec3(0, 0.2, 0.95));
  Force pull{"pull", faces_where(s.mesh, [](const Vec3& p) { return p.z() < -0.55 && p.y() > 0.0; }),
             Vec3(0.2, 0.1, 0.0), 50.0};
  ASSERT_FALSE(pull.faces.empty());
  Deformer flat(s.mesh, PrismParameters{}, s.handles, {pull});
  SolveOptions g;
  g.tolerance = 1e-11;
  ASSERT_TRUE(flat.solve(g).converged);
  Deformer hier(s.mesh, PrismParameters{}, s.handles, {pull});
  const SolveReport r = hier.solve(hierarchical(2000, 1e-10, 150));
  ASSERT_GE(hier.hierarchical_solver()->levels(), 3);
  const double diagonal = bounding_box_diagonal(s.mesh);
  const double error =
      largest_point_distance(hier.vertex_positions(), flat.vertex_positions()) / diagonal;
  std::cout << "[ metric   ] spot with a spring and an orientation handle: " << r.iterations
            << " cycles, energy " << 100 * (r.energy / flat.energy() - 1) << "% off, vertices "
            << error << " of the diagonal\n";
  EXPECT_LT(std::abs(r.energy / flat.energy() - 1), 1e-5);
  EXPECT_LT(error, 1e-4);
  // The spring moved the tail: the test would not see a broken spring restriction otherwise.
  Deformer no_spring(s.mesh, PrismParameters{}, s.handles);
  no_spring.solve(g);
  EXPECT_GT(largest_point_distance(no_spring.vertex_positions(), flat.vertex_positions()),
            0.01 * diagonal);
}

// Spot with its head fixed in position and orientation, and the head's pose at a fraction
// t of the drag: moved by the posed offset and turned 30 degrees about x.
struct SpotHeadDrag {
  PosedMesh s = posed_spot();
  Vec3 offset;
  SpotHeadDrag() {
    s.handles[1].fix = Fix::All;
    offset = s.handles[1].transform.translation;
  }
  RigidTransform at(double t) const {
    return make_rigid_transform(t * offset, Vec3::UnitX(), 30.0 * t, Vec3(0, 0.2, 0.95));
  }
};

TEST(HierarchicalSolver, DragsRefreshCoarseFactorsInTheBackgroundReproducibly) {
  // A 40-frame drag of Spot's head, one cycle per frame, done twice: the background
  // factorizations finish at different times, the results may not differ.
  const SpotHeadDrag head;
  PosedMesh s = head.s;
  auto at = [&](double t) { return head.at(t); };
  const SolveOptions frame = hierarchical(1, 0.0, HierarchyOptions{}.coarsest_max_bodies);
  auto drag = [&](Deformer& d) {
    for (int k = 1; k <= 40; ++k) {
      d.set_handle_transform(1, at(k / 40.0));
      d.solve(frame);
    }
    return d.vertex_positions();
  };
  Deformer first(s.mesh, PrismParameters{}, s.handles), second(s.mesh, PrismParameters{}, s.handles);
  const std::vector<Vec3> a = drag(first), b = drag(second);
  EXPECT_EQ(largest_point_distance(a, b), 0.0);
  const GlobalSolverTimings& t = first.hierarchical_solver()->coarse_solver()->timings();
  EXPECT_GT(first.hierarchical_solver()->drag_factor_lag(), 0);
  EXPECT_GE(t.background_factorizations, 2);
  EXPECT_EQ(t.factorizations, 1);  // the first frame's, made before there was a factor

  // Solved on, the dragged state reaches the flat minimum.
  const SolveReport on = first.solve(hierarchical(400, 1e-10, HierarchyOptions{}.coarsest_max_bodies));
  EXPECT_TRUE(on.converged);
  s.handles[1].transform = at(1.0);
  Deformer flat(s.mesh, PrismParameters{}, s.handles);
  SolveOptions exact;
  exact.tolerance = 1e-12;
  const SolveReport rf = flat.solve(exact);
  EXPECT_LT(on.energy, rf.energy * (1 + 1e-6));
  EXPECT_LT(largest_point_distance(first.vertex_positions(), flat.vertex_positions()),
            1e-4 * bounding_box_diagonal(s.mesh));
}

TEST(HierarchicalSolver, TheAutomaticDragFactorLagCountsTheCoarseStepsOfACycle) {
  // A background factorization hides behind whole cycles; the factor is taken over after a
  // number of coarse steps, and a W-cycle makes two coarse steps a cycle on three levels.
  const PosedMesh s = posed_spot();
  Deformer d(s.mesh, PrismParameters{}, s.handles);
  for (int coarsest : {150, 100000})
    for (int cycles : {1, 2, 3})
      for (int iterations : {1, 2}) {
        HierarchicalOptions o;
        o.hierarchy.coarsest_max_bodies = coarsest;
        o.intermediate_cycles = cycles;
        o.coarse_iterations = iterations;
        const HierarchicalSolver h(d.system(), o);
        int expected = iterations;
        for (int l = 3; l <= h.levels(); ++l) expected *= cycles;
        EXPECT_EQ(h.coarse_steps_per_cycle(), expected)
            << h.levels() << " levels, " << cycles << " visits, " << iterations << " iterations";
        if (coarsest == 150) {
          EXPECT_GE(h.levels(), 3);
        } else {
          EXPECT_EQ(h.levels(), 2);
        }
      }
  // The figures it was measured on: the 240k-face drag's 4.9e8-flop factor beside 180,871 fine
  // bodies takes about two cycles, four steps of its W-cycle; the armadillo's 3e8 flops
  // beside 23,893 bodies nine steps of one a cycle. Within [2, 16] whatever the figures.
  EXPECT_EQ(automatic_drag_factor_lag(4.87e8, 180871, 2), 4);
  EXPECT_EQ(automatic_drag_factor_lag(4.87e8, 180871, 1), 2);
  EXPECT_EQ(automatic_drag_factor_lag(3e8, 23893, 1), 9);
  EXPECT_EQ(automatic_drag_factor_lag(1.0, 1000, 4), 2);
  EXPECT_EQ(automatic_drag_factor_lag(1e12, 1000, 1), 16);
}

// A settle that starts near the minimum (after a drag that followed the hand) keeps a coarse
// factor for HierarchicalOptions::settle_factor_reuse steps; one from afar (a jump) for
// coarse_factor_reuse. Either way it ends at the flat minimum.
TEST(HierarchicalSolver, ASettleAfterADragKeepsItsCoarseFactorLongerAndTheMinimum) {
  const SpotHeadDrag head;
  PosedMesh s = head.s;
  auto at = [&](double t) { return head.at(t); };
  auto settle_after_drag = [&](int settle_reuse, int frames) {
    SolveOptions frame = hierarchical(1, 0.0, HierarchyOptions{}.coarsest_max_bodies);
    frame.hierarchical.settle_factor_reuse = settle_reuse;
    frame.hierarchical.coarse_factor_reuse = 0;  // from afar: a fresh factor every step
    frame.hierarchical.newton_krylov_above = 0.0;  // cycles throughout, from afar too
    frame.hierarchical.newton_krylov_below = 0.0;  // and near the minimum
    auto d = std::make_unique<Deformer>(s.mesh, PrismParameters{}, s.handles);
    for (int k = 1; k <= frames; ++k) {
      d->set_handle_transform(1, at(double(k) / frames));
      d->solve(frame);
    }
    const int before = d->hierarchical_solver()->coarse_solver()->timings().factorizations;
    SolveOptions on = frame;
    on.max_iterations = 400;
    on.tolerance = 1e-10;
    const SolveReport r = d->solve(on);
    EXPECT_TRUE(r.converged);
    const int made = d->hierarchical_solver()->coarse_solver()->timings().factorizations - before;
    return std::make_tuple(std::move(d), r.iterations, made);
  };
  s.handles[1].transform = at(1.0);
  Deformer flat(s.mesh, PrismParameters{}, s.handles);
  SolveOptions exact;
  exact.tolerance = 1e-12;
  const SolveReport rf = flat.solve(exact);
  const double diagonal = bounding_box_diagonal(s.mesh);
  const auto [kept, kept_cycles, kept_made] = settle_after_drag(1000, 40);
  const auto [fresh, fresh_cycles, fresh_made] = settle_after_drag(0, 40);
  const auto [jumped, jump_cycles, jump_made] = settle_after_drag(1000, 1);
  std::cout << "[ metric   ] spot, settle after a 40-frame drag: " << kept_cycles << " cycles, "
            << kept_made << " coarse factorizations with the factor kept, " << fresh_cycles
            << " cycles, " << fresh_made << " factorizations with fresh factors; after a jump "
            << jump_cycles << " cycles, " << jump_made << " factorizations\n";
  // The settle's first cycle still counts as the drag's (which factorizes every step here), and
  // a kept factor whose step fails to lower the energy is refreshed: a few, not one a cycle.
  EXPECT_LE(kept_made * 4, fresh_made);
  EXPECT_GE(fresh_made, fresh_cycles - 3);
  EXPECT_GE(jump_made, jump_cycles - 3);  // from afar: coarse_factor_reuse
  for (const Deformer* d : {kept.get(), fresh.get(), jumped.get()}) {
    EXPECT_LT(d->energy(), rf.energy * (1 + 1e-6));
    EXPECT_LT(largest_point_distance(d->vertex_positions(), flat.vertex_positions()),
              1e-4 * diagonal);
  }
}

TEST(HierarchicalSolver, ShowsTheCoarseCorrectionOncePerCycleWithoutChangingTheResult) {
  const PosedMesh s = bent_cylinder();
  Deformer plain(s.mesh, PrismParameters{}, s.handles);
  SolveOptions o = hierarchical(6, 0.0);
  o.path.enabled = false;
  o.hierarchical.newton_krylov_above = 0.0;  // a cycle per iteration
  plain.solve(o);

  Deformer shown(s.mesh, PrismParameters{}, s.handles);
  int calls = 0;
  double moved = 0.0;  // how far an intermediate shape lies from the cycle's start
  std::vector<Vec3> before = shown.vertex_positions();
  o.on_coarse_correction = [&] {
    ++calls;
    const std::vector<Vec3> intermediate = shown.vertex_positions();
    moved = std::max(moved, largest_point_distance(intermediate, before));
    before = intermediate;
  };
  const SolveReport report = shown.solve(o);
  EXPECT_EQ(calls, report.iterations);
  EXPECT_GT(moved, 0.0);
  EXPECT_EQ(largest_point_distance(shown.vertex_positions(), plain.vertex_positions()), 0.0)
      << "reading the state mid-cycle changes nothing";
}

TEST(HierarchicalSolver, ADragOfAThinBladeStaysNearItsMinimum) {
  // The sword (a blade 0.034 thick, 0.23 wide, 0.92 long) held by its two long edges, one
  // turned 30 degrees in the blade's plane and moved along the blade: `bench drag
  // --bbox-handles` on it. A drag's frame has one coarse step; when its reused coarse factor's
  // step was cut by halving, the drag predictor repeated the cut frames' changes and the blade
  // was 35 to 65 times above its minimum at frames 20 to 40 (docs/decisions/0002);
  // now 1.3 times at most.
  const std::string path = test::shared_path("meshes/sword-quad-dominant.obj");
  if (!test::exists(path)) GTEST_SKIP() << "skipped: " << path << " is not present";
  const Mesh mesh = load_mesh(path);
  const bench::ReachPose pose = bench::make_reach_pose(mesh, path);
  auto at = [&](double s) {
    return make_rigid_transform(s * pose.translate, pose.axis, s * pose.angle_deg,
                                pose.top_centroid);
  };
  std::vector<Handle> handles = pose.handles();
  handles[1].transform = at(0.0);

  SolveOptions frame;
  frame.method = SolveMethod::Hierarchical;
  frame.max_iterations = 1;
  frame.tolerance = 0.0;
  SolveOptions converge = frame;
  converge.max_iterations = 5000;
  converge.tolerance = 1e-7;
  converge.path.enabled = true;
  Deformer drag(mesh, PrismParameters{}, handles), reference(mesh, PrismParameters{}, handles);
  drag.prepare(frame);
  constexpr int kFrames = 60;
  for (int k = 1; k <= 40; ++k) {
    drag.set_handle_transform(1, at(double(k) / kFrames));
    const double dragged = drag.solve(frame).energy;
    if (k < 20 || k % 10 != 0) continue;  // at frame 10, 3.2 times (the blade starts to buckle)
    reference.set_handle_transform(1, at(double(k) / kFrames));
    const SolveReport converged = reference.solve(converge);
    ASSERT_TRUE(converged.converged) << "frame " << k;
    EXPECT_LT(dragged, 2.0 * converged.energy) << "frame " << k;
  }
}
