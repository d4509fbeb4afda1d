// Parallel loops and solvers give the same bits on any number of threads: chunks depend on the
// size of the work only, sums are added in chunk order, and a sweep's parts are coloured.

#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "primo/solve/deformer.h"
#include "primo/mesh/geometry.h"
#include "primo/solve/local_solver.h"
#include "primo/mesh/mesh.h"
#include "primo/util/parallel.h"
#include "support/test_support.h"

using namespace primo;

namespace {

// Restores the default (every core) when a test ends, whatever it set.
struct ThreadCount {
  explicit ThreadCount(int n) { set_thread_count(n); }
  ~ThreadCount() { set_thread_count(0); }
};

bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

// run(threads) on 1, 2, 3 and 8 threads gives the same vertices, bit for bit.
void expect_same_on_every_thread_count(const std::function<std::vector<Vec3>(int)>& run) {
  std::vector<std::vector<Vec3>> results;
  for (int threads : {1, 2, 3, 8}) {
    ThreadCount count(threads);
    results.push_back(run(threads));
  }
  for (size_t k = 1; k < results.size(); ++k)
    EXPECT_TRUE(same_bits(results[k], results[0]))
        << "thread count #" << k << ": " << largest_point_distance(results[k], results[0]);
}

// The top's targets of a drag bending the 96 x 200 cylinder by 10 degrees a frame.
std::vector<RigidTransform> bend_frames(int frames) {
  std::vector<RigidTransform> targets;
  for (int k = 1; k <= frames; ++k)
    targets.push_back(test::bent_cylinder(96, 200, 10.0 * k).handles[1].transform);
  return targets;
}

// A drag's frames of `iterations` hierarchical iterations each.
SolveOptions drag_frames(int iterations) {
  SolveOptions o;
  o.method = SolveMethod::Hierarchical;
  o.drag_frame = true;
  o.max_iterations = iterations;
  o.tolerance = 0.0;
  return o;
}

}  // namespace

TEST(Parallel, ChunksDependOnTheSizeAloneAndSumsOnNoThreadCount) {
  EXPECT_EQ(chunk_count(0, 100), 1u);
  EXPECT_EQ(chunk_count(199, 100), 1u);
  EXPECT_EQ(chunk_count(1000, 100), 10u);
  EXPECT_EQ(chunk_count(size_t(1) << 40, 100), 256u);
  // A sum whose rounding depends on how it is split: the same bits for every thread count.
  const size_t n = 300000;
  auto term = [](size_t i) { return 1.0 / double(i + 1) * (i % 3 == 0 ? -1e3 : 1.0); };
  std::vector<double> sums;
  for (int threads : {1, 2, 3, 8}) {
    ThreadCount count(threads);
    EXPECT_EQ(thread_count(), threads);
    sums.push_back(parallel_sum(n, 1000, 0.0, [&](size_t b, size_t e) {
      double s = 0.0;
      for (size_t i = b; i < e; ++i) s += term(i);
      return s;
    }));
    std::vector<int> hits(n, 0);
    parallel_chunks(n, 1000, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) ++hits[i];
    });
    EXPECT_EQ(std::count(hits.begin(), hits.end(), 1), std::ptrdiff_t(n)) << "each item once";
  }
  for (double s : sums) EXPECT_EQ(s, sums.front());
}

TEST(Parallel, CopiesEveryElementIntoAVectorOfAnySize) {
  std::vector<Vec3> from(50000);
  for (size_t i = 0; i < from.size(); ++i) from[i] = Vec3(double(i), -double(i), 0.5 * double(i));
  for (int threads : {1, 3}) {
    ThreadCount count(threads);
    std::vector<Vec3> fresh, same(from.size(), Vec3::Constant(7.0)), longer(from.size() + 5);
    parallel_copy(from, fresh);
    parallel_copy(from, same);  // in place, in chunks
    parallel_copy(from, longer);
    EXPECT_TRUE(same_bits(fresh, from));
    EXPECT_TRUE(same_bits(same, from));
    EXPECT_TRUE(same_bits(longer, from));
  }
}

TEST(Parallel, AssignsTheValueToEveryElementOfAVectorOfAnySize) {
  const Vec3 value(1.5, -2.0, 0.25);
  for (int threads : {1, 3})
    for (const size_t n : {size_t(0), size_t(1), size_t(50000)}) {
      ThreadCount count(threads);
      std::vector<Vec3> fresh, shorter(n / 2, Vec3::Constant(7.0)), longer(n + 5);
      parallel_assign(fresh, n, value);
      parallel_assign(shorter, n, value);
      parallel_assign(longer, n, value);
      const std::vector<Vec3> want(n, value);
      EXPECT_TRUE(same_bits(fresh, want)) << n;
      EXPECT_TRUE(same_bits(shorter, want)) << n;
      EXPECT_TRUE(same_bits(longer, want)) << n;
    }
}

