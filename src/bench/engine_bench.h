#pragma once
// `primo bench engine [--mesh PATH] [--json FILE] [--quick]`
//
// Measures the engine against the figures the paper quotes (Sect. 4: 67k local matches/s and
// 6,500 global prism updates/s on a 3.2 GHz Pentium 4; < 10 global iterations even for extreme
// deformations): local and global throughput and Newton iteration counts on a limb-like
// cylinder, and a global solve of a ~30k-face real mesh. Prints a table; --json writes the same
// figures (docs/performance.md).

#include <string>

namespace primo::bench {

struct EngineBenchOptions {
  std::string mesh;    // the real mesh; "" for kEngineBenchMesh in ../shared/meshes
  std::string json;    // also write the figures here ("" for none)
  bool quick = false;  // small cases only, no real mesh unless `mesh` is set: seconds
};

// The real mesh's default, looked up in a shared/meshes folder.
inline constexpr const char* kEngineBenchMesh = "armadillo_29k.obj";

// Prints the tables; returns the exit code. Throws primo::Error on bad options.
int run_engine_bench(const EngineBenchOptions& options);

}  // namespace primo::bench
