// OpenMesh IO before the mesh type: the binary-OFF test writes one with OpenMesh directly.
// clang-format off
#include <OpenMesh/Core/IO/MeshIO.hh>
#include "primo/io/mesh_io.h"
// clang-format on

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "primo/util/error.h"
#include "primo/mesh/geometry.h"
#include "support/test_support.h"

namespace fs = std::filesystem;

namespace {

using primo::Mesh;
using primo::PolygonSoup;
using primo::Vec3;
using primo::test::read_text;
using primo::test::shared_path;
using primo::test::temp_dir;
using primo::test::write_text;

// The bit pattern, so that -0.0 against 0.0 or a last-bit change counts as a difference.
uint64_t bits_of(double value) {
  uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

std::vector<std::vector<int>> faces_of(const Mesh& mesh) {
  std::vector<std::vector<int>> faces;
  for (auto f : mesh.faces()) {
    faces.emplace_back();
    for (auto v : f.vertices()) faces.back().push_back(v.idx());
  }
  return faces;
}

std::vector<Vec3> points_of(const Mesh& mesh) {
  std::vector<Vec3> points;
  for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
  return points;
}

std::map<int, int> degree_histogram(const Mesh& mesh) {
  std::map<int, int> histogram;
  for (auto f : mesh.faces()) ++histogram[int(f.valence())];
  return histogram;
}

std::vector<std::string> folder_entries(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename());
  return names;
}

// Tri, quad, tri, pentagon, tri: a small open disk whose faces differ in degree, in an order that
// a writer sorting or triangulating faces would change. The coordinates need all 17 digits, and
// include a negative zero and the smallest subnormal.
Mesh mixed_mesh() {
  const double grid[9][2] = {{0, 0}, {1, 0}, {2, 0},   {0, 1}, {1, 1},
                             {2, 1}, {0, 2}, {1, 2.5}, {2, 2}};
  PolygonSoup soup;
  for (int i = 0; i < 9; ++i)
    soup.points.emplace_back(grid[i][0] + 1e-3 * std::sin(1.7 * i),
                             grid[i][1] + 1e-3 * std::cos(2.3 * i), 0.1 * std::sin(0.9 * i + 0.3));
  soup.points[0].z() = -0.0;
  soup.points[1].z() = 4.9406564584124654e-324;
  soup.points[2].x() = 0.18477590650225734 + 2;
  soup.points[8].z() = 1e-300;
  soup.faces = {{1, 2, 5}, {0, 1, 4, 3}, {1, 5, 4}, {3, 4, 8, 7, 6}, {4, 5, 8}};
  return primo::mesh_from_soup(soup, "mixed_mesh");
}

// n x n planar quads (on a tilted plane, so that fan triangulation keeps the area).
Mesh quad_grid(int n) {
  PolygonSoup soup;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) soup.points.emplace_back(i * 0.5, j * 0.25, 0.01 * i + 0.02 * j);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      soup.faces.push_back({a, a + 1, a + n + 2, a + n + 1});
    }
  return primo::mesh_from_soup(soup, "quad_grid");
}

Mesh octahedron() {
  PolygonSoup soup;
  soup.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  soup.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (Vec3& p : soup.points) p += Vec3(0.1234567, -0.7654321, 0.3333333);
  return primo::mesh_from_soup(soup, "octahedron");
}

void expect_bit_exact_copy(const Mesh& expected, const Mesh& actual) {
  ASSERT_EQ(expected.n_vertices(), actual.n_vertices());
  const std::vector<Vec3> a = points_of(expected), b = points_of(actual);
  for (size_t v = 0; v < a.size(); ++v)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(bits_of(a[v][c]), bits_of(b[v][c]))
          << "vertex " << v << " coordinate " << c << ": " << a[v][c] << " became " << b[v][c];
  EXPECT_EQ(faces_of(expected), faces_of(actual));
}

std::string message_of_load(const std::string& path) {
  try {
    primo::load_mesh(path);
  } catch (const primo::Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "loading " << path << " threw a non-Error exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "loading " << path << " did not throw";
  return "";
}

// Writes `text` to a fresh file called `name` and returns the error that loading it gives.
std::string load_error(const std::string& name, const std::string& text) {
  const std::string path = temp_dir() + "/" + name;
  write_text(path, text);
  return message_of_load(path);
}

void expect_mentions(const std::string& message, const std::vector<std::string>& parts) {
  EXPECT_FALSE(message.empty());
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos)
        << "the message\n  " << message << "\ndoes not mention '" << part << "'";
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
}