TEST(Parallel, SolvesGiveIdenticalVerticesOnOneTwoThreeAndEightThreads) {
  // 19,200 quads: eight sweep parts on the finest level, gradient and energy in chunks.
  const test::BentCylinder c = test::bent_cylinder(96, 200, 120.0);
  ASSERT_GE(c.mesh.n_faces(), 16000u);
  for (const SolveMethod method : {SolveMethod::Hierarchical, SolveMethod::Global}) {
    std::vector<std::vector<Vec3>> results;
    for (int threads : {1, 2, 3, 8}) {
      ThreadCount count(threads);
      Deformer d(c.mesh, PrismParameters{}, c.handles);
      SolveOptions o;
      o.method = method;
      o.max_iterations = method == SolveMethod::Hierarchical ? 6 : 2;
      o.tolerance = 0.0;
      o.path.enabled = false;
      if (method == SolveMethod::Hierarchical) {
        const SweepPlan plan = plan_sweep(d.system());
        EXPECT_EQ(plan.parts.size(), 8u);
      }
      d.solve(o);
      results.push_back(d.vertex_positions());
    }
    std::vector<Vec3> rest;
    for (auto v : c.mesh.vertices()) rest.push_back(c.mesh.point(v));
    ASSERT_GT(largest_point_distance(results[0], rest), 0.01 * c.diagonal);
    for (size_t k = 1; k < results.size(); ++k)
      EXPECT_TRUE(same_bits(results[k], results[0]))
          << (method == SolveMethod::Global ? "global" : "hierarchical") << ", thread count #" << k
          << ": " << largest_point_distance(results[k], results[0]);
  }
}

TEST(Parallel, DragFramesGiveIdenticalVerticesOnOneTwoThreeAndEightThreads) {
  // The frames of a drag add the prediction's passes (drag_predictor.h) to the cycles.
  const std::vector<RigidTransform> frames = bend_frames(4);
  const test::BentCylinder c = test::bent_cylinder(96, 200, 0.0);
  expect_same_on_every_thread_count([&](int threads) {
    Deformer d(c.mesh, PrismParameters{}, c.handles);
    const SolveOptions o = drag_frames(1);
    int predicted = 0;
    for (const RigidTransform& t : frames) {
      d.set_handle_transform(1, t);
      const double unpredicted = d.energy();
      predicted += d.solve(o).initial_energy < unpredicted;
    }
    EXPECT_EQ(predicted, 3) << threads << " threads";  // every frame but the first
    return d.vertex_positions();
  });
}

TEST(Parallel, DragFramesWithNewtonKrylovStepsGiveIdenticalVerticesOnOneTwoThreeAndEightThreads) {
  // Frames of two iterations: a cycle and a Newton-Krylov step each
  // (HierarchicalOptions::newton_krylov_in_frames).
  const std::vector<RigidTransform> frames = bend_frames(3);
  const test::BentCylinder c = test::bent_cylinder(96, 200, 0.0);
  expect_same_on_every_thread_count([&](int threads) {
    Deformer d(c.mesh, PrismParameters{}, c.handles);
    const SolveOptions o = drag_frames(2);
    for (const RigidTransform& t : frames) {
      d.set_handle_transform(1, t);
      d.solve(o);
    }
    EXPECT_EQ(d.hierarchical_solver()->timings().newton_krylov_steps, 3) << threads << " threads";
    return d.vertex_positions();
  });
}

TEST(Parallel, NewtonKrylovStepsGiveIdenticalVerticesOnOneTwoThreeAndEightThreads) {
  // A settling solve: cycles, then Newton-Krylov steps (Hessian blocks by body and pair,
  // multigrid sweeps by parts and colours, dot products in chunks).
  const test::BentCylinder c = test::bent_cylinder(96, 200, 60.0);
  expect_same_on_every_thread_count([&](int threads) {
    Deformer d(c.mesh, PrismParameters{}, c.handles);
    SolveOptions o;
    o.method = SolveMethod::Hierarchical;
    o.tolerance = 1e-3;
    o.hierarchical.newton_krylov_below = 1e-3;
    d.solve(o);  // cycles, near enough for Newton
    o.tolerance = 0.0;
    o.max_iterations = 4;
    d.solve(o);
    EXPECT_GE(d.hierarchical_solver()->timings().newton_krylov_steps, 1) << threads << " threads";
    return d.vertex_positions();
  });
}
