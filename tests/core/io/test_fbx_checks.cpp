// An FBX file's records and model tree are checked before Assimp reads them
// (src/core/io/scene/checks/fbx_checks.h): a model that is its own parent, a cycle, an instancing
// bomb, a tree or a nesting too deep, a record running past its parent, in binary and ASCII files,
// are refused in one line naming the rule; real files still load.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "../../../src/core/io/scene/checks/fbx_checks.h"
#include "../../../src/core/io/scene/mesh_import_assimp.h"
#include "primo/util/error.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

namespace primo {
namespace {

// --- ASCII FBX --------------------------------------------------------------------------

// A triangle's geometry under model 2000, with `connections` after the geometry's own.
std::string ascii_fbx(const std::string& objects, const std::string& connections) {
  return R"(; FBX 7.4.0 project file
FBXHeaderExtension:  {
	FBXHeaderVersion: 1003
	FBXVersion: 7400
}
Objects:  {
	Geometry: 1000, "Geometry::tri", "Mesh" {
		Vertices: *9 {
			a: 0,0,0,1,0,0,0,1,0
		}
		PolygonVertexIndex: *3 {
			a: 0,1,-3
		}
	}
	Model: 2000, "Model::tri", "Mesh" {
		Version: 232
	}
)" + objects + R"(}
Connections:  {
	C: "OO",1000,2000
)" + connections + "}\n";
}

std::string models(int first, int count) {
  std::string out;
  for (int k = 0; k < count; ++k)
    out += "\tModel: " + std::to_string(first + k) + ", \"Model::m" + std::to_string(k) +
           "\", \"Null\" {\n\t\tVersion: 232\n\t}\n";
  return out;
}

std::string connection(long long child, long long parent) {
  return "\tC: \"OO\"," + std::to_string(child) + "," + std::to_string(parent) + "\n";
}

// --- binary FBX -------------------------------------------------------------------------

struct Record {
  std::string name;
  std::string properties;  // encoded
  int n_properties = 0;
  std::vector<Record> children;
  Record& L(int64_t v) { return raw('L', &v, 8); }
  Record& S(const std::string& s) {
    const uint32_t n = uint32_t(s.size());
    raw('S', &n, 4);
    properties += s;
    return *this;
  }
  Record& raw(char type, const void* data, size_t n) {
    properties += type;
    properties.append(static_cast<const char*>(data), n);
    ++n_properties;
    return *this;
  }
};

void put32(std::string& out, size_t at, uint32_t v) { std::memcpy(&out[at], &v, 4); }

// Writes `r` at the end of `out`, whose first byte is at file offset 0.
void encode(const Record& r, std::string& out) {
  const size_t begin = out.size();
  out.append(13, '\0');
  put32(out, begin + 4, uint32_t(r.n_properties));
  put32(out, begin + 8, uint32_t(r.properties.size()));
  out[begin + 12] = char(r.name.size());
  out += r.name + r.properties;
  for (const Record& c : r.children) encode(c, out);
  if (!r.children.empty()) out.append(13, '\0');
  put32(out, begin, uint32_t(out.size()));
}

std::string binary_fbx(const std::vector<Record>& top) {
  std::string out = std::string("Kaydara FBX Binary  ") + '\0' + "\x1a" + '\0';
  const uint32_t version = 7400;
  out.append(reinterpret_cast<const char*>(&version), 4);
  for (const Record& r : top) encode(r, out);
  out.append(13, '\0');
  out.append(16, '\xfa');  // a footer
  return out;
}

Record model(int64_t id) { return Record{"Model", "", 0, {}}.L(id).S(std::string("m\0\1Model", 8)).S("Null"); }
Record oo(int64_t child, int64_t parent) { return Record{"C", "", 0, {}}.S("OO").L(child).L(parent); }

void expect_refused(const std::string& name, const std::string& bytes, const std::string& needle) {
  const std::string path = test::temp_dir() + "/" + name;
  test::write_text(path, bytes);
  for (int from_memory = 0; from_memory < 2; ++from_memory) {
    try {
      if (from_memory)
        detail::read_scene_bytes(bytes, path);
      else
        load_mesh(path);
      ADD_FAILURE() << name << " loaded";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path + ": cannot read: not an FBX file PriMo accepts (", 0), 0u) << what;
      EXPECT_NE(what.find(needle), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(FbxChecks, AsciiModelTreesAreCheckedBeforeAssimpWalksThem) {
  const std::string root = connection(2000, 0);
  // Each crashed Assimp (a model its own parent, two each other's) or asked for 2^40 nodes.
  expect_refused("own-parent.fbx", ascii_fbx("", root + connection(2000, 2000)),
                 "model 2000 is its own parent");
  expect_refused("cycle.fbx",
                 ascii_fbx(models(3000, 1), connection(3000, 0) + connection(2000, 3000) +
                                                connection(3000, 2000)),
                 "has a cycle");
  std::string bomb = connection(3000, 0);
  for (int k = 0; k < 40; ++k) bomb += connection(3001 + k, 3000 + k) + connection(3001 + k, 3000 + k);
  expect_refused("bomb.fbx", ascii_fbx(models(3000, 41), bomb + connection(2000, 3040)),
                 "expands to more than 1000000 node instances");
  std::string chain = connection(3000, 0);
  for (int k = 0; k < 1200; ++k) chain += connection(3001 + k, 3000 + k);
  expect_refused("deep.fbx", ascii_fbx(models(3000, 1201), chain), "deeper than 1000 levels");
  expect_refused("nested.fbx", ascii_fbx(std::string(100, '{') + std::string(100, '}'), root),
                 "scopes nest deeper than 64 levels");
  // Sound trees load: the triangle under the root, and under a model listed once.
  const std::string dir = test::temp_dir();
  test::write_text(dir + "/triangle.fbx", ascii_fbx("", root));
  EXPECT_EQ(load_mesh(dir + "/triangle.fbx").n_faces(), 1u);
  test::write_text(dir + "/parented.fbx",
                   ascii_fbx(models(3000, 1), connection(3000, 0) + connection(2000, 3000)));
  EXPECT_EQ(load_mesh(dir + "/parented.fbx").n_faces(), 1u);
}

TEST(FbxChecks, BinaryRecordsAndModelTreesAreCheckedBeforeAssimpReadsThem) {
  const auto file = [](std::vector<Record> objects, std::vector<Record> connections) {
    return binary_fbx({Record{"Objects", "", 0, std::move(objects)},
                       Record{"Connections", "", 0, std::move(connections)}});
  };
  expect_refused("own-parent-binary.fbx", file({model(2000)}, {oo(2000, 0), oo(2000, 2000)}),
                 "model 2000 is its own parent");
  expect_refused("cycle-binary.fbx", file({model(2000), model(3000)}, {oo(2000, 3000), oo(3000, 2000)}),
                 "has a cycle");
  Record deep{"Deep", "", 0, {}};
  for (int k = 0; k < 100; ++k) deep = Record{"Deep", "", 0, {deep}};
  expect_refused("nested-binary.fbx", binary_fbx({deep}), "records nest deeper than 64 levels");
  // A record whose end lies past its parent's.
  std::string past = file({model(2000)}, {oo(2000, 0)});
  const size_t objects_end = 27;  // the Objects record's end offset, pushed far out
  put32(past, objects_end, uint32_t(past.size() + 100));
  expect_refused("past-binary.fbx", past, "runs past the file");
  // The shipped binary files load.
  EXPECT_GT(load_mesh(test::source_path("tests/data/scenes/phong_cube.fbx")).n_faces(), 0u);
  EXPECT_GT(load_mesh(test::source_path("assets/meshes/huesitos.fbx")).n_faces(), 0u);
}

}  // namespace
}  // namespace primo
