// Reliability (docs/reliability.md): thousands of random handle moves, huge and
// degenerate ones included, never give a non-finite state or an energy that rises within a
// solve; the degenerate geometry the paper says PriMo survives either solves or is one error
// naming the face; the same inputs give the same bytes run after run.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "support/session_support.h"
#include "support/test_support.h"

namespace {

using namespace primo;

void expect_finite_state(const Deformer& d, const std::string& where) {
  for (const BodyState& b : d.body_states())
    ASSERT_TRUE(b.rotation.allFinite() && b.position.allFinite()) << where;
  for (const Vec3& p : d.vertex_positions()) ASSERT_TRUE(p.allFinite()) << where;
  ASSERT_TRUE(std::isfinite(d.energy())) << where;
}

void expect_monotone(const SolveReport& r, const std::string& where) {
  for (size_t i = 1; i < r.energies.size(); ++i)
    ASSERT_LE(r.energies[i], r.energies[i - 1] * (1.0 + 1e-9) + 1e-300)
        << where << ": iteration " << i << " of " << r.stop_reason;
}

RigidTransform random_move(std::mt19937& rng, int kind) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Vec3 axis(unit(rng), unit(rng), unit(rng));
  RigidTransform t;
  switch (kind) {
    case 0:  // an ordinary drag step
      t.rotation = Eigen::AngleAxisd(0.5 * unit(rng), axis.normalized()).toRotationMatrix();
      t.translation = 0.3 * Vec3(unit(rng), unit(rng), unit(rng));
      break;
    case 1:  // a 180-degree flip
      t.rotation = Eigen::AngleAxisd(M_PI, axis.normalized()).toRotationMatrix();
      break;
    case 2:  // huge: a million times the mesh away
      t.translation = 1e6 * Vec3(unit(rng), unit(rng), unit(rng));
      break;
    case 3:  // a zero axis: make_rigid_transform refuses a turn, an angle of 0 is the identity
      t = make_rigid_transform(Vec3(unit(rng), 0, 0), Vec3::Zero(), 0.0, Vec3::Zero());
      break;
    default:  // back to rest
      break;
  }
  return t;
}

