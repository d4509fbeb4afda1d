#include "autosave.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>

#include "primo/output_files.h"
#include "user_folders.h"

namespace primo::editor {
namespace fs = std::filesystem;
namespace {

std::string autosave_folder() { return state_folder() + "/autosave"; }

}  // namespace

std::string autosave_path(const std::string& mesh_path) {
  std::error_code ec;
  const std::string absolute = fs::absolute(mesh_path, ec).lexically_normal().string();
  // The stem for people, a hash of the full path so that equal names in different folders
  // stay apart.
  const size_t hash = std::hash<std::string>{}(ec ? mesh_path : absolute);
  char suffix[20];
  std::snprintf(suffix, sizeof suffix, "%08zx", hash & 0xffffffffu);
  return autosave_folder() + "/" + fs::path(mesh_path).stem().string() + "-" + suffix + ".json";
}

std::vector<AutosavedWork> list_autosaved_work() {
  std::vector<std::pair<fs::file_time_type, AutosavedWork>> found;
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (const auto& entry : fs::directory_iterator(autosave_folder(), ec)) {
    if (!entry.is_regular_file(ec) || entry.path().extension() != ".json") continue;
    const fs::file_time_type time = entry.last_write_time(ec);
    if (ec) continue;
    AutosavedWork w;
    w.path = entry.path().string();
    w.age_seconds = std::chrono::duration_cast<std::chrono::seconds>(now - time).count();
    const long long minutes = w.age_seconds / 60;
    w.label = entry.path().filename().string() + " (" +
              (minutes < 1 ? std::string("just now")
                           : minutes < 120 ? std::to_string(minutes) + " min ago"
                                           : std::to_string(minutes / 60) + " h ago") +
              ")";
    found.emplace_back(time, std::move(w));
  }
  std::sort(found.begin(), found.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<AutosavedWork> work;
  for (auto& f : found) work.push_back(std::move(f.second));
  return work;
}

void write_autosave(const std::string& path, const std::string& scenario_json) {
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  write_text_atomically(path, scenario_json);
}

void remove_autosave(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

}  // namespace primo::editor
