#include "inputs.h"

#include <filesystem>
#include <vector>

#include "data_dir.h"

namespace fs = std::filesystem;

namespace primo::bench {

std::string find_shared_mesh(const std::string& name) {
  std::vector<fs::path> starts;
  std::error_code ec;
  starts.push_back(fs::current_path(ec));
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) starts.push_back(exe.parent_path());
  for (fs::path dir : starts) {
    for (int level = 0; level <= 4 && !dir.empty(); ++level) {
      const fs::path candidate = dir / "shared" / "meshes" / name;
      if (fs::is_regular_file(candidate, ec)) return candidate.string();
      if (dir == dir.parent_path()) break;
      dir = dir.parent_path();
    }
  }
  return "";
}

std::string locate_mesh(const std::string& mesh) {
  std::error_code ec;
  if (fs::is_regular_file(mesh, ec)) return mesh;
  if (fs::path(mesh).has_parent_path()) return "";
  return find_shared_mesh(mesh);
}

std::string asset_dir() { return data_dir("PRIMO_ASSET_DIR", "assets"); }

}  // namespace primo::bench