TEST(Reliability, ThousandsOfRandomHandleMovesStayFiniteAndMonotone) {
  const Mesh bar = make_bar(0.2, 1.0, 2, 8);
  std::vector<int> bottom, top;
  for (auto f : bar.faces()) {
    Vec3 c = Vec3::Zero();
    int n = 0;
    for (auto v : f.vertices()) c += bar.point(v), ++n;
    c /= n;
    if (c.y() < 0.1) bottom.push_back(f.idx());
    if (c.y() > 0.9) top.push_back(f.idx());
  }
  ASSERT_FALSE(bottom.empty());
  ASSERT_FALSE(top.empty());
  std::mt19937 rng(16);
  int moves = 0;
  for (SolveMethod method : {SolveMethod::Global, SolveMethod::Local, SolveMethod::Hierarchical})
    for (Fix fix : {Fix::All, Fix::Position, Fix::Orientation}) {
      Deformer d(bar, PrismParameters{}, {{"base", bottom, Fix::All, {}}, {"top", top, fix, {}}},
                 {{"pull", {int(bar.n_faces()) / 2}, Vec3(0, 0, 0.1), 2.0}});
      SolveOptions options;
      options.method = method;
      options.max_iterations = 3;
      options.path.max_iterations = 4;
      for (int k = 0; k < 250; ++k, ++moves) {
        const int kind = int(rng() % 6);
        d.set_handle_transform(1, random_move(rng, kind));
        if (k % 7 == 0) d.set_force_offset(0, Vec3(0, 0, 0.5 * (k % 3)));
        if (k % 50 == 25) {
          // The paper's Figure 6: every prism collapsed to one point, turned at random.
          std::vector<RigidTransform> motions(bar.n_faces());
          for (auto& m : motions) {
            m.rotation = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
            m.translation = -m.rotation * Vec3(0, 0.5, 0);
          }
          d.set_face_motions(motions);
        }
        const std::string where = "method " + std::to_string(int(method)) + ", fix " +
                                  std::to_string(int(fix)) + ", move " + std::to_string(k) +
                                  " (kind " + std::to_string(kind) + ")";
        const SolveReport r = d.solve(options);
        expect_monotone(r, where);
        expect_finite_state(d, where);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  EXPECT_EQ(2250, moves);
}

// A move of a million bounding-box diagonals was followed in a million sub-steps, each a
// factorization, and sub-steps without a decrease did not count against the budget: a hang.
TEST(Reliability, AHugeMoveIsFollowedInABoundedPath) {
  const Mesh grid = make_grid(1.0, 1.0, 4, 4, FaceShape::Quads);
  RigidTransform far;
  far.translation = Vec3(1e6, 0, 0);
  Deformer d(grid, PrismParameters{}, {{"a", {0}, Fix::All, {}}, {"b", {15}, Fix::All, far}});
  const auto start = std::chrono::steady_clock::now();
  const SolveReport r = d.solve(SolveOptions{});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
  EXPECT_LE(r.path_steps, kMaxPathSteps);
  expect_finite_state(d, "huge move");
}

TEST(Reliability, NonFiniteTargetsAreRefusedWhereTheyEnter) {
  const Mesh grid = make_grid(1.0, 1.0, 4, 4, FaceShape::Quads);
  Deformer d(grid, PrismParameters{}, {{"a", {0}, Fix::All, {}}, {"b", {15}, Fix::All, {}}},
             {{"f", {5}, Vec3::Zero(), 1.0}});
  RigidTransform nan;
  nan.translation.x() = std::nan("");
  EXPECT_THROW(d.set_handle_transform(1, nan), Error);
  RigidTransform skew;
  skew.rotation(0, 1) = 3.0;
  EXPECT_THROW(d.set_handle_transform(1, skew), Error);
  EXPECT_THROW(d.set_force_offset(0, Vec3(INFINITY, 0, 0)), Error);
  EXPECT_THROW(Deformer(grid, PrismParameters{}, {{"a", {0}, Fix::All, nan}}), Error);
  EXPECT_THROW(Deformer(grid, PrismParameters{}, {}, {{"f", {5}, Vec3::Zero(), NAN}}), Error);
  expect_finite_state(d, "after the refusals");
}

// --- degenerate geometry (docs/mesh-io.md, "Degenerate geometry") --------------------------

std::string load_error(const std::string& obj) {
  try {
    mesh_from_soup(parse_mesh_bytes(obj, "d.obj"), "d.obj");
  } catch (const Error& e) {
    return e.what();
  }
  return "(loaded)";
}

// Solves a bend with the first face fixed and the last turned 60 degrees about x.
SolveReport bend(const Mesh& mesh) {
  RigidTransform turn =
      make_rigid_transform(Vec3(0, 0, 0.1), Vec3(1, 0, 0), 60.0, Vec3(0.5, 0.5, 0));
  Deformer d(mesh, PrismParameters{},
             {{"a", {0}, Fix::All, {}}, {"b", {int(mesh.n_faces()) - 1}, Fix::All, turn}});
  const SolveReport r = d.solve(SolveOptions{});
  expect_finite_state(d, "bend");
  expect_monotone(r, "bend");
  return r;
}

Mesh from_obj(const std::string& obj) {
  return mesh_from_soup(parse_mesh_bytes(obj, "d.obj"), "d.obj");
}

// A 3 x 3 triangle grid with its middle vertex (5) moved: to (0.5, 0.0001) its faces become
// needles and caps.
std::string grid_with_middle(const std::string& middle) {
  return "v 0 0 0\nv 0.5 0 0\nv 1 0 0\nv 0 0.5 0\nv " + middle +
         "\nv 1 0.5 0\nv 0 1 0\nv 0.5 1 0\nv 1 1 0\n"
         "f 1 2 5\nf 1 5 4\nf 2 3 6\nf 2 6 5\nf 4 5 8\nf 4 8 7\nf 5 6 9\nf 5 9 8\n";
}

TEST(DegenerateGeometry, NeedlesAndCapsSolve) {
  const SolveReport needle = bend(from_obj(grid_with_middle("0.5 0.0001 0")));  // needles and caps
  EXPECT_TRUE(needle.converged) << needle.stop_reason;
  const SolveReport cap = bend(from_obj(grid_with_middle("0.5 0.49999 0")));  // near-flat caps
  EXPECT_TRUE(cap.converged) << cap.stop_reason;
  // A sliver 1e-9 thin on a 1-long edge: still a face with a normal.
  EXPECT_TRUE(
      bend(from_obj("v 0 0 0\nv 1 0 0\nv 0.5 1e-9 0\nv 0.5 -1 0\nf 1 3 2\nf 1 2 4\n")).converged);
}

TEST(DegenerateGeometry, ZeroAreaAndRepeatedIndicesAreErrorsNamingTheFace) {
  EXPECT_NE(
      std::string::npos,
      load_error(grid_with_middle("0.5 0 0")).find("d.obj: face 0 (vertices 0, 1, 4): zero area"));
  EXPECT_NE(std::string::npos,
            load_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2 3\n")
                .find("face 0 (vertices 0, 1, 1, 2): vertex 1 appears more than once"));
  // Duplicate vertices (two at one position) in one face: zero area.
  EXPECT_NE(std::string::npos, load_error("v 0 0 0\nv 1 0 0\nv 1 0 0\nf 1 2 3\n")
                                   .find("face 0 (vertices 0, 1, 2): zero area"));
}

TEST(DegenerateGeometry, DuplicateIsolatedOneFaceDisconnectedAndBoundariesSolve) {
  // Duplicate vertices in different faces: a cut along the seam, two boundaries that touch.
  EXPECT_TRUE(
      bend(from_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 2 0 0\nv 2 1 0\n"
                    "f 1 2 3 4\nf 5 7 8 6\n"))
          .converged);
  // Isolated vertices, one far away: they stay where they are.
  const Mesh isolated = from_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nv 1e7 0 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 7 "
      "8 3\n");
  EXPECT_TRUE(bend(isolated).converged);
  // One face: a handle and nothing else.
  const Mesh one = from_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Deformer d(
      one, PrismParameters{},
      {{"a", {0}, Fix::All, make_rigid_transform(Vec3(1, 2, 3), Vec3(0, 0, 1), 90, Vec3::Zero())}});
  EXPECT_TRUE(d.solve(SolveOptions{}).converged);
  expect_finite_state(d, "one face");
  // Two pieces, the second without any handle: it stays at rest.
  const Mesh pieces = from_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 3 0 0\nv 4 0 0\nv 4 1 0\nv 3 1 0\nv 2 0 0\nv 2 1 0\n"
      "f 1 2 3 4\nf 2 9 10 3\nf 5 6 7 8\n");
  Deformer p(pieces, PrismParameters{},
             {{"a", {0}, Fix::All, {}},
              {"b",
               {1},
               Fix::All,
               make_rigid_transform(Vec3(0, 0, 0.3), Vec3(0, 1, 0), 30, Vec3(1.5, 0.5, 0))}});
  EXPECT_TRUE(p.solve(SolveOptions{}).converged);
  const std::vector<Vec3> after = p.vertex_positions();
  for (int v : {4, 5, 6, 7})
    EXPECT_LT((after[size_t(v)] - pieces.point(Mesh::VertexHandle(v))).norm(), 1e-9);
  // Boundaries everywhere: an open cylinder.
  EXPECT_TRUE(bend(make_cylinder(0.25, 1.0, 8, 4, FaceShape::Quads)).converged);
}

