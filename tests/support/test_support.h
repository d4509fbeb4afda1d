#pragma once
// Helpers shared by the unit tests: paths to shipped data, temporary files, running `primo`.

#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace primo::test {

// <repo>/<relative>
std::string source_path(const std::string& relative);
// <repo>/../shared/<relative>; shared data is optional, tests skip with a message when absent.
std::string shared_path(const std::string& relative);
bool exists(const std::string& path);
// A fresh, empty directory under the system temp dir, unique per call; removed when the test
// process exits (kept when PRIMO_KEEP_TEST_FILES is set).
std::string temp_dir();
// While it lives, files this process writes stop growing at `bytes` (RLIMIT_FSIZE), as on a
// full disk, and SIGXFSZ is ignored so that the write fails instead of killing the test; both
// are restored when it goes. Throws std::runtime_error when the limit cannot be set.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(unsigned long long bytes);
  ~FileSizeLimit();
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  unsigned long long old_soft_limit_ = 0;
  void (*old_handler_)(int) = nullptr;
};
// Writes `text` to `path` (truncating).
void write_text(const std::string& path, const std::string& text);
// The whole file, byte for byte ("" when it cannot be read).
std::string read_text(const std::string& path);
// The file parsed as JSON (throws when it cannot be read or parsed).
nlohmann::json read_json(const std::string& path);

// `primo ARGUMENTS` (the built executable) with its output captured.
struct CommandResult {
  int exit_code = -1;  // -1 when it did not exit normally
  std::string out, err;
};
CommandResult run_primo(const std::string& arguments);
// The same, stopped after `seconds` (then exit_code is 124, as timeout(1) reports it, or -1):
// for inputs that could make primo hang.
CommandResult run_primo_within(int seconds, const std::string& arguments);

// The message of the primo::Error that `action` throws, or "(no error)".
std::string error_of(const std::function<void()>& action);

// Expects (as a GoogleTest failure otherwise) that `load` throws a primo::Error whose message is
// one line starting with "<path>: " and containing `needle`.
void expect_one_line_error(const std::function<void()>& load, const std::string& path,
                           const std::string& needle);
// `bytes` written to `path` and read as a scene file from the file (load_mesh) and from memory
// (detail::read_scene_bytes): both one line naming the file and saying `needle`.
void expect_refused_from_file_and_bytes(const std::string& path, const std::string& bytes,
                                        const std::string& needle);

}  // namespace primo::test

#include <functional>
#include <vector>

#include "primo/model/constraints.h"
#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/model/rigid_system.h"

namespace primo::test {

// The largest difference between corresponding body states: of positions, or of rotation
// matrices (Frobenius norm).
double max_difference(const std::vector<BodyState>& a, const std::vector<BodyState>& b);

// Indices of the faces whose centroid satisfies `keep`.
std::vector<int> faces_where(const Mesh& mesh, const std::function<bool(const Vec3&)>& keep);

// A cylinder of radius 0.25 and length 2 along y, `segments` around and `bands` along, with
// its bottom band fixed and its top band a handle bent along a circular arc towards +x by
// `bend_deg` and twisted about its axis by `twist_deg`.
struct BentCylinder {
  Mesh mesh;
  std::vector<Handle> handles;
  double diagonal;
};
BentCylinder bent_cylinder(int segments, int bands, double bend_deg, double twist_deg = 0.0,
                           Fix top_fix = Fix::All, FaceShape shape = FaceShape::Quads);

}  // namespace primo::test
