// End-to-end behaviour of the engine: the global and local solvers on bent cylinders, the
// constraint variants, drag-back, recovery from a collapse (paper Fig. 6), polygon meshes,
// and the width and plate parameters.

#include "primo/solve/deformer.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>
#include <random>

#include "primo/mesh/geometry.h"
#include "primo/solve/local_solver.h"
#include "primo/mesh/mesh_generators.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::bent_cylinder;
using primo::test::BentCylinder;
using primo::test::faces_where;

namespace {

// Vertices all of whose faces belong to `faces`.
std::vector<int> interior_vertices(const Mesh& mesh, const std::vector<int>& faces) {
  std::vector<bool> in(mesh.n_faces(), false);
  for (int f : faces) in[f] = true;
  std::vector<int> result;
  for (auto v : mesh.vertices()) {
    bool all = true;
    for (auto f : v.faces()) all = all && in[f.idx()];
    if (all) result.push_back(v.idx());
  }
  return result;
}

double total_area(const Mesh& mesh) {
  double a = 0.0;
  for (double x : compute_face_geometry(mesh).area) a += x;
  return a;
}

double max_distance(const std::vector<Vec3>& a, const Mesh& mesh) {
  double d = 0.0;
  for (auto v : mesh.vertices()) d = std::max(d, (a[v.idx()] - mesh.point(v)).norm());
  return d;
}

}  // namespace

TEST(Deformer, BendAndTwistInOneStepConvergesMonotonically) {
  BentCylinder c = bent_cylinder(40, 60, 90.0, 180.0);  // 2,400 quads
  Deformer d(c.mesh, PrismParameters{}, c.handles);
  SolveOptions options;
  options.tolerance = 1e-10;
  options.max_iterations = 100;
  const SolveReport r = d.solve(options);
  std::cout << "[ metric   ] bend 90 + twist 180, 2400 quads: " << r.iterations << " iterations ("
            << r.exact_newton_steps << " exact Newton), E = " << r.energy << ", " << r.seconds
            << " s\n";
  RecordProperty("iterations", r.iterations);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_LE(r.iterations, 80);
  double previous = r.initial_energy;
  for (double e : r.energies) {
    EXPECT_LE(e, previous);
    previous = e;
  }
  // Handles are satisfied exactly: vertices inside the top handle sit at their targets.
  const std::vector<Vec3> p = d.vertex_positions();
  for (int v : interior_vertices(c.mesh, c.handles[1].faces))
    EXPECT_LT((p[v] - c.handles[1].transform.apply(c.mesh.point(c.mesh.vertex_handle(v)))).norm(),
              1e-9 * c.diagonal);
  for (int v : interior_vertices(c.mesh, c.handles[0].faces))
    EXPECT_LT((p[v] - c.mesh.point(c.mesh.vertex_handle(v))).norm(), 1e-9 * c.diagonal);
}

TEST(Deformer, ExactHessianAndGaussNewtonReachTheSameMinimum) {
  BentCylinder c = bent_cylinder(16, 24, 90.0, 0.0);
  SolveOptions options;
  options.tolerance = 1e-12;
  options.max_iterations = 500;
  Deformer exact(c.mesh, PrismParameters{}, c.handles);
  const SolveReport re = exact.solve(options);
  options.exact_hessian_below = 0.0;
  Deformer gauss_newton(c.mesh, PrismParameters{}, c.handles);
  const SolveReport rg = gauss_newton.solve(options);
  std::cout << "[ metric   ] bend 90, 384 quads: Gauss-Newton " << rg.iterations
            << " iterations, with exact Hessian " << re.iterations << "\n";
  EXPECT_EQ(rg.exact_newton_steps, 0);
  EXPECT_GT(re.exact_newton_steps, 0);
  EXPECT_LT(re.iterations, rg.iterations);
  EXPECT_NEAR(re.energy, rg.energy, 1e-9 * rg.energy);
}

