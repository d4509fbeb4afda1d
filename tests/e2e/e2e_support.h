#pragma once
// Helpers shared by the end-to-end tests: running the `primo` executable, their artifacts
// folder, small text files, and the bar scenario both tests pose.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "primo/mesh/mesh.h"

namespace primo::e2e {

inline const std::string kPrimo = PRIMO_EXECUTABLE;

// A fresh <build>/tests/e2e-artifacts/<test>/ folder (kept after the test for inspection).
inline std::string artifacts(const std::string& test) {
  const std::filesystem::path dir = std::filesystem::path(PRIMO_E2E_ARTIFACTS) / test;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Exit status of a shell command (-1 when it did not exit normally).
inline int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline double max_vertex_distance(const Mesh& a, const Mesh& b) {
  double m = 0;
  for (auto v : a.vertices())
    m = std::max(m, (a.point(v) - b.point(OpenMesh::VertexHandle(v.idx()))).norm());
  return m;
}

// A 0.2 x 1 x 0.2 bar of 4 x 40 quads per side: fixed base, position-only top, a softer
// middle. Writes dir/bar.obj and dir/bar-setup.json; returns the scenario's path.
inline std::string make_bar_scenario(const std::string& dir) {
  EXPECT_EQ(run(kPrimo + " generate bar --width 0.2 --length 1 --across 2 --along 20 -o " + dir +
                "/bar.obj > /dev/null"),
            0);
  const std::string path = dir + "/bar-setup.json";
  write_text(path, R"({
  "format": "primo-scenario/1",
  "mesh": "bar.obj",
  "regions": [ { "name": "soft middle", "select": { "box": { "min": [-1, 0.4, -1], "max": [1, 0.6, 1] } }, "height": 0.5 } ],
  "handles": [
    { "name": "base", "select": { "box": { "min": [-1, -1, -1], "max": [1, 0.06, 1] } }, "fix": "all" },
    { "name": "top", "select": { "box": { "min": [-1, 0.94, -1], "max": [1, 2, 1] } }, "fix": "position" }
  ]
})");
  return path;
}

// A tube (`primo generate cylinder` with `cylinder_options`) along y in `dir`, its bottom
// fixed and its top the handle "top" whose fix and transform are `top` (JSON members).
// Returns the scenario's path.
inline std::string make_tube_scenario(const std::string& dir, const std::string& cylinder_options,
                                      const std::string& top) {
  EXPECT_EQ(run(kPrimo + " generate cylinder " + cylinder_options + " -o " + dir +
                "/tube.obj > /dev/null"),
            0);
  const std::string path = dir + "/tube.json";
  write_text(path, R"({
  "format": "primo-scenario/1",
  "mesh": "tube.obj",
  "handles": [
    { "name": "bottom", "select": { "box": { "min": [-1, -1, -1], "max": [1, 0.05, 1] } }, "fix": "all" },
    { "name": "top", "select": { "box": { "min": [-1, 1.95, -1], "max": [1, 3, 1] } }, )" + top + R"( }
  ]
})");
  return path;
}

}  // namespace primo::e2e
