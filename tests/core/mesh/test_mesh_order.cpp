// The solver's own numbering of a mesh (MeshOrder): the same solver mesh whatever order a file
// lists the surface in, neighbours near each other, and a deformer whose results do not depend
// on the file's order, bit for bit, on any number of threads.

#include "primo/mesh/mesh_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>

#include "primo/solve/deformer.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/util/parallel.h"
#include "support/test_support.h"

using namespace primo;

namespace {

std::vector<int> face_cycle(const Mesh& mesh, int face) {
  std::vector<int> cycle;
  for (auto v : mesh.fv_range(mesh.face_handle(face))) cycle.push_back(v.idx());
  return cycle;
}

// A face's key that no renumbering changes: its points, sorted.
std::vector<std::array<double, 3>> face_key(const Mesh& mesh, int face) {
  std::vector<std::array<double, 3>> key;
  for (int v : face_cycle(mesh, face)) {
    const Vec3& p = mesh.point(mesh.vertex_handle(v));
    key.push_back({p.x(), p.y(), p.z()});
  }
  std::sort(key.begin(), key.end());
  return key;
}

// For each face of `to`, the face of `from` with the same points.
std::vector<int> match_faces(const Mesh& from, const Mesh& to) {
  std::map<std::vector<std::array<double, 3>>, int> index;
  for (int f = 0; f < int(from.n_faces()); ++f) index[face_key(from, f)] = f;
  std::vector<int> match;
  for (int f = 0; f < int(to.n_faces()); ++f) match.push_back(index.at(face_key(to, f)));
  return match;
}

std::vector<int> match_vertices(const Mesh& from, const Mesh& to) {
  std::map<std::array<double, 3>, int> index;
  for (auto v : from.vertices()) {
    const Vec3& p = from.point(v);
    index[{p.x(), p.y(), p.z()}] = v.idx();
  }
  std::vector<int> match;
  for (auto v : to.vertices()) {
    const Vec3& p = to.point(v);
    match.push_back(index.at({p.x(), p.y(), p.z()}));
  }
  return match;
}

// The largest index distance between faces that share an edge.
int largest_neighbour_gap(const Mesh& mesh) {
  int gap = 0;
  for (auto e : mesh.edges())
    if (!e.is_boundary()) gap = std::max(gap, std::abs(e.h0().face().idx() - e.h1().face().idx()));
  return gap;
}

}  // namespace

TEST(HilbertIndex, VisitsEveryCellOnceMovingToANeighbour) {
  constexpr int kBits = 3, kSide = 1 << kBits;
  std::vector<std::array<int, 3>> cell_at(kSide * kSide * kSide, {-1, -1, -1});
  for (int x = 0; x < kSide; ++x)
    for (int y = 0; y < kSide; ++y)
      for (int z = 0; z < kSide; ++z) {
        const std::uint64_t index = hilbert_index(std::uint32_t(x), std::uint32_t(y), std::uint32_t(z), kBits);
        ASSERT_LT(index, cell_at.size());
        EXPECT_EQ(cell_at[index][0], -1) << "index " << index << " given twice";
        cell_at[index] = {x, y, z};
      }
  for (size_t i = 1; i < cell_at.size(); ++i) {
    const int step = std::abs(cell_at[i][0] - cell_at[i - 1][0]) +
                     std::abs(cell_at[i][1] - cell_at[i - 1][1]) +
                     std::abs(cell_at[i][2] - cell_at[i - 1][2]);
    EXPECT_EQ(step, 1) << "from index " << i - 1 << " to " << i;
  }
}

TEST(MeshOrder, IsARenumberingThatKeepsEveryFaceCycle) {
  const Mesh mesh = shuffled_mesh(make_cylinder(0.25, 2.0, 12, 10, FaceShape::Quads), 3);
  const MeshOrder order = locality_order(mesh);
  ASSERT_EQ(order.n_faces(), int(mesh.n_faces()));
  ASSERT_EQ(order.n_vertices(), int(mesh.n_vertices()));
  EXPECT_EQ(std::set<int>(order.face_of.begin(), order.face_of.end()).size(), mesh.n_faces());
  EXPECT_EQ(std::set<int>(order.vertex_of.begin(), order.vertex_of.end()).size(), mesh.n_vertices());
  const Mesh solver = reordered_mesh(mesh, order);
  for (int i = 0; i < order.n_faces(); ++i) {
    const std::vector<int> file = face_cycle(mesh, order.face_of[size_t(i)]);
    const std::vector<int> own = face_cycle(solver, i);
    ASSERT_EQ(file.size(), own.size());
    for (size_t j = 0; j < own.size(); ++j)
      EXPECT_EQ(order.vertex_of[size_t(own[j])],
                file[(j + size_t(order.face_rotation[size_t(i)])) % file.size()]);
  }
  EXPECT_EQ(order.faces_to_file(order.faces_to_solver(order.face_of)), order.face_of);
}

