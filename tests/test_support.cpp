#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace primo::test {

std::string source_path(const std::string& relative) {
  return std::string(PRIMO_SOURCE_DIR) + "/" + relative;
}

std::string shared_path(const std::string& relative) {
  return std::string(PRIMO_SHARED_DIR) + "/" + relative;
}

bool exists(const std::string& path) { return fs::exists(path); }

std::string temp_dir() {
  static std::atomic<int> counter{0};
  fs::path dir = fs::temp_directory_path() /
                 ("primo-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
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

CommandResult run_primo(const std::string& arguments) {
  const std::string dir = temp_dir();
  const std::string command = std::string(PRIMO_EXECUTABLE) + " " + arguments + " >" + dir +
                              "/out.txt 2>" + dir + "/err.txt";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(dir + "/out.txt"),
          read_text(dir + "/err.txt")};
}

}  // namespace primo::test

#include "primo/geometry.h"

namespace primo::test {

std::vector<int> faces_where(const Mesh& mesh, const std::function<bool(const Vec3&)>& keep) {
  const FaceGeometry g = compute_face_geometry(mesh);
  std::vector<int> faces;
  for (int f = 0; f < int(mesh.n_faces()); ++f)
    if (keep(g.centroid[f])) faces.push_back(f);
  return faces;
}

}  // namespace primo::test