// ---------------------------------------------------------------------------------------------

TEST(MeshIoRoundTrip, ObjKeepsDoublesVertexOrderAndFaceDegrees) {
  const Mesh mesh = mixed_mesh();
  const std::string path = temp_dir() + "/mixed.obj";
  primo::save_mesh(mesh, path);
  const Mesh loaded = primo::load_mesh(path);
  expect_bit_exact_copy(mesh, loaded);
  EXPECT_EQ((std::map<int, int>{{3, 3}, {4, 1}, {5, 1}}), degree_histogram(loaded));
}

TEST(MeshIoRoundTrip, OffKeepsDoublesVertexOrderAndFaceDegrees) {
  const Mesh mesh = mixed_mesh();
  const std::string path = temp_dir() + "/mixed.off";
  primo::save_mesh(mesh, path);
  expect_bit_exact_copy(mesh, primo::load_mesh(path));
  EXPECT_EQ(read_text(path).rfind("OFF\n9 5 ", 0), 0u) << read_text(path);
}

TEST(MeshIoRoundTrip, ObjIsWrittenWith17DigitsAndOneBasedNgons) {
  const std::string path = temp_dir() + "/mixed.obj";
  primo::save_mesh(mixed_mesh(), path);
  const std::string text = read_text(path);
  char expected_x[64];
  std::snprintf(expected_x, sizeof expected_x, "\nv %.17g ",
                mixed_mesh().point(Mesh::VertexHandle(2)).x());
  EXPECT_NE(text.find(expected_x), std::string::npos) << expected_x << " not in\n" << text;
  EXPECT_NE(text.find("\nf 4 5 9 8 7\n"), std::string::npos) << text;
}

TEST(MeshIoRoundTrip, OmKeepsDoubles) {
  const Mesh mesh = mixed_mesh();
  const std::string path = temp_dir() + "/mixed.om";
  primo::save_mesh(mesh, path);
  expect_bit_exact_copy(mesh, primo::load_mesh(path));
}

TEST(MeshIoRoundTrip, PlyKeepsTopologyAndFloatPrecision) {
  const Mesh mesh = mixed_mesh();
  const std::string path = temp_dir() + "/mixed.ply";
  primo::save_mesh(mesh, path);
  const Mesh loaded = primo::load_mesh(path);
  EXPECT_EQ(faces_of(mesh), faces_of(loaded));
  ASSERT_EQ(mesh.n_vertices(), loaded.n_vertices());
  for (auto v : mesh.vertices())
    EXPECT_LT((mesh.point(v) - loaded.point(v)).norm(), 1e-6) << "vertex " << v.idx();
}

TEST(MeshIoRoundTrip, StlTriangleMesh) {
  const Mesh mesh = octahedron();
  const std::string path = temp_dir() + "/octahedron.stl";
  primo::save_mesh(mesh, path);
  const Mesh loaded = primo::load_mesh(path);
  // STL has no shared vertices: OpenMesh merges equal corners, so only positions are compared.
  ASSERT_EQ(mesh.n_vertices(), loaded.n_vertices());
  ASSERT_EQ(mesh.n_faces(), loaded.n_faces());
  for (auto f : mesh.faces()) {
    std::vector<Vec3> expected, actual;
    for (auto v : f.vertices()) expected.push_back(mesh.point(v));
    for (auto v : OpenMesh::make_smart(loaded.face_handle(f.idx()), loaded).vertices())
      actual.push_back(loaded.point(v));
    ASSERT_EQ(expected.size(), actual.size());
    for (size_t k = 0; k < expected.size(); ++k)
      EXPECT_LT((expected[k] - actual[k]).norm(), 1e-6) << "face " << f.idx() << " corner " << k;
  }
}

