// A glTF asset's buffer files (gltf_buffer_files.h) are checked as inputs before Assimp opens
// them: a named pipe there used to block the import for ever.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../../../src/core/io/scene/checks/gltf_buffer_files.h"
#include "primo/util/error.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using namespace primo;
using primo::test::error_of;
using primo::test::read_text;
using primo::test::source_path;
using primo::test::temp_dir;
using primo::test::write_text;

namespace {

// The shipped two-file glTF sample copied into a folder of its own.
std::string cube_folder() {
  const std::string dir = temp_dir() + "/cube";
  fs::create_directories(dir);
  fs::copy_file(source_path("assets/meshes/AnimatedMorphCube.gltf"), dir + "/cube.gltf");
  fs::copy_file(source_path("assets/meshes/AnimatedMorphCube.bin"), dir + "/AnimatedMorphCube.bin");
  return dir;
}

std::string u32(uint32_t v) {
  std::string s(4, '\0');
  for (int k = 0; k < 4; ++k) s[size_t(k)] = char((v >> (8 * k)) & 0xff);
  return s;
}

// A .glb holding only a JSON chunk: its buffers all name files. (Assimp 5.2 takes a .glb's
// first buffer for its binary chunk whatever its URI says, so such a file does not load; its
// buffer files are checked all the same.)
std::string glb_with_json(std::string json) {
  while (json.size() % 4 != 0) json += ' ';
  return "glTF" + u32(2) + u32(uint32_t(12 + 8 + json.size())) + u32(uint32_t(json.size())) +
         u32(0x4E4F534A) + json;
}

}  // namespace

TEST(GltfBufferFiles, AGltfWithItsBufferFileBesideItLoads) {
  const std::string dir = cube_folder();
  EXPECT_GT(load_mesh(dir + "/cube.gltf").n_faces(), 0u);
  // Relative to the working directory when the path has no folder, as Assimp looks it up.
  const fs::path before = fs::current_path();
  fs::current_path(dir);
  EXPECT_NO_THROW(detail::check_gltf_buffer_files(detail::gltf_outline(read_text("cube.gltf"), "cube.gltf"), "cube.gltf"));
  fs::current_path(before);
}

TEST(GltfBufferFiles, APipeAFolderOrAMissingFileIsNamedBeforeAssimpOpensIt) {
  const std::string dir = cube_folder();
  const std::string bin = dir + "/AnimatedMorphCube.bin";
  write_text(dir + "/cube.glb", glb_with_json(read_text(dir + "/cube.gltf")));
  struct Case {
    const char* what;
    std::function<void()> make;
  };
  const Case cases[] = {
      {"a named pipe", [&] { ASSERT_EQ(::mkfifo(bin.c_str(), 0600), 0); }},
      {"a folder", [&] { fs::create_directory(bin); }},
      {"No such file or directory", [] {}},
  };
  for (const Case& c : cases) {
    fs::remove_all(bin);
    c.make();
    for (const char* name : {"/cube.gltf", "/cube.glb"}) {
      const std::string path = dir + name;
      // In a child process with a time limit: before the check, the pipe blocked for ever.
      const test::CommandResult r =
          test::run_primo_within(20, "metrics '" + path + "' '" + path + "'");
      EXPECT_EQ(r.exit_code, 1) << c.what << " " << name << ": " << r.err;
      const std::string expected = path + ": buffer 0 (AnimatedMorphCube.bin): " + bin + ": ";
      EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(c.what), std::string::npos) << r.err;
      if (std::string(c.what) != "a named pipe") {  // in this process only where it cannot block
        EXPECT_NE(error_of([&] { load_mesh(path); }).find(expected), std::string::npos);
      }
    }
  }
}

TEST(GltfBufferFiles, EmbeddedBuffersAndUnparsableJsonAreLeftAlone) {
  const std::string dir = temp_dir();
  // A data: URI names no file; JSON that does not parse is Assimp's to report.
  nlohmann::json json = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"uri", "data:application/octet-stream;base64,AAAA"}, {"byteLength", 3}}}}};
  EXPECT_NO_THROW(detail::check_gltf_buffer_files(detail::gltf_outline(json.dump(), dir + "/a.gltf"), dir + "/a.gltf"));
  EXPECT_NO_THROW(detail::check_gltf_buffer_files(detail::gltf_outline("{ not json", dir + "/b.gltf"), dir + "/b.gltf"));
  EXPECT_NO_THROW(detail::check_gltf_buffer_files(detail::gltf_outline("glTF\x02", dir + "/c.glb"), dir + "/c.glb"));
  json["buffers"][0]["uri"] = "missing.bin";
  EXPECT_NE(error_of([&] {
              detail::check_gltf_buffer_files(detail::gltf_outline(json.dump(), dir + "/a.gltf"), dir + "/a.gltf");
            }).find(dir + "/a.gltf: buffer 0 (missing.bin): " + dir + "/missing.bin: cannot open"),
            std::string::npos);
  // glTF 1 keeps its buffers in an object by id.
  const nlohmann::json v1 = {{"asset", {{"version", "1.0"}}},
                             {"buffers", {{"geometry", {{"uri", "v1.bin"}}}}}};
  EXPECT_NE(error_of([&] {
              detail::check_gltf_buffer_files(detail::gltf_outline(v1.dump(), dir + "/v1.gltf"), dir + "/v1.gltf");
            }).find(dir + "/v1.gltf: buffer 'geometry' (v1.bin): " + dir + "/v1.bin: cannot open"),
            std::string::npos);
  // A .glb whose header claims a JSON chunk longer than the file: only what is there is read.
  const std::string glb = glb_with_json(json.dump());
  std::string lying = glb;
  lying.replace(12, 4, u32(0x7fffffff));
  EXPECT_LE(detail::gltf_json_text(lying).size(), lying.size());
}