// --- determinism ----------------------------------------------------------------------------

TEST(Determinism, DeformAndReplayTwiceGiveTheSameBytes) {
  const std::string dir = test::temp_dir();
  const test::RecordedSession r = test::record_bar_session(dir + "/bar.obj");
  save_mesh(r.mesh, dir + "/bar.obj");
  save_session(r.session, dir + "/pose.session.json");
  test::write_text(dir + "/s.json", R"({"format": "primo-scenario/1", "mesh": "bar.obj",
    "handles": [{"select": {"box": {"min": [-1, -1, -1], "max": [1, 0.1, 1]}}, "fix": "all"},
                {"select": {"box": {"min": [-1, 0.9, -1], "max": [1, 2, 1]}}, "fix": "all",
                 "transform": {"axis": [0, 0, 1], "angle_deg": 90, "translate": [0.3, 0, 0]}}]})");
  for (const std::string run : {"1", "2"}) {
    ASSERT_EQ(
        0, test::run_primo("deform " + dir + "/s.json -o " + dir + "/d" + run + ".obj").exit_code);
    ASSERT_EQ(0, test::run_primo("replay " + dir + "/pose.session.json -o " + dir + "/r" + run +
                                 ".obj --frames " + dir + "/frames" + run + " --every 5")
                     .exit_code);
  }
  EXPECT_EQ(test::read_text(dir + "/d1.obj"), test::read_text(dir + "/d2.obj"));
  EXPECT_EQ(test::read_text(dir + "/r1.obj"), test::read_text(dir + "/r2.obj"));
  for (const char* frame : {"frame_000000.obj", "frame_000005.obj", "frame_000010.obj"})
    EXPECT_EQ(test::read_text(dir + "/frames1/" + frame),
              test::read_text(dir + "/frames2/" + frame))
        << frame;
  EXPECT_FALSE(test::read_text(dir + "/frames1/frame_000010.obj").empty());
}

}  // namespace