TEST(MeshIoRoundTrip, StlOfQuadMeshWritesTriangles) {
  const Mesh mesh = quad_grid(3);
  const std::string path = temp_dir() + "/grid.stl";
  primo::save_mesh(mesh, path);
  const Mesh loaded = primo::load_mesh(path);
  EXPECT_EQ(16u, loaded.n_vertices());
  EXPECT_EQ(18u, loaded.n_faces());
  EXPECT_EQ((std::map<int, int>{{3, 18}}), degree_histogram(loaded));
  double area = 0, loaded_area = 0;
  for (double a : primo::compute_face_geometry(mesh).area) area += a;
  for (double a : primo::compute_face_geometry(loaded).area) loaded_area += a;
  EXPECT_NEAR(area, loaded_area, 1e-6);
}

TEST(MeshIoRoundTrip, ExtensionCaseDoesNotMatter) {
  const std::string folder = temp_dir();
  for (const std::string name : {"MIXED.OBJ", "Mixed.Off", "MIXED.PLY", "MIXED.OM"}) {
    primo::save_mesh(mixed_mesh(), folder + "/" + name);
    EXPECT_EQ(5u, primo::load_mesh(folder + "/" + name).n_faces()) << name;
  }
}

TEST(MeshIoRoundTrip, BinaryOffGoesThroughOpenMesh) {
  const Mesh mesh = mixed_mesh();
  const std::string path = temp_dir() + "/binary.off";
  ASSERT_TRUE(OpenMesh::IO::write_mesh(mesh, path, OpenMesh::IO::Options::Binary));
  ASSERT_EQ(read_text(path).rfind("OFF BINARY", 0), 0u);
  const Mesh loaded = primo::load_mesh(path);
  EXPECT_EQ(faces_of(mesh), faces_of(loaded));
}

// ---------------------------------------------------------------------------------------------

TEST(MeshIoRead, SpecCylinderSmall) {
  const std::string path = shared_path("spec/examples/cylinder-small.obj");
  if (!primo::test::exists(path)) GTEST_SKIP() << "shared spec example absent: " << path;
  const Mesh mesh = primo::load_mesh(path);
  EXPECT_EQ(208u, mesh.n_vertices());
  EXPECT_EQ(192u, mesh.n_faces());
  EXPECT_EQ((std::map<int, int>{{4, 192}}), degree_histogram(mesh));
  // "v 0.18477590650225734 0 0.076536686473017965": OpenMesh would give 0.18477590382099152.
  EXPECT_EQ(0.18477590650225734, mesh.point(mesh.vertex_handle(1)).x());
  EXPECT_EQ(0.076536686473017965, mesh.point(mesh.vertex_handle(1)).z());
}

TEST(MeshIoRead, SpecHexsphere) {
  const std::string path = shared_path("spec/examples/hexsphere.off");
  if (!primo::test::exists(path)) GTEST_SKIP() << "shared spec example absent: " << path;
  const Mesh mesh = primo::load_mesh(path);
  EXPECT_EQ(320u, mesh.n_vertices());
  EXPECT_EQ(162u, mesh.n_faces());
  const std::map<int, int> degrees = degree_histogram(mesh);
  EXPECT_EQ(162, degrees.at(5) + degrees.at(6));
  EXPECT_EQ(-0.5591252432832623, mesh.point(mesh.vertex_handle(0)).x());
  EXPECT_EQ(0.81679679896554436, mesh.point(mesh.vertex_handle(0)).y());
}

TEST(MeshIoRead, SharedSpotControlMesh) {
  const std::string path = shared_path("meshes/spot_control_mesh.obj");
  if (!primo::test::exists(path)) GTEST_SKIP() << "shared mesh absent: " << path;
  const Mesh mesh = primo::load_mesh(path);
  EXPECT_EQ(188u, mesh.n_vertices());
  EXPECT_EQ(180u, mesh.n_faces());
  EXPECT_EQ((std::map<int, int>{{3, 4}, {4, 160}, {5, 16}}), degree_histogram(mesh));
}

TEST(MeshIoRead, SharedCylinderWithNgonCaps) {
  const std::string path = shared_path("meshes/cylinder.obj");
  if (!primo::test::exists(path)) GTEST_SKIP() << "shared mesh absent: " << path;
  const Mesh mesh = primo::load_mesh(path);
  EXPECT_EQ(220u, mesh.n_vertices());
  EXPECT_EQ(202u, mesh.n_faces());
  EXPECT_EQ((std::map<int, int>{{4, 200}, {20, 2}}), degree_histogram(mesh));
}

