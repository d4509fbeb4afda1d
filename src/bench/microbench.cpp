// Micro-benchmarks of the engine's inner loops with Google Benchmark (docs/performance.md,
// "Micro-benchmarks"). Where `primo bench engine` reports whole-solve throughput against the
// paper's figures, these time one kernel each, so that a change to it shows up on its own:
//
//  - HornRotation: Horn's closed-form rotation of one 3x3 cross-covariance (horn.h), the core
//    of every local match;
//  - LocalMatch: one body's match against its neighbours (local_solver.h, paper Sect. 4.1);
//  - LocalSweep / PlannedSweep: one Gauss-Seidel sweep over every body, plain and the solvers'
//    two-thread planned sweep;
//  - DragPrediction / SystemEnergy: a drag frame's prediction and the energy pass that
//    checks it (drag_predictor.h);
//  - NewtonKrylovMove: a step's trial state for its line search;
//  - NewtonKrylovStructure / ClusterHierarchyBuild: what the first Newton-Krylov step builds
//    (rows' order, Hessian structure, multigrid levels), and the hierarchy of clusters alone;
//  - HessianProduct / MultigridCycle: the two kernels of a Newton-Krylov step's conjugate
//    gradients (newton_krylov.h): a product with the exact Hessian's 6x6 blocks, and one
//    application of the rigid-cluster multigrid preconditioner (rigid_multigrid.h);
//  - GlobalAssembly: assembling the global Gauss-Newton system (global_solver.h, Sect. 4.2),
//    timed by the solver's own assembly clock so that the factorization that follows is not
//    counted (10 iterations each, which take a few seconds in all because of it).
//
// The mesh is the limb of `primo bench engine`: a quad cylinder of radius 0.25 and length 2
// along y (mesh_generators.h), its bottom band fixed and its top band bent 90 degrees. The
// argument is the number of bands (40 segments around each), so faces = 40 x bands.
//
//   build/src/primo_microbench                      # everything, in about 10 s
//   build/src/primo_microbench --benchmark_filter=Sweep --benchmark_min_time=2

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "primo/solve/cluster_hierarchy.h"
#include "primo/solve/deformer.h"
#include "primo/solve/drag_predictor.h"
#include "primo/mesh/geometry.h"
#include "primo/solve/global_solver.h"
#include "primo/solve/horn.h"
#include "primo/solve/local_solver.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/solve/rigid_hessian.h"
#include "primo/solve/rigid_multigrid.h"

namespace {

using namespace primo;

constexpr double kRadius = 0.25;
constexpr double kLength = 2.0;
constexpr int kSegments = 40;

// The bent limb, made once per size and shared by the benchmarks of that size.
struct Limb {
  Mesh mesh;
  Deformer deformer;
  std::vector<BodyState> state;  // a few sweeps from the start: every body has moved
  int moving_bodies = 0;

  static Deformer make_deformer(const Mesh& mesh, int bands) {
    const FaceGeometry faces = compute_face_geometry(mesh);
    const double band = kLength / bands;
    std::vector<int> bottom, top;
    for (int f = 0; f < int(faces.centroid.size()); ++f) {
      if (faces.centroid[f].y() < band) bottom.push_back(f);
      if (faces.centroid[f].y() > kLength - band) top.push_back(f);
    }
    // The top turned 90 degrees towards +x and moved to where a constant-curvature bend of
    // the same length puts it (as `primo bench engine` bends it).
    const Vec3 top_centre(0.0, kLength, 0.0);
    const double arc_radius = kLength / (M_PI / 2.0);
    const RigidTransform bend = make_rigid_transform(Vec3(arc_radius, arc_radius, 0.0) - top_centre,
                                                     Vec3::UnitZ(), -90.0, top_centre);
    std::vector<Handle> handles = {{"bottom", bottom, Fix::All, RigidTransform::identity()},
                                   {"top", top, Fix::All, bend}};
    return Deformer(mesh, PrismParameters{}, std::move(handles));
  }