TEST(Deformer, PositionHandleMovesItsCentroidAndRotatesFreely) {
  BentCylinder c = bent_cylinder(16, 12, 60.0, 0.0, Fix::Position);
  Deformer d(c.mesh, PrismParameters{}, c.handles);
  const SolveReport r = d.solve(SolveOptions{});
  EXPECT_TRUE(r.converged);
  const FaceGeometry g = compute_face_geometry(c.mesh);
  const Vec3 rest = area_weighted_centroid(g, c.handles[1].faces);
  const Vec3 target = c.handles[1].transform.apply(rest);
  const BodyState& top = d.body_states()[1];
  EXPECT_LT((top.position - target).norm(), 1e-12);
  // The orientation was optimized: it is not the prescribed one (the free end straightens).
  EXPECT_GT((top.rotation - c.handles[1].transform.rotation).norm(), 1e-2);
  // ... and it is better than prescribing it.
  Deformer prescribed(c.mesh, PrismParameters{}, bent_cylinder(16, 12, 60.0, 0.0).handles);
  EXPECT_LT(r.energy, prescribed.solve(SolveOptions{}).energy);
}

TEST(Deformer, OrientationHandleKeepsItsRotationAndTranslatesFreely) {
  BentCylinder c = bent_cylinder(16, 12, 60.0, 30.0, Fix::Orientation);
  Deformer d(c.mesh, PrismParameters{}, c.handles);
  const SolveReport r = d.solve(SolveOptions{});
  EXPECT_TRUE(r.converged);
  const BodyState& top = d.body_states()[1];
  EXPECT_LT((top.rotation - c.handles[1].transform.rotation).norm(), 1e-14);
  const Vec3 prescribed = c.handles[1].transform.apply(d.system().bodies[1].rest_center);
  EXPECT_GT((top.position - prescribed).norm(), 1e-3);
}

