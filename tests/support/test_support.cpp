#include "test_support.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "../../src/core/io/scene/mesh_import_assimp.h"
#include "primo/util/error.h"
#include "primo/io/mesh_io.h"

namespace fs = std::filesystem;

namespace primo::test {

std::string source_path(const std::string& relative) {
  return std::string(PRIMO_SOURCE_DIR) + "/" + relative;
}

std::string shared_path(const std::string& relative) {
  return std::string(PRIMO_SHARED_DIR) + "/" + relative;
}

bool exists(const std::string& path) { return fs::exists(path); }

namespace {

// The directories handed out by temp_dir(), removed when the test process exits (each test
// runs in its own process under ctest), unless PRIMO_KEEP_TEST_FILES is set for a post-mortem.
class TempDirectories {
 public:
  ~TempDirectories() {
    if (std::getenv("PRIMO_KEEP_TEST_FILES")) return;
    std::error_code ignored;
    for (const fs::path& dir : dirs_) fs::remove_all(dir, ignored);
  }
  void add(const fs::path& dir) {
    std::lock_guard<std::mutex> lock(mutex_);
    dirs_.push_back(dir);
  }

 private:
  std::mutex mutex_;
  std::vector<fs::path> dirs_;
};

TempDirectories& temp_directories() {
  static TempDirectories dirs;
  return dirs;
}

}  // namespace

// The editor keeps autosaves and its recent-files list in the user's folders; tests must not
// touch the real ones (nor see what is there), so every test process gets its own.
const bool kUserFoldersIsolated = [] {
  const fs::path root = fs::temp_directory_path() / ("primo-test-user-" + std::to_string(::getpid()));
  ::setenv("PRIMO_STATE_DIR", (root / "state").c_str(), 1);
  ::setenv("PRIMO_CONFIG_DIR", (root / "config").c_str(), 1);
  temp_directories().add(root);
  return true;
}();

std::string temp_dir() {
  static std::atomic<int> counter{0};
  fs::path dir = fs::temp_directory_path() /
                 ("primo-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  temp_directories().add(dir);
  return dir.string();
}

FileSizeLimit::FileSizeLimit(unsigned long long bytes) {
  rlimit limit;
  if (getrlimit(RLIMIT_FSIZE, &limit) != 0) throw std::runtime_error("getrlimit(RLIMIT_FSIZE) failed");
  old_soft_limit_ = limit.rlim_cur;
  old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
  limit.rlim_cur = rlim_t(bytes);
  if (setrlimit(RLIMIT_FSIZE, &limit) != 0) {
    std::signal(SIGXFSZ, old_handler_);
    throw std::runtime_error("setrlimit(RLIMIT_FSIZE) failed");
  }
}

FileSizeLimit::~FileSizeLimit() {
  rlimit limit;
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0) {
    limit.rlim_cur = rlim_t(old_soft_limit_);
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  std::signal(SIGXFSZ, old_handler_);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

CommandResult run_primo(const std::string& arguments) { return run_primo_within(0, arguments); }

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

void expect_one_line_error(const std::function<void()>& load, const std::string& path,
                           const std::string& needle) {
  try {
    load();
    ADD_FAILURE() << path << ": no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(needle), std::string::npos) << message;
  }
}

void expect_refused_from_file_and_bytes(const std::string& path, const std::string& bytes,
                                        const std::string& needle) {
  write_text(path, bytes);
  expect_one_line_error([&] { load_mesh(path); }, path, needle);
  expect_one_line_error(
      [&] { detail::mesh_from_scene_soup(detail::read_scene_bytes(bytes, path), path); }, path,
      needle);
}

CommandResult run_primo_within(int seconds, const std::string& arguments) {
  const std::string dir = temp_dir();
  // timeout(1) sends SIGTERM, then SIGKILL 5 s later to a process that ignores it.
  const std::string limit =
      seconds > 0 ? "timeout -k 5 " + std::to_string(seconds) + " " : std::string();
  const std::string command =
      limit + PRIMO_EXECUTABLE + " " + arguments + " >" + dir + "/out.txt 2>" + dir + "/err.txt";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(dir + "/out.txt"),
          read_text(dir + "/err.txt")};
}

}  // namespace primo::test

#include <Eigen/Geometry>
#include <cmath>

#include "primo/mesh/geometry.h"

namespace primo::test {

std::vector<int> faces_where(const Mesh& mesh, const std::function<bool(const Vec3&)>& keep) {
  const FaceGeometry g = compute_face_geometry(mesh);
  std::vector<int> faces;
  for (int f = 0; f < int(mesh.n_faces()); ++f)
    if (keep(g.centroid[f])) faces.push_back(f);
  return faces;
}

BentCylinder bent_cylinder(int segments, int bands, double bend_deg, double twist_deg,
                           Fix top_fix, FaceShape shape) {
  constexpr double kRadius = 0.25, kLength = 2.0;
  BentCylinder c;
  c.mesh = make_cylinder(kRadius, kLength, segments, bands, shape);
  const double band = kLength / bands;
  Handle bottom{"bottom", faces_where(c.mesh, [&](const Vec3& p) { return p.y() < band; }),
                Fix::All, {}};
  Handle top{"top", faces_where(c.mesh, [&](const Vec3& p) { return p.y() > kLength - band; }),
             top_fix, {}};
  // Bend along a circular arc of the cylinder's length towards +x, twisting about the axis.
  const double theta = bend_deg * M_PI / 180.0;
  const double rho = theta > 0 ? kLength / theta : 0.0;
  const Vec3 end = theta > 0 ? Vec3(rho * (1 - std::cos(theta)), rho * std::sin(theta), 0)
                             : Vec3(0, kLength, 0);
  const Mat3 R = (Eigen::AngleAxisd(-theta, Vec3::UnitZ()) *
                  Eigen::AngleAxisd(twist_deg * M_PI / 180.0, Vec3::UnitY()))
                     .toRotationMatrix();
  const Vec3 top_center(0, kLength, 0);
  top.transform.rotation = R;
  top.transform.translation = end - R * top_center;
  c.handles = {bottom, top};
  c.diagonal = bounding_box_diagonal(c.mesh);
  return c;
}

double max_difference(const std::vector<BodyState>& a, const std::vector<BodyState>& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    d = std::max({d, (a[i].position - b[i].position).norm(), (a[i].rotation - b[i].rotation).norm()});
  return d;
}

}  // namespace primo::test
