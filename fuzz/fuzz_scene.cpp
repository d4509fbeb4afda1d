// libFuzzer target for one scene format read through Assimp: the format is
// PRIMO_FUZZ_EXTENSION (".gltf", ".glb", ".fbx", ".dae", ".3mf"), chosen at compile time. The
// bytes go through every check before Assimp, Assimp in its child process
// (src/core/io/scene/scene_reader_process.h) and, when they read, mesh_from_soup's validation. A
// primo::Error is the expected outcome for bad bytes, also when Assimp crashes in the child:
// that is what a user meets. A crash, a sanitizer report or another exception in this process
// is a finding. Assimp itself is Debian's build, not instrumented: coverage guides the checks
// and the parent's side, and the child's reading is a black box.
//
// 3MF is a zip that Assimp opens from a file only, so its bytes are written to a file first.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>

#include "../src/core/io/scene/mesh_import_assimp.h"
#include "../src/core/io/scene/scene_reader_process.h"
#include "primo/util/error.h"

namespace {

// Within libFuzzer's -timeout=10 and far below the machine's memory.
const primo::detail::ReaderProcessLimits kLimits{size_t(1500) << 20, 6.0};

std::string scratch_file() {
  const char* dir = getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/primo-fuzz-" + std::to_string(getpid()) +
         PRIMO_FUZZ_EXTENSION;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string extension = PRIMO_FUZZ_EXTENSION;
  try {
    primo::detail::SceneSoup scene;
    if (extension == ".3mf") {
      static const std::string path = scratch_file();
      std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
      scene = primo::detail::read_scene_file(path, &kLimits);
      primo::detail::mesh_from_scene_soup(scene, path);
    } else {
      const std::string path = "fuzz" + extension;
      scene = primo::detail::read_scene_bytes(bytes, path, &kLimits);
      primo::detail::mesh_from_scene_soup(scene, path);
    }
  } catch (const primo::Error&) {
  }
  return 0;
}