TEST(MeshOrder, GivesTheSameSolverMeshForAnyFileOrder) {
  for (const Mesh& mesh : {make_icosphere(3), make_cylinder(0.25, 2.0, 16, 12, FaceShape::Quads),
                           make_grid(1.0, 2.0, 9, 7, FaceShape::Triangles)}) {
    const Mesh a = reordered_mesh(mesh, locality_order(mesh));
    for (std::uint64_t seed : {1u, 2u}) {
      const Mesh shuffled = shuffled_mesh(mesh, seed);
      const Mesh b = reordered_mesh(shuffled, locality_order(shuffled));
      ASSERT_EQ(a.n_faces(), b.n_faces());
      for (int v = 0; v < int(a.n_vertices()); ++v)
        ASSERT_EQ(a.point(a.vertex_handle(v)), b.point(b.vertex_handle(v))) << "vertex " << v;
      for (int f = 0; f < int(a.n_faces()); ++f)
        ASSERT_EQ(face_cycle(a, f), face_cycle(b, f)) << "face " << f;
    }
  }
}

TEST(MeshOrder, PutsNeighboursNearEachOther) {
  // 20,000 triangles: shuffled, neighbours lie thousands of faces apart; in the solver's
  // order within two breadth-first fronts (a front crosses the grid: about 400 faces).
  const Mesh shuffled = shuffled_mesh(make_grid(1.0, 1.0, 100, 100, FaceShape::Triangles), 9);
  const Mesh solver = reordered_mesh(shuffled, locality_order(shuffled));
  EXPECT_GT(largest_neighbour_gap(shuffled), 15000);
  EXPECT_LT(largest_neighbour_gap(solver), 1000);
}

TEST(MeshOrder, DeformerGivesTheSameBitsForAnyFileOrderAndThreadCount) {
  const test::BentCylinder c = test::bent_cylinder(24, 40, 90.0, 60.0);  // 960 quads
  const Mesh shuffled = shuffled_mesh(c.mesh, 11);
  const std::vector<int> face_in_original = match_faces(c.mesh, shuffled);
  const std::vector<int> vertex_in_original = match_vertices(c.mesh, shuffled);
  std::vector<int> shuffled_face(c.mesh.n_faces());
  for (int f = 0; f < int(shuffled.n_faces()); ++f) shuffled_face[size_t(face_in_original[size_t(f)])] = f;
  std::vector<Handle> handles = c.handles;
  for (Handle& h : handles)
    for (int& f : h.faces) f = shuffled_face[size_t(f)];
  // A force's faces too, listed in the shuffled file's order.
  std::vector<Force> forces(1), shuffled_forces(1);
  forces[0].faces = test::faces_where(c.mesh, [](const Vec3& p) { return p.y() > 0.1 && p.y() < 0.3; });
  forces[0].target_offset = Vec3(0.1, 0.0, 0.05);
  forces[0].stiffness = 5.0;
  shuffled_forces[0] = forces[0];
  shuffled_forces[0].faces.clear();
  for (int f : forces[0].faces) shuffled_forces[0].faces.push_back(shuffled_face[size_t(f)]);
  std::sort(shuffled_forces[0].faces.begin(), shuffled_forces[0].faces.end());

  for (SolveMethod method : {SolveMethod::Hierarchical, SolveMethod::Global}) {
    SolveOptions options;
    options.method = method;
    options.max_iterations = method == SolveMethod::Global ? 4 : 12;
    options.tolerance = 0.0;
    Deformer original(c.mesh, PrismParameters{}, c.handles, forces);
    original.solve(options);
    const std::vector<Vec3> expected = original.vertex_positions();
    const std::vector<RigidTransform> expected_motions = original.face_motions();
    for (int threads : {1, 2, 3, 8}) {
      set_thread_count(threads);
      Deformer d(shuffled, PrismParameters{}, handles, shuffled_forces);
      d.solve(options);
      const std::vector<Vec3> got = d.vertex_positions();
      const std::vector<RigidTransform> motions = d.face_motions();
      set_thread_count(0);
      EXPECT_EQ(d.energy(), original.energy()) << threads << " threads";
      for (size_t v = 0; v < got.size(); ++v)
        ASSERT_EQ(got[v], expected[size_t(vertex_in_original[v])])
            << "vertex " << v << ", " << threads << " threads";
      for (size_t f = 0; f < motions.size(); ++f) {
        ASSERT_EQ(motions[f].rotation, expected_motions[size_t(face_in_original[f])].rotation);
        ASSERT_EQ(motions[f].translation, expected_motions[size_t(face_in_original[f])].translation);
      }
    }
  }
}

TEST(MeshOrder, FaceMotionsAreInTheFilesNumbering) {
  const test::BentCylinder c = test::bent_cylinder(12, 10, 30.0);
  Deformer d(c.mesh, PrismParameters{}, c.handles);
  std::vector<RigidTransform> motions = d.face_motions();
  // A motion that says which face it is for: the face's index in x.
  for (size_t f = 0; f < motions.size(); ++f)
    motions[f] = {Mat3::Identity(), Vec3(double(f), 0.0, 0.0)};
  d.set_face_motions(motions);
  const std::vector<RigidTransform> back = d.face_motions();
  const std::set<int> handle_faces = [&] {
    std::set<int> s;
    for (const Handle& h : c.handles) s.insert(h.faces.begin(), h.faces.end());
    return s;
  }();
  for (size_t f = 0; f < back.size(); ++f) {
    if (!handle_faces.count(int(f))) {
      EXPECT_EQ(back[f].translation, Vec3(double(f), 0.0, 0.0)) << "face " << f;
    }
  }
}