  explicit Limb(int bands)
      : mesh(make_cylinder(kRadius, kLength, kSegments, bands, FaceShape::Quads)),
        deformer(make_deformer(mesh, bands)),
        state(deformer.body_states()) {
    for (int i = 0; i < 3; ++i) local_sweep(deformer.system(), state);
    for (const auto& body : deformer.system().bodies)
      if (body.kind != BodyKind::Fixed) ++moving_bodies;
  }

  static const Limb& of(int bands) {
    static std::vector<std::unique_ptr<Limb>> made;
    for (const auto& limb : made)
      if (int(limb->mesh.n_faces()) == kSegments * bands) return *limb;
    made.push_back(std::make_unique<Limb>(bands));
    return *made.back();
  }
};

void HornRotation(benchmark::State& run) {
  // Cross-covariances of slightly rotated point sets, as a match sees them.
  std::mt19937 random(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<Mat3> S(64);
  for (Mat3& s : S) {
    const Mat3 R = Eigen::AngleAxisd(0.3 * noise(random), Vec3(noise(random), noise(random),
                                                                  noise(random)).normalized())
                       .toRotationMatrix();
    s.setZero();
    for (int k = 0; k < 8; ++k) {
      const Vec3 p(noise(random), noise(random), noise(random));
      s += p * (R * p).transpose();
    }
  }
  size_t i = 0;
  for (auto _ : run) benchmark::DoNotOptimize(horn_rotation(S[i++ & 63]));
  run.SetItemsProcessed(run.iterations());
}
BENCHMARK(HornRotation);

void LocalMatch(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  const RigidSystem& system = limb.deformer.system();
  std::vector<int> moving;
  for (int b = 0; b < system.n_bodies(); ++b)
    if (system.bodies[size_t(b)].kind != BodyKind::Fixed) moving.push_back(b);
  size_t i = 0;
  for (auto _ : run) {
    benchmark::DoNotOptimize(local_match(system, limb.state, moving[i]));
    if (++i == moving.size()) i = 0;
  }
  run.SetItemsProcessed(run.iterations());  // matches per second
}
BENCHMARK(LocalMatch)->Arg(60);

void LocalSweep(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  std::vector<BodyState> state = limb.state;
  for (auto _ : run) {
    local_sweep(limb.deformer.system(), state);
    benchmark::ClobberMemory();
  }
  run.SetItemsProcessed(run.iterations() * limb.moving_bodies);  // matches per second
  run.counters["faces"] = double(limb.mesh.n_faces());
}
BENCHMARK(LocalSweep)->Arg(60)->Arg(240)->Unit(benchmark::kMicrosecond);

void PlannedSweep(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  const RigidSystem& system = limb.deformer.system();
  const SweepPlan plan = plan_sweep(system, /*parallel=*/true);
  std::vector<BodyState> state = limb.state;
  for (auto _ : run) {
    planned_sweep(system, plan, state);
    benchmark::ClobberMemory();
  }
  run.SetItemsProcessed(run.iterations() * limb.moving_bodies);
  run.counters["faces"] = double(limb.mesh.n_faces());
}
BENCHMARK(PlannedSweep)->Arg(60)->Arg(240)->Arg(4800)->Unit(benchmark::kMicrosecond)->UseRealTime();

// A drag frame's extra work with the predictor (drag_predictor.h): every body carried on by
// its last change (argument 2: a steady drag, fraction 1; otherwise 0.7), and the energy
// pass that checks the prediction, for comparison (bands 4800: 192,000 faces).
void DragPrediction(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  const RigidSystem& system = limb.deformer.system();
  std::vector<BodyState> start(system.n_bodies());
  for (int b = 0; b < system.n_bodies(); ++b)
    start[size_t(b)] = {Mat3::Identity(), system.bodies[size_t(b)].rest_center};
  DragPredictor predictor;
  predictor.remember({1.0}, start);
  const double fraction = run.range(1) == 2 ? 1.0 : 0.7;
  std::vector<BodyState> predicted;
  for (auto _ : run) {
    predictor.predict(system, limb.state, fraction, predicted);
    benchmark::ClobberMemory();
  }
  run.SetItemsProcessed(run.iterations() * system.n_bodies());
}
BENCHMARK(DragPrediction)->Args({240, 2})->Args({4800, 2})->Args({4800, 1})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

void SystemEnergy(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  for (auto _ : run) benchmark::DoNotOptimize(limb.deformer.system().energy(limb.state));
  run.SetItemsProcessed(run.iterations() * limb.deformer.system().n_bodies());
}
BENCHMARK(SystemEnergy)->Arg(240)->Arg(4800)->Unit(benchmark::kMillisecond)->UseRealTime();

// The exact Hessian at the limb's state with its multigrid preconditioner set up, shared by the
// Newton-Krylov kernels of one size.
struct LimbHessian {
  RigidHessian hessian;
  RigidMultigrid multigrid;
  BlockVector residual;  // the negative gradient, what conjugate gradients start from

  explicit LimbHessian(const Limb& limb)
      : LimbHessian(limb, multigrid_rows(limb.deformer.system())) {}
  LimbHessian(const Limb& limb, MultigridRows rows)
      : hessian(limb.deformer.system(), std::move(rows.order)),
        multigrid(limb.deformer.system(), hessian.matrix().pairs, {}, hessian.order(),
                  std::move(rows.partition)) {
    hessian.assemble(limb.state, /*second_order=*/true);
    std::vector<Vec3> position;
    for (int body : hessian.order()) position.push_back(limb.state[size_t(body)].position);
    multigrid.set_matrix(hessian.matrix(), position);
    for (const Vec6& g : hessian.gradient()) residual.push_back(-g);
  }
  static LimbHessian& of(int bands) {
    static std::vector<std::pair<int, std::unique_ptr<LimbHessian>>> made;
    for (auto& [b, h] : made)
      if (b == bands) return *h;
    made.emplace_back(bands, std::make_unique<LimbHessian>(Limb::of(bands)));
    return *made.back().second;
  }
};

void HessianProduct(benchmark::State& run) {
  const LimbHessian& h = LimbHessian::of(int(run.range(0)));
  BlockVector y;
  for (auto _ : run) {
    h.hessian.matrix().multiply(h.residual, y);
    benchmark::ClobberMemory();
  }
  run.SetItemsProcessed(run.iterations() * h.hessian.matrix().size());  // rows per second
}
BENCHMARK(HessianProduct)->Arg(60)->Arg(4800)->Unit(benchmark::kMillisecond)->UseRealTime();

// The exact Hessian's assembly at the limb's state (a Newton-Krylov step's first phase).
void HessianAssembly(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  LimbHessian& h = LimbHessian::of(int(run.range(0)));
  for (auto _ : run) {
    h.hessian.assemble(limb.state, /*second_order=*/true);
    benchmark::ClobberMemory();
  }
  run.SetItemsProcessed(run.iterations() * h.hessian.matrix().size());
}
BENCHMARK(HessianAssembly)->Arg(60)->Arg(4800)->Unit(benchmark::kMillisecond)->UseRealTime();

// The multigrid's set-up for a new matrix: Galerkin projections, the smoothers' inverse
// diagonal blocks and the coarsest factor (a Newton-Krylov step's second phase).
void MultigridSetUp(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  LimbHessian& h = LimbHessian::of(int(run.range(0)));
  std::vector<Vec3> position;
  for (int body : h.hessian.order()) position.push_back(limb.state[size_t(body)].position);
  for (auto _ : run) {
    h.multigrid.set_matrix(h.hessian.matrix(), position);
    benchmark::ClobberMemory();
  }
  run.SetItemsProcessed(run.iterations() * h.hessian.matrix().size());
}
BENCHMARK(MultigridSetUp)->Arg(60)->Arg(4800)->Unit(benchmark::kMillisecond)->UseRealTime();

// A Newton-Krylov step's trial state for its line search: every body moved by its part of
// the step (its turn through the exponential map).
void NewtonKrylovMove(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  LimbHessian& h = LimbHessian::of(int(run.range(0)));
  BlockVector step;
  for (const Vec6& r : h.residual) step.push_back(1e-3 * r);
  std::vector<BodyState> trial;
  for (auto _ : run) {
    h.hessian.move_into(limb.state, step, 1.0, trial);
    benchmark::ClobberMemory();
  }
  run.SetItemsProcessed(run.iterations() * int64_t(limb.state.size()));
}
BENCHMARK(NewtonKrylovMove)->Arg(4800)->Unit(benchmark::kMillisecond)->UseRealTime();

// What a solve's first Newton-Krylov step builds before it can assemble: the rows' order,
// the Hessian's structure and the multigrid's levels (at 240k faces it runs beside the first
// coarse factorization and took longer than it), and the cluster hierarchy alone.
void NewtonKrylovStructure(benchmark::State& run) {
  const RigidSystem& system = Limb::of(int(run.range(0))).deformer.system();
  for (auto _ : run) {
    MultigridRows rows = multigrid_rows(system);
    RigidHessian hessian(system, std::move(rows.order));
    RigidMultigrid multigrid(system, hessian.matrix().pairs, {}, hessian.order(),
                             std::move(rows.partition));
    benchmark::DoNotOptimize(multigrid.levels());
  }
  run.SetItemsProcessed(run.iterations() * system.n_bodies());
}
BENCHMARK(NewtonKrylovStructure)->Arg(60)->Arg(4800)->Unit(benchmark::kMillisecond)->UseRealTime();

void ClusterHierarchyBuild(benchmark::State& run) {
  const RigidSystem& system = Limb::of(int(run.range(0))).deformer.system();
  HierarchyOptions options;  // the hierarchical solver's: clusters of 8
  for (auto _ : run) benchmark::DoNotOptimize(build_cluster_hierarchy(system, options));
  run.SetItemsProcessed(run.iterations() * system.n_bodies());
}
BENCHMARK(ClusterHierarchyBuild)->Arg(60)->Arg(4800)->Unit(benchmark::kMillisecond)->UseRealTime();

void MultigridCycle(benchmark::State& run) {
  LimbHessian& h = LimbHessian::of(int(run.range(0)));
  BlockVector z;
  for (auto _ : run) {
    h.multigrid.apply(h.residual, z);
    benchmark::ClobberMemory();
  }
  run.SetItemsProcessed(run.iterations() * h.hessian.matrix().size());
  run.counters["levels"] = double(h.multigrid.levels());
}
BENCHMARK(MultigridCycle)->Arg(60)->Arg(4800)->Unit(benchmark::kMillisecond)->UseRealTime();

// factorize_at assembles and then factorizes; only the assembly is reported, read from the
// solver's assembly clock (manual time), so the figure is the assembly's alone. The numeric
// factorization after it costs tens of times more, so the iterations are few and fixed, and it
// runs on one thread (BLAS threads waiting between factorizations would only add noise).
void GlobalAssembly(benchmark::State& run) {
  const Limb& limb = Limb::of(int(run.range(0)));
  GlobalSolver solver(limb.deformer.system(), GlobalSolver::Factorization::SupernodalOneThread);
  solver.factorize_at(limb.state);  // the symbolic analysis, once
  for (auto _ : run) {
    const double before = solver.timings().assembly;
    solver.factorize_at(limb.state);
    run.SetIterationTime(solver.timings().assembly - before);
  }
  run.SetItemsProcessed(run.iterations() * limb.moving_bodies);  // prism updates per second
  run.counters["faces"] = double(limb.mesh.n_faces());
}
BENCHMARK(GlobalAssembly)->Arg(60)->Arg(240)->UseManualTime()->Iterations(10)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
