#pragma once
// `primo bench scaling [SCENARIO] [--mesh M] [--steps 0,1,2,3] [--bbox-handles] [--frames N]
//                      [--seed S] [--ordered-only] [--json FILE]`: how the interactive figures
// grow with the mesh. The scenario's mesh is Loop-subdivided 0, 1, 2, 3 times (the shared
// 60k-face bunny: about 60k, 240k, 1M and 4M faces) and the same pull is dragged on each, on
// the file's order and on a randomly renumbered copy (another tool's order). Every case runs
// as its own `primo bench drag` process, so that its peak memory is its own. Prints per case
// the setup, the frame median, the settle, the full solve from rest, the peak memory, time
// and memory a face, the renumbered copy against the file's order, and the lag the artist
// sees (the last frame's largest vertex distance from its converged shape).

#include <cstdint>
#include <string>
#include <vector>

namespace primo::bench {

struct ScalingBenchOptions {
  std::string scenario;  // default: assets/scenarios/bench/bunny-ears.json
  std::string mesh;      // instead of the scenario's (as `bench drag --mesh`)
  std::vector<int> steps = {0, 1, 2, 3};  // Loop steps, one size each
  bool bbox_handles = false;  // `bench drag --bbox-handles`: a pull that fits any mesh
  int frames = 60;
  std::uint64_t seed = 1;     // of the renumbered copies
  bool ordered_only = false;  // no renumbered copies
  std::string json;
};

// Prints the table; returns the exit code (1 when a case failed). Throws primo::Error on bad
// options.
int run_scaling_bench(const ScalingBenchOptions& options);

}  // namespace primo::bench
