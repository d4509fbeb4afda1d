// Hostile mesh files: the inputs a sanitizer-built fuzzing pass crashed, hung or
// misread OpenMesh's readers with, now read by PriMo's own (src/core/io/mesh_readers.cpp). Each
// must give one clear Error naming the file, or the right mesh; none may crash, hang or load
// short. fuzz/ holds the fuzz targets that found them; docs/reliability.md lists them.

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

namespace {

using primo::Mesh;
using primo::test::temp_dir;
using primo::test::write_text;

std::string load_error(const std::string& name, const std::string& bytes) {
  const std::string path = temp_dir() + "/" + name;
  write_text(path, bytes);
  try {
    primo::load_mesh(path);
  } catch (const primo::Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(0u, message.rfind(path, 0)) << "the message must start with the file: " << message;
    EXPECT_EQ(std::string::npos, message.find('\n')) << message;
    return message;
  }
  ADD_FAILURE() << name << " loaded";
  return "";
}

Mesh load_bytes(const std::string& name, const std::string& bytes) {
  const std::string path = temp_dir() + "/" + name;
  write_text(path, bytes);
  return primo::load_mesh(path);
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(std::string::npos, text.find(part)) << "'" << part << "' not in: " << text;
}

template <typename T>
void put(std::string& out, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

// A 4 x 4 vertex grid of 9 quads as binary OFF: Geomview's layout (big-endian, a colour count
// after each face) or OpenMesh's (little-endian, no colour count).
std::string binary_off(bool big_endian, bool colour_counts, int faces_declared = 9,
                       size_t cut = 0) {
  std::string out = "OFF BINARY\n";
  put<int32_t>(out, 16, big_endian);
  put<int32_t>(out, faces_declared, big_endian);
  put<int32_t>(out, 0, big_endian);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      put<float>(out, float(i), big_endian);
      put<float>(out, float(j), big_endian);
      put<float>(out, 0.0f, big_endian);
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      put<int32_t>(out, 4, big_endian);
      for (int v : {4 * j + i, 4 * j + i + 1, 4 * j + i + 5, 4 * j + i + 4})
        put<int32_t>(out, v, big_endian);
      if (colour_counts) put<int32_t>(out, 0, big_endian);
    }
  return out.substr(0, out.size() - cut);
}

const char* kAsciiPlyQuad =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

// --- crashes --------------------------------------------------------------------------------

TEST(HostileMeshes, PlyPropertyBeforeAnyElement) {
  // The 49-byte file that segfaulted OpenMesh's PLY reader.
  const std::string bytes = "ply\nformat ascii 1.0\nproperty float x\nend_header\n";
  EXPECT_EQ(49u, bytes.size());
  expect_contains(load_error("crash.ply", bytes), "'property' before any 'element'");
}

TEST(HostileMeshes, MutatedOmFilesAreErrorsOrMeshes) {
  // Every single-byte change of a small OM file (OpenMesh: heap overflows, use-after-free and an
  // assertion): each loads as a valid mesh or is one Error naming the file.
  const std::string folder = temp_dir();
  const std::string original = folder + "/grid.om";
  primo::save_mesh(primo::make_grid(1.0, 1.0, 2, 2, primo::FaceShape::Quads), original);
  const std::string bytes = primo::test::read_text(original);
  ASSERT_GT(bytes.size(), 100u);
  int errors = 0;
  for (size_t i = 0; i < bytes.size(); ++i)
    for (unsigned char value : {0x00, 0x7f, 0x80, 0xff}) {
      std::string mutated = bytes;
      mutated[i] = char(value);
      try {
        primo::parse_mesh_bytes(mutated, "mutated.om");
      } catch (const primo::Error& e) {
        ++errors;
        EXPECT_EQ(0u, std::string(e.what()).rfind("mutated.om: ", 0)) << e.what();
      }
    }
  EXPECT_GT(errors, 0);
  for (size_t cut = 1; cut < bytes.size(); ++cut)
    EXPECT_THROW(primo::parse_mesh_bytes(bytes.substr(0, cut), "cut.om"), primo::Error) << cut;
}

// --- hangs ----------------------------------------------------------------------------------

TEST(HostileMeshes, PlyWithoutEndHeader) {
  const auto start = std::chrono::steady_clock::now();
  expect_contains(load_error("endless.ply",
                             "ply\nformat ascii 1.0\nelement vertex 3\n"
                             "property float x\nproperty float y\n"),
                  "no 'end_header'");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

TEST(HostileMeshes, PlyHugeOrNegativeCounts) {
  expect_contains(load_error("minus.ply",
                             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face -1e308\n"
                             "property list uchar int vertex_indices\nend_header\n"),
                  "count from 0 to 2147483647");
  expect_contains(load_error("many.ply",
                             "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\n"
                             "property float x\nproperty float y\nproperty float z\nend_header\n"),
                  "has room for at most 0");
}

TEST(HostileMeshes, BinaryOffHugeOrNegativeCounts) {
  expect_contains(load_error("max.off", binary_off(true, true, 2147483647)), "room for at most");
  expect_contains(load_error("minus.off", binary_off(true, true, -1)), "negative counts");
}

// --- silent wrong results -------------------------------------------------------------------

TEST(HostileMeshes, BinaryOffInEitherByteOrderAndWithColourCounts) {
  for (bool big_endian : {true, false})
    for (bool colours : {true, false}) {
      const Mesh mesh = load_bytes("grid.off", binary_off(big_endian, colours));
      EXPECT_EQ(16u, mesh.n_vertices()) << big_endian << colours;
      EXPECT_EQ(9u, mesh.n_faces()) << big_endian << colours;
      EXPECT_EQ(3.0, mesh.point(Mesh::VertexHandle(15)).x());
    }
}

TEST(HostileMeshes, TruncatedFilesDoNotLoadShort) {
  expect_contains(load_error("cut.off", binary_off(true, true, 9, 10)), "truncated");
  const std::string ply = kAsciiPlyQuad;
  expect_contains(load_error("cut.ply", ply.substr(0, ply.size() - 6)), "truncated");
  const std::string stl =
      "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\n";
  expect_contains(load_error("cut.stl", stl), "ends early");
  expect_contains(load_error("cut2.stl", stl.substr(0, stl.find("facet normal", 10))),
                  "no 'endsolid'");
  std::string binary_stl(80, ' ');
  put<uint32_t>(binary_stl, 3, false);
  binary_stl += std::string(100, '\0');
  expect_contains(load_error("cut3.stl", binary_stl), "declares 3 triangles");
}

TEST(HostileMeshes, AsciiPlyAndStlLoad) {
  EXPECT_EQ(1u, load_bytes("quad.ply", kAsciiPlyQuad).n_faces());
  const Mesh stl = load_bytes(
      "two.stl",
      "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
  EXPECT_EQ(4u, stl.n_vertices());
  EXPECT_EQ(2u, stl.n_faces());
}

// --- messages -------------------------------------------------------------------------------

TEST(HostileMeshes, CarriageReturnOnlyObj) {
  const Mesh mesh =
      load_bytes("mac.obj", "# old Mac line ends\rv 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r");
  EXPECT_EQ(1u, mesh.n_faces());
  EXPECT_EQ(2, load_bytes("mixed.obj", "v 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2 3\n").n_faces() * 2);
}

TEST(HostileMeshes, ControlBytesAreNotEchoedRaw) {
  const std::string message = load_error("bell.obj", "v 0 0 0\nq\x1b[31m\x07 1 2\n");
  expect_contains(message, "\\x1B[31m\\x07");
  for (char c : message) EXPECT_TRUE(static_cast<unsigned char>(c) >= 0x20) << message;
}

}  // namespace