TEST(MeshIoRead, ObjSyntaxVariants) {
  const std::string path = temp_dir() + "/variants.obj";
  write_text(path,
             "# comment\r\n"
             "mtllib variants.mtl\r\n"
             "o thing\r\n"
             "\r\n"
             "v 0 0 0\r\n"
             "v 1 0 0 1.0\r\n"              // homogeneous weight
             "v +1 1 0 0.5 0.25 0.125\r\n"  // vertex color
             "v 0 1 \\\r\n"
             "  0.0e0\r\n"  // continued
             "vt 0 0\r\nvt 1 0\r\nvt 1 1\r\n"
             "vn 0 0 1\r\n"
             "g group\r\n"
             "s 1\r\n"
             "usemtl material\r\n"
             "\tv 2 0 0   \r\n"
             "v 2 1 0 # trailing comment\r\n"
             "f 1/1 2/2 3/3 4/1\r\n"
             "f 2//1 5//1 -1//1\r\n"
             "l 1 2\r\n"
             "f -5/1/1 \\\n"
             "6/2/1 3/3/1\n"
             "s off\n");
  const Mesh mesh = primo::load_mesh(path);
  const std::vector<Vec3> expected_points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                                             {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  EXPECT_EQ(expected_points, points_of(mesh));
  EXPECT_EQ((std::vector<std::vector<int>>{{0, 1, 2, 3}, {1, 4, 5}, {1, 5, 2}}), faces_of(mesh));
}

TEST(MeshIoRead, OffVariants) {
  const std::vector<Vec3> expected_points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<std::vector<int>> expected_faces = {{0, 1, 2}, {0, 2, 3}};
  const std::map<std::string, std::string> files = {
      {"plain", "OFF\n4 2 5\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"},
      {"comments_crlf",
       "# made by hand\r\nOFF # header\r\n\r\n# counts next\r\n4 2 0\r\n0 0 0\r\n1 0 0\r\n"
       "1 1 0\r\n0 1 0\r\n# faces\r\n3 0 1 2\r\n3 0 2 3\r\n"},
      {"colors",
       "COFF\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 9\n"
       "3 0 1 2 255 0 0\n3 0 2 3 0.5 0.5 0.5 1\n"},
      {"normals_counts_on_header",
       "NOFF 4 2 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n"
       "3 0 1 2\n3 0 2 3\n"},
      {"colors_normals",
       "CNOFF\n4 2 0\n0 0 0 0 0 1 1 0 0 1\n1 0 0 0 0 1 1 0 0 1\n"
       "1 1 0 0 0 1 1 0 0 1\n0 1 0 0 0 1 1 0 0 1\n3 0 1 2\n3 0 2 3\n"},
      {"no_header", "4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"},
      {"no_edge_count", "OFF\n4 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"},
  };
  const std::string folder = temp_dir();
  for (const auto& [name, text] : files) {
    const std::string path = folder + "/" + name + ".off";
    write_text(path, text);
    try {
      const Mesh mesh = primo::load_mesh(path);
      EXPECT_EQ(expected_points, points_of(mesh)) << name;
      EXPECT_EQ(expected_faces, faces_of(mesh)) << name;
    } catch (const primo::Error& e) {
      ADD_FAILURE() << name << ": " << e.what();
    }
  }
}

TEST(MeshIoRead, UnusedVerticesAreKept) {
  const Mesh mesh = primo::mesh_from_soup(
      PolygonSoup{{{0, 0, 0}, {5, 5, 5}, {1, 0, 0}, {0, 1, 0}}, {{0, 2, 3}}}, "unused");
  EXPECT_EQ(4u, mesh.n_vertices());
  EXPECT_EQ((std::vector<std::vector<int>>{{0, 2, 3}}), faces_of(mesh));
}

// The zero-area test is relative to a face's own size and position: small faces are valid, down
// to where the area itself (|F| = ||a_F||, as the engine computes it) would underflow.
TEST(MeshIoRead, TinyButWellShapedFacesAreValid) {
  for (const double scale : {1e-70, 1e-9, 1.0, 1e70}) {
    for (const double offset : {0.0, 1000.0 * scale, 1e3}) {
      PolygonSoup soup;
      soup.points = {{offset, offset, 0}, {offset + scale, offset, 0}, {offset, offset + scale, 0}};
      soup.faces = {{0, 1, 2}};
      if (scale < 1e-15 * offset) continue;  // below what doubles at this offset can resolve
      EXPECT_NO_THROW(primo::mesh_from_soup(soup, "tiny")) << scale << " at " << offset;
    }
  }
}

// ---------------------------------------------------------------------------------------------

TEST(MeshIoErrors, MissingFile) {
  const std::string path = temp_dir() + "/nowhere.obj";
  expect_mentions(message_of_load(path), {path, "No such file"});
  const std::string ply = temp_dir() + "/nowhere.ply";
  expect_mentions(message_of_load(ply), {ply, "No such file"});
}

TEST(MeshIoErrors, UnknownOrMissingExtension) {
  expect_mentions(load_error("mesh.xyz", "v 0 0 0\n"), {"mesh.xyz", "'.xyz'", ".obj"});
  expect_mentions(load_error("mesh", "v 0 0 0\n"), {"mesh", "no extension"});
}

TEST(MeshIoErrors, EmptyFiles) {
  expect_mentions(load_error("empty.obj", ""), {"empty.obj", "empty mesh"});
  expect_mentions(load_error("comments.obj", "# nothing\nv 0 0 0\n"),
                  {"comments.obj", "empty mesh"});
  expect_mentions(load_error("empty.off", ""), {"empty.off", "empty"});
  expect_mentions(load_error("zero.off", "OFF\n0 0 0\n"), {"zero.off", "empty mesh"});
  expect_mentions(load_error("empty.stl", ""), {"empty.stl", "empty mesh"});
  expect_mentions(load_error("faceless.stl", "solid x\nendsolid x\n"),
                  {"faceless.stl", "empty mesh"});
}

TEST(MeshIoErrors, ObjSyntaxErrorsNameTheLine) {
  const std::string head = "# a triangle\nv 0 0 0\n";
  expect_mentions(load_error("short.obj", head + "v 1 0\nv 0 1 0\nf 1 2 3\n"),
                  {"short.obj", "line 3", "expected 3 coordinates after 'v'"});
  expect_mentions(load_error("word.obj", head + "v 1 0 zero\n"), {"word.obj", "line 3", "'zero'"});
  expect_mentions(load_error("corner.obj", head + "v 1 0 0\nv 0 1 0\nf 1/ 2 3\n"),
                  {"corner.obj", "line 5", "'1/'"});
  expect_mentions(load_error("corner2.obj", head + "v 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n"),
                  {"corner2.obj", "line 5", "'1/2/3/4'"});
  expect_mentions(load_error("nof.obj", head + "v 1 0 0\nv 0 1 0\nf\n"), {"nof.obj", "line 5"});
  expect_mentions(load_error("zero.obj", head + "v 1 0 0\nv 0 1 0\nf 0 1 2\n"),
                  {"zero.obj", "line 5", "index 0"});
  expect_mentions(load_error("relative.obj", head + "v 1 0 0\nv 0 1 0\nf -1 -2 -4\n"),
                  {"relative.obj", "line 5", "-4"});
  expect_mentions(load_error("unknown.obj", head + "vx 1 0 0\n"),
                  {"unknown.obj", "line 3", "'vx'"});
  expect_mentions(load_error("curve.obj", head + "curv 0 1 1 2\n"),
                  {"curve.obj", "line 3", "curv"});
  // A continued statement is reported at the line where it starts.
  expect_mentions(load_error("cont.obj", head + "v 1 \\\n 0\n"), {"cont.obj", "line 3"});
}

TEST(MeshIoErrors, IndexOutOfRange) {
  // OBJ: the 1-based index as written and the line.
  expect_mentions(load_error("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 9\n"),
                  {"range.obj", "line 6", "face 1", "index 9", "4 vertices"});
  // OFF indices are 0-based, as everywhere else.
  expect_mentions(
      load_error("range.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 4\n"),
      {"range.off", "face 1 (vertices 1, 3, 4)", "index 4", "out of range"});
  expect_mentions(load_error("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
                  {"negative.off", "face 0", "index -1"});
}

TEST(MeshIoErrors, FaceWithTwoVertices) {
  expect_mentions(load_error("two.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n"),
                  {"two.obj", "face 1 (vertices 0, 1)", "at least 3"});
  expect_mentions(load_error("two.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n2 0 1\n"),
                  {"two.off", "face 1 (vertices 0, 1)", "at least 3"});
}

TEST(MeshIoErrors, RepeatedVertex) {
  expect_mentions(
      load_error("repeat.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n4 1 3 2 3\n"),
      {"repeat.off", "face 1 (vertices 1, 3, 2, 3)", "vertex 3 appears more than once"});
  // The first repeat in the face's own order is named, not the smallest index.
  expect_mentions(
      load_error("repeat2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 3 1 3 1\n"),
      {"repeat2.obj", "face 0 (vertices 2, 0, 2, 0)", "vertex 2 appears more than once"});
}

TEST(MeshIoErrors, NonFiniteCoordinate) {
  expect_mentions(load_error("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n"),
                  {"nan.obj", "vertex 2", "non-finite", "(0, nan, 0)"});
  expect_mentions(load_error("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n"),
                  {"inf.off", "vertex 1", "non-finite", "-inf"});
  // Too large for a double: infinite, not a silently clamped number.
  expect_mentions(load_error("huge.obj", "v 0 0 0\nv 1e400 0 0\nv 0 1 0\nf 1 2 3\n"),
                  {"huge.obj", "vertex 1", "non-finite"});
  // Unused vertices are checked too: a NaN is never data.
  expect_mentions(load_error("unused.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nf 1 2 3\n"),
                  {"unused.obj", "vertex 3"});
}

TEST(MeshIoErrors, ZeroAreaFace) {
  // The decimal points are collinear; their doubles are not exactly, and still are rejected.
  expect_mentions(load_error("collinear.obj",
                             "v 0 0 0\nv 0.1 0.2 0.3\nv 0.3 0.6 0.9\nv 1 0 0\nf 4 2 1\nf 1 2 3\n"),
                  {"collinear.obj", "face 1 (vertices 0, 1, 2)", "zero area"});
  expect_mentions(
      load_error("coincident.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 0 0\n3 0 1 2\n3 1 0 3\n"),
      {"coincident.off", "face 1 (vertices 1, 0, 3)", "zero area"});
  // A self-intersecting "bowtie" quad: its Newell area cancels to zero.
  expect_mentions(load_error("twisted.obj", "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n"),
                  {"twisted.obj", "face 0", "zero area"});
}

TEST(MeshIoErrors, EdgeWithThreeFaces) {
  expect_mentions(load_error("fin.off",
                             "OFF\n5 3 0\n0 0 0\n1 0 0\n0.5 1 0\n0.5 -1 0\n0.5 0 1\n"
                             "3 0 1 2\n3 1 0 3\n3 0 1 4\n"),
                  {"fin.off", "face 2 (vertices 0, 1, 4)", "edge 0-1", "more than two faces",
                   "also faces 0, 1"});
}

TEST(MeshIoErrors, InconsistentOrientation) {
  // Faces 1 and 3 are both flipped; face 1 is named, against face 0.
  expect_mentions(
      load_error("flip.obj",
                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                 "f 1 2 3\nf 4 3 1\nf 2 5 3\nf 5 3 6\n"),
      {"flip.obj", "face 1 (vertices 3, 2, 0)", "edge 2-0", "face 0", "inconsistently oriented"});
  // The same error once the fin edge check cannot fire: two faces, same direction.
  expect_mentions(load_error("same.off",
                             "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n"
                             "3 0 1 2\n3 0 1 3\n"),
                  {"same.off", "face 1", "edge 0-1", "face 0", "inconsistently oriented"});
}

TEST(MeshIoErrors, NonManifoldVertex) {
  // Bowtie: two triangles touching only at vertex 2.
  expect_mentions(load_error("bowtie.obj",
                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 2 0\nv 1 2 0\n"
                             "f 1 2 3\nf 3 4 5\n"),
                  {"bowtie.obj", "vertex 2", "non-manifold", "2 separate fans", "face 0; face 1"});
  // Two closed tetrahedra sharing vertex 3: every vertex has as many faces as interior
  // edges, so only the fan structure shows it.
  expect_mentions(load_error("tetras.off",
                             "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 2\n0 1 2\n1 0 2\n"
                             "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n"
                             "3 3 4 5\n3 3 6 4\n3 4 6 5\n3 6 3 5\n"),
                  {"tetras.off", "vertex 3", "non-manifold", "faces 1, 2, 3; faces 4, 5, 7"});
}

TEST(MeshIoErrors, TruncatedOrMalformedOff) {
  expect_mentions(load_error("verts.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n"),
                  {"verts.off", "expected 4 vertices", "ends after 2"});
  expect_mentions(load_error("faces.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n"),
                  {"faces.off", "expected 2 faces", "ends after 1"});
  expect_mentions(load_error("header.off", "OFF\n"), {"header.off", "counts"});
  expect_mentions(load_error("short_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n"),
                  {"short_face.off", "line 6", "face 0", "expected 4 vertex indices, found 3"});
  expect_mentions(load_error("short_vertex.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n"),
                  {"short_vertex.off", "line 4", "vertex 1", "expected 3 coordinates"});
  expect_mentions(load_error("keyword.off", "PLY\n3 1 0\n"), {"keyword.off", "line 1", "'PLY'"});
  expect_mentions(load_error("counts.off", "OFF\n3 one 0\n"), {"counts.off", "line 2", "counts"});
  expect_mentions(load_error("fourd.off", "4OFF\n3 1 0\n"), {"fourd.off", "3D"});
  expect_mentions(load_error("extra.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n"),
                  {"extra.off", "line 7", "after the last of the 1 faces"});
}

TEST(MeshIoErrors, UnreadableOpenMeshFile) {
  expect_mentions(load_error("garbage.ply", "this is not a ply file\n"), {"garbage.ply", "PLY"});
}

// Each check reports the first offender in file order, and the checks run in the documented
// order (coordinates, face structure, edges, orientation, vertices, areas).
TEST(MeshIoErrors, FirstOffenderInFileOrder) {
  const std::string points = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 2 0\n";
  expect_mentions(load_error("first.obj", points + "f 1 2 3\nf 2 4 4\nf 1 1 3\n"), {"face 1 "});
  // Both a zero-area face (first in file) and a repeated vertex: structure is checked first.
  expect_mentions(load_error("order.obj", points + "f 1 2 2\n"), {"appears more than once"});
  expect_mentions(
      load_error("order2.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 inf 0\nf 1 2 3\nf 1 1 4\n"),
      {"vertex 3", "non-finite"});
}

TEST(MeshIoErrors, LongFacesAreAbbreviated) {
  PolygonSoup soup;
  std::vector<int> face;
  for (int i = 0; i < 30; ++i) {
    soup.points.emplace_back(std::cos(i * 0.2), std::sin(i * 0.2), 0);
    face.push_back(i);
  }
  face.back() = 0;
  soup.faces = {face};
  try {
    primo::mesh_from_soup(soup, "long");
    ADD_FAILURE() << "no error";
  } catch (const primo::Error& e) {
    expect_mentions(e.what(), {"long: face 0 (vertices 0, 1, 2, 3, 4, 5, 6, 7, ... (30 in all))",
                               "vertex 0 appears more than once"});
  }
}

// ---------------------------------------------------------------------------------------------

std::string message_of_save(const Mesh& mesh, const std::string& path) {
  try {
    primo::save_mesh(mesh, path);
  } catch (const primo::Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "saving " << path << " did not throw";
  return "";
}

TEST(MeshIoSave, MissingFolderThrowsAndLeavesNothing) {
  const std::string folder = temp_dir();
  const std::string path = folder + "/missing/out.obj";
  expect_mentions(message_of_save(mixed_mesh(), path), {path, "does not exist"});
  EXPECT_FALSE(fs::exists(folder + "/missing"));
  EXPECT_TRUE(folder_entries(folder).empty());
}

TEST(MeshIoSave, UnknownExtensionThrowsBeforeWriting) {
  const std::string folder = temp_dir();
  const std::string path = folder + "/out.xyz";
  write_text(path, "keep me");
  expect_mentions(message_of_save(mixed_mesh(), path), {path, "'.xyz'"});
  EXPECT_EQ("keep me", read_text(path));
  EXPECT_EQ(std::vector<std::string>{"out.xyz"}, folder_entries(folder));
}

TEST(MeshIoSave, FloatFormatsRefuseWhatRoundingWouldMakeUnreadable) {
  // A sliver that is a valid face in doubles and zero area in 32-bit floats (1 + 1e-9 rounds
  // to 1), and a mesh whose coordinates overflow floats: PLY, STL and glTF store floats, and
  // such a file would be refused by every reader, PriMo's included; OBJ keeps full precision.
  PolygonSoup sliver;
  sliver.points = {{1, 0, 0}, {1 + 1e-9, 0, 0}, {1, 1e-9, 0}};
  sliver.faces = {{0, 1, 2}};
  PolygonSoup huge;
  huge.points = {{0, 0, 0}, {1e39, 0, 0}, {0, 1e39, 0}};
  huge.faces = {{0, 1, 2}};
  const std::string folder = temp_dir();
  for (const PolygonSoup* soup : {&sliver, &huge}) {
    const primo::Mesh mesh = primo::mesh_from_soup(*soup, "test");
    for (const std::string ext : {".ply", ".stl", ".gltf", ".glb"}) {
      const std::string path = folder + "/out" + ext;
      write_text(path, "kept");
      expect_mentions(message_of_save(mesh, path), {path, "32-bit floats", "save as .obj"});
      EXPECT_EQ(read_text(path), "kept");
    }
    primo::save_mesh(mesh, folder + "/full.obj");
    EXPECT_EQ(primo::load_mesh(folder + "/full.obj").n_faces(), 1u);
  }
  // A well-shaped mesh is written as before.
  primo::save_mesh(mixed_mesh(), folder + "/mixed.ply");
  EXPECT_EQ(primo::load_mesh(folder + "/mixed.ply").n_vertices(), 9u);
}

TEST(MeshIoSave, ReplacesAnExistingFile) {
  const std::string folder = temp_dir();
  const std::string path = folder + "/out.off";
  write_text(path, "old contents");
  primo::save_mesh(mixed_mesh(), path);
  EXPECT_EQ(9u, primo::load_mesh(path).n_vertices());
  EXPECT_EQ(std::vector<std::string>{"out.off"}, folder_entries(folder));
}

// A write that fails half-way (here: the file size limit, as on a full disk) must leave the
// existing file alone and no temporary file behind. OpenMesh's own file writers report
// success in this situation, so PLY and OM are part of the test.
TEST(MeshIoSave, FailedWriteKeepsTheExistingFile) {
  const Mesh mesh = quad_grid(40);  // ~100 kB in every format
  for (const std::string name : {"big.obj", "big.off", "big.ply", "big.om", "big.stl"}) {
    const std::string folder = temp_dir();
    const std::string path = folder + "/" + name;
    write_text(path, "keep me");

    std::string message;
    {
      const primo::test::FileSizeLimit limit(4096);
      try {
        primo::save_mesh(mesh, path);
      } catch (const primo::Error& e) {
        message = e.what();
      }
    }

    expect_mentions(message, {path, "cannot save"});
    EXPECT_EQ("keep me", read_text(path)) << name;
    EXPECT_EQ(std::vector<std::string>{name}, folder_entries(folder));
  }
}

TEST(MeshIoSave, TargetThatIsAFolderIsLeftAlone) {
  const std::string folder = temp_dir();
  const std::string path = folder + "/taken.obj";
  fs::create_directory(path);
  write_text(path + "/inside.txt", "keep me");
  expect_mentions(message_of_save(mixed_mesh(), path), {path, "cannot save"});
  EXPECT_EQ("keep me", read_text(path + "/inside.txt"));
  EXPECT_EQ(std::vector<std::string>{"taken.obj"}, folder_entries(folder));
}

TEST(MeshIoSave, RelativePathInCurrentFolder) {
  const std::string folder = temp_dir();
  const fs::path previous = fs::current_path();
  fs::current_path(folder);
  EXPECT_NO_THROW(primo::save_mesh(mixed_mesh(), "here.obj"));
  fs::current_path(previous);
  EXPECT_EQ(std::vector<std::string>{"here.obj"}, folder_entries(folder));
}

}  // namespace