TEST(Deformer, LocalMatchRecoversAKnownRigidMotionExactly) {
  const Mesh mesh = make_cylinder(0.3, 1.0, 10, 6, FaceShape::Quads);
  Deformer d(mesh, PrismParameters{}, {});
  RigidTransform m;
  m.rotation = Eigen::AngleAxisd(1.1, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  m.translation = Vec3(0.3, -2, 5);
  std::vector<RigidTransform> motions(mesh.n_faces(), m);
  motions[17] = RigidTransform{};  // one prism left at rest
  d.set_face_motions(motions);
  const int body = d.system().face_body[17];
  const BodyState matched = local_match(d.system(), d.body_states(), body);
  EXPECT_LT((matched.rotation - m.rotation).norm(), 1e-12);
  EXPECT_LT((matched.position - m.apply(d.system().bodies[body].rest_center)).norm(), 1e-12);
}

TEST(Deformer, LocalMatchVariantsObeyTheirConstraints) {
  BentCylinder pinned = bent_cylinder(12, 8, 45.0, 0.0, Fix::Position);
  Deformer dp(pinned.mesh, PrismParameters{}, pinned.handles);
  const BodyState before_p = dp.body_states()[1];
  const BodyState after_p = local_match(dp.system(), dp.body_states(), 1);
  EXPECT_EQ(after_p.position, before_p.position);
  EXPECT_GT((after_p.rotation - before_p.rotation).norm(), 1e-3);
  EXPECT_NEAR(after_p.rotation.determinant(), 1.0, 1e-12);

  BentCylinder oriented = bent_cylinder(12, 8, 45.0, 0.0, Fix::Orientation);
  Deformer dr(oriented.mesh, PrismParameters{}, oriented.handles);
  const BodyState before_r = dr.body_states()[1];
  const BodyState after_r = local_match(dr.system(), dr.body_states(), 1);
  EXPECT_EQ(after_r.rotation, before_r.rotation);
  EXPECT_GT((after_r.position - before_r.position).norm(), 1e-3);

  // A fixed handle never moves.
  const BodyState fixed = local_match(dr.system(), dr.body_states(), 0);
  EXPECT_EQ(fixed.rotation, dr.body_states()[0].rotation);
  EXPECT_EQ(fixed.position, dr.body_states()[0].position);
}

TEST(Deformer, LocalSweepsAndGlobalSolverReachTheSameEnergy) {
  BentCylinder c = bent_cylinder(8, 6, 45.0, 20.0);
  Deformer global(c.mesh, PrismParameters{}, c.handles);
  SolveOptions options;
  options.tolerance = 1e-13;
  const SolveReport rg = global.solve(options);
  Deformer local(c.mesh, PrismParameters{}, c.handles);
  options.method = SolveMethod::Local;
  options.max_iterations = 50000;
  options.tolerance = 1e-14;
  const SolveReport rl = local.solve(options);
  std::cout << "[ metric   ] 48 quads: global " << rg.iterations << " iterations, local "
            << rl.iterations << " sweeps\n";
  double previous = rl.initial_energy;
  for (double e : rl.energies) {
    EXPECT_LE(e, previous * (1 + 1e-15));
    previous = e;
  }
  EXPECT_NEAR(rl.energy, rg.energy, 1e-6 * rg.energy);
  EXPECT_LT(max_distance(local.vertex_positions(), global.deformed_mesh(c.mesh)), 1e-5 * c.diagonal);
}

TEST(Deformer, DraggingTheHandleBackRestoresTheInput) {
  BentCylinder c = bent_cylinder(16, 12, 120.0, 90.0);
  Deformer d(c.mesh, PrismParameters{}, c.handles);
  d.solve(SolveOptions{});
  ASSERT_GT(max_distance(d.vertex_positions(), c.mesh), 0.1 * c.diagonal);
  d.set_handle_transform(1, RigidTransform::identity());
  SolveOptions options;
  options.tolerance = 1e-12;
  const SolveReport back = d.solve(options);
  EXPECT_TRUE(back.converged);
  EXPECT_LT(max_distance(d.vertex_positions(), c.mesh), 1e-6 * c.diagonal);
}

namespace {

// Paper Fig. 6: fix two prisms, collapse all others into one point with perturbed
// orientations, and solve. Returns the maximum vertex distance to the rest shape.
double collapse_and_recover(int seed, double max_angle, int* iterations) {
  const Mesh mesh = make_cylinder(0.3, 1.0, 16, 8, FaceShape::Quads);
  const int n = int(mesh.n_faces());
  Handle a{"a", {0}, Fix::All, {}}, b{"b", {n - 9}, Fix::All, {}};
  Deformer d(mesh, PrismParameters{}, {a, b});
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Vec3 point(0.1, 0.5, -0.05);
  const FaceGeometry g = compute_face_geometry(mesh);
  std::vector<RigidTransform> motions(n);
  for (int f = 0; f < n; ++f) {
    const Vec3 axis = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    motions[f].rotation = Eigen::AngleAxisd(max_angle * uniform(rng), axis).toRotationMatrix();
    motions[f].translation = point - motions[f].rotation * g.centroid[f];
  }
  d.set_face_motions(motions);
  SolveOptions options;
  options.max_iterations = 300;
  options.tolerance = 1e-14;
  const SolveReport r = d.solve(options);
  if (iterations) *iterations = r.iterations;
  return max_distance(d.vertex_positions(), mesh) / bounding_box_diagonal(mesh);
}

}  // namespace

TEST(Deformer, RecoversFromACollapseWithOrientationsPerturbedUpTo90Degrees) {
  for (int seed = 1; seed <= 3; ++seed) {
    int iterations = 0;
    const double error = collapse_and_recover(seed, M_PI / 2, &iterations);
    std::cout << "[ metric   ] Fig. 6 collapse, seed " << seed << ": " << iterations
              << " iterations, max vertex error " << error << " of the diagonal\n";
    EXPECT_LT(error, 1e-6) << "seed " << seed;
  }
}

TEST(Deformer, QuadBarBendStaysSymmetric) {
  const Mesh bar = make_bar(0.2, 1.0, 2, 10);
  ASSERT_TRUE(std::all_of(bar.faces().begin(), bar.faces().end(),
                          [](auto f) { return f.valence() == 4; }));
  Handle base{"base", faces_where(bar, [](const Vec3& p) { return p.y() < 0.05; }), Fix::All, {}};
  Handle tip{"tip", faces_where(bar, [](const Vec3& p) { return p.y() > 0.95; }), Fix::All, {}};
  // Bending in the xy plane keeps the mirror symmetry z -> -z of the bar.
  tip.transform = make_rigid_transform(Vec3(0.3, -0.2, 0), Vec3::UnitZ(), -70.0, Vec3(0, 1, 0));
  Deformer d(bar, PrismParameters{}, {base, tip});
  ASSERT_TRUE(d.solve(SolveOptions{}).converged);
  const std::vector<Vec3> p = d.vertex_positions();
  const double diagonal = bounding_box_diagonal(bar);
  int pairs = 0;
  for (auto v : bar.vertices()) {
    const Vec3 mirrored = bar.point(v).cwiseProduct(Vec3(1, 1, -1));
    for (auto w : bar.vertices()) {
      if ((bar.point(w) - mirrored).norm() > 1e-12) continue;
      ++pairs;
      EXPECT_LT((p[w.idx()] - p[v.idx()].cwiseProduct(Vec3(1, 1, -1))).norm(), 1e-7 * diagonal);
    }
  }
  EXPECT_EQ(pairs, int(bar.n_vertices()));
  EXPECT_GT(max_distance(p, bar), 0.1);
}

TEST(Deformer, TriangleAndPolygonMeshesBendAlike) {
  // The same bend on quads and on triangulated quads gives nearly the same shape.
  BentCylinder quads = bent_cylinder(24, 24, 90.0, 0.0);
  BentCylinder tris = bent_cylinder(24, 24, 90.0, 0.0, Fix::All, FaceShape::Triangles);
  Deformer dq(quads.mesh, PrismParameters{}, quads.handles);
  Deformer dt(tris.mesh, PrismParameters{}, tris.handles);
  ASSERT_TRUE(dq.solve(SolveOptions{}).converged);
  ASSERT_TRUE(dt.solve(SolveOptions{}).converged);
  const std::vector<Vec3> pq = dq.vertex_positions(), pt = dt.vertex_positions();
  double worst = 0.0;
  for (size_t v = 0; v < pq.size(); ++v) worst = std::max(worst, (pq[v] - pt[v]).norm());
  EXPECT_LT(worst, 0.02 * quads.diagonal);
}

TEST(Deformer, WidthBelowOneShrinksTheSurface) {
  const Mesh grid = make_grid(1.0, 1.0, 10, 10, FaceShape::Quads);
  PrismParameters p;
  p.width = 0.8;
  Handle anchor{"anchor", faces_where(grid, [](const Vec3& c) {
                  return std::abs(c.x() - 0.55) < 0.01 && std::abs(c.y() - 0.55) < 0.01;
                }), Fix::All, {}};
  ASSERT_EQ(anchor.faces.size(), 1u);
  Deformer d(grid, p, {anchor});
  SolveOptions options;
  options.max_iterations = 200;
  ASSERT_TRUE(d.solve(options).converged);
  const double ratio = total_area(d.deformed_mesh(grid)) / total_area(grid);
  EXPECT_LT(ratio, 0.8);
  EXPECT_GT(ratio, 0.5);
}

TEST(Deformer, PlateBlendSmoothsANoisySphereWithoutShrinking) {
  Mesh sphere = make_icosphere(3);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> noise(-0.03, 0.03);
  for (auto v : sphere.vertices()) sphere.set_point(v, sphere.point(v) * (1.0 + noise(rng)));
  // Mean deviation of the distance to the centre, relative to the mean radius. The centre is
  // the vertex average: only one face is anchored, so the sphere may drift as it relaxes.
  auto roughness = [](const Mesh& m) {
    Vec3 center = Vec3::Zero();
    for (auto v : m.vertices()) center += m.point(v);
    center /= double(m.n_vertices());
    double mean = 0.0, dev = 0.0;
    for (auto v : m.vertices()) mean += (m.point(v) - center).norm();
    mean /= m.n_vertices();
    for (auto v : m.vertices()) dev += std::abs((m.point(v) - center).norm() - mean);
    return dev / m.n_vertices() / mean;
  };
  PrismParameters plate;
  plate.normal_blend = 1.0;
  Deformer d(sphere, plate, {Handle{"anchor", {0}, Fix::All, {}}});
  SolveOptions options;
  options.max_iterations = 200;
  ASSERT_TRUE(d.solve(options).converged);
  const Mesh smoothed = d.deformed_mesh(sphere);
  std::cout << "[ metric   ] plate smoothing: roughness " << roughness(sphere) << " -> "
            << roughness(smoothed) << ", area ratio "
            << total_area(smoothed) / total_area(sphere) << "\n";
  EXPECT_LT(roughness(smoothed), 0.5 * roughness(sphere));
  EXPECT_NEAR(total_area(smoothed) / total_area(sphere), 1.0, 0.03);
}

TEST(Deformer, KeepsSolvingAfterBeingMoved) {
  BentCylinder c = bent_cylinder(12, 8, 45.0, 0.0);
  Deformer first(c.mesh, PrismParameters{}, c.handles);
  SolveOptions one;
  one.max_iterations = 1;
  first.solve(one);  // makes the global solver, which refers to the deformer's system
  Deformer moved(std::move(first));
  const SolveReport r = moved.solve(SolveOptions{});
  EXPECT_TRUE(r.converged);
  Deformer reference(c.mesh, PrismParameters{}, c.handles);
  EXPECT_NEAR(r.energy, reference.solve(SolveOptions{}).energy, 1e-9);
}

TEST(Deformer, EnergyCarriedThroughHandleMovesMatchesAFullPass) {
  BentCylinder c = bent_cylinder(12, 8, 45.0, 30.0);
  Force pull{"pull", faces_where(c.mesh, [](const Vec3& p) { return p.y() > 0.7 && p.y() < 1.3; }),
             Vec3(0.05, 0.0, 0.0), 2.0};
  ASSERT_FALSE(pull.faces.empty());
  Deformer d(c.mesh, PrismParameters{}, c.handles, {pull});
  SolveOptions one;
  one.max_iterations = 2;
  one.drag_prediction = 0.0;  // a frame would start from a predicted state, with its energy
  d.solve(one);
  for (int step = 1; step <= 3; ++step) {
    RigidTransform top = c.handles[1].transform;
    top.translation += Vec3(0.02 * step, 0.0, 0.01);
    d.set_handle_transform(1, top);
    RigidTransform bottom = RigidTransform::identity();
    bottom.translation = Vec3(0.0, 0.0, 0.01 * step);
    d.set_handle_transform(0, bottom);
    const double full = d.system().energy(d.body_states());
    EXPECT_NEAR(d.energy(), full, 1e-12 * full) << "step " << step;
    EXPECT_NEAR(d.solve(one).initial_energy, full, 1e-12 * full);
  }
  d.set_force_offset(0, Vec3(0.0, 0.1, 0.0));  // a changed force is not carried: a full pass
  EXPECT_DOUBLE_EQ(d.energy(), d.system().energy(d.body_states()));
}

TEST(Deformer, HierarchicalStartEndsAtTheGlobalMinimum) {
  // What `primo deform` does when no solver is asked for: cheap cycles, then a Newton polish.
  const BentCylinder c = bent_cylinder(24, 36, 120.0, 0.0, Fix::All, FaceShape::Triangles);
  const PrismParameters material = PrismParameters::product_default();
  SolveOptions options;
  options.tolerance = 1e-8;
  options.max_iterations = 200;
  Deformer global(c.mesh, material, c.handles);
  const SolveReport exact = global.solve(options);
  options.hierarchical_start = true;
  Deformer hybrid(c.mesh, material, c.handles);
  const SolveReport r = hybrid.solve(options);
  std::cout << "[ metric   ] 1,728 triangles bent 120 degrees: global " << exact.iterations
            << " Newton iterations in " << exact.seconds << " s; hierarchical start "
            << r.hierarchical_cycles << " cycles + " << r.iterations << " Newton in " << r.seconds
            << " s\n";
  ASSERT_TRUE(exact.converged && r.converged);
  EXPECT_GT(r.hierarchical_cycles, 0);
  EXPECT_LT(r.iterations, exact.iterations);
  EXPECT_NEAR(r.energy, exact.energy, 1e-9 * exact.energy);
  EXPECT_LT(largest_point_distance(hybrid.vertex_positions(), global.vertex_positions()),
            1e-6 * c.diagonal);
}

TEST(Deformer, FaceMotionsRestoreTheWholeStateIncludingHandlesFreeParts) {
  // A position handle's rotation and an orientation handle's translation are solved for;
  // setting the face motions of a solved deformer on a new one gives back the same pose.
  BentCylinder c = bent_cylinder(12, 16, 60.0, 30.0, Fix::Position);
  c.handles.push_back({"side", faces_where(c.mesh, [](const Vec3& p) {
                         return p.y() > 0.9 && p.y() < 1.1 && p.x() > 0.2;
                       }), Fix::Orientation, {}});
  c.handles.back().transform.rotation = Eigen::AngleAxisd(0.3, Vec3::UnitY()).toRotationMatrix();
  Deformer solved(c.mesh, PrismParameters{}, c.handles);
  SolveOptions o;
  o.max_iterations = 200;
  ASSERT_TRUE(solved.solve(o).converged);
  Deformer copy(c.mesh, PrismParameters{}, c.handles);
  copy.set_face_motions(solved.face_motions());
  EXPECT_LT(largest_point_distance(copy.vertex_positions(), solved.vertex_positions()),
            1e-12 * c.diagonal);
  EXPECT_NEAR(copy.energy(), solved.energy(), 1e-12 * solved.energy());
  // The state counts as solved for these targets: nothing to follow, nothing to do.
  EXPECT_FALSE(copy.path_pending(o.path));
  EXPECT_LE(copy.solve(o).iterations, 1);
}

TEST(Deformer, AMeshPosedAtRestKeepsTheFilesCoordinatesBitForBit) {
  // A cylinder's coordinates are sines and cosines, which c + (p - c) does not give back
  // exactly: the prisms' rest copies are the vertices themselves and a body at rest adds
  // nothing, so the solve of handles left at rest returns every coordinate unchanged, and a
  // handle moved and moved back does too once the solve is back at rest.
  const Mesh mesh = make_cylinder(0.3, 1.0, 24, 10, FaceShape::Triangles);
  const int n = int(mesh.n_faces());
  Handle bottom{"bottom", {0, 1, 2}, Fix::All, {}}, top{"top", {n - 1, n - 2}, Fix::All, {}};
  Deformer d(mesh, PrismParameters{}, {bottom, top});
  d.solve(SolveOptions{});
  std::vector<Vec3> points = d.vertex_positions();
  int moved = 0;
  for (auto v : mesh.vertices()) moved += points[size_t(v.idx())] != mesh.point(v);
  EXPECT_EQ(moved, 0) << "of " << mesh.n_vertices() << " vertices";
  // With widths below 1 the rest copies are scaled about the face centroids, and the
  // vertex is their mean, as the scenario format says.
  PrismParameters narrow;
  narrow.width = 0.8;
  Deformer w(mesh, narrow, {bottom, top});
  points = w.vertex_positions();
  double farthest = 0.0;
  for (auto v : mesh.vertices()) farthest = std::max(farthest, (points[size_t(v.idx())] - mesh.point(v)).norm());
  EXPECT_GT(farthest, 1e-4) << "the narrower copies' mean lies inside the surface";
}
