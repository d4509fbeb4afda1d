#include "autosave.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>

#include "primo/util/error.h"
#include "primo/io/output_files.h"
#include "primo/util/utf8.h"
#include "user_folders.h"

namespace primo::editor {
namespace fs = std::filesystem;
namespace {

std::string autosave_folder() { return state_folder() + "/autosave"; }

// The link beside an autosave that stands for a mesh whose name is not text.
constexpr const char* kMeshLinkInfix = ".mesh";

std::string mesh_link_path(const std::string& autosave, const std::string& mesh_path) {
  fs::path link(autosave);
  link.replace_extension(kMeshLinkInfix + escape_invalid_utf8(fs::path(mesh_path).extension().string()));
  return link.string();
}

}  // namespace

std::string autosave_path(const std::string& mesh_path) {
  std::error_code ec;
  const std::string absolute = fs::absolute(mesh_path, ec).lexically_normal().string();
  // The stem for people, a hash of the full path so that equal names in different folders
  // stay apart.
  const size_t hash = std::hash<std::string>{}(ec ? mesh_path : absolute);
  char suffix[20];
  std::snprintf(suffix, sizeof suffix, "%08zx", hash & 0xffffffffu);
  return autosave_folder() + "/" + escape_invalid_utf8(fs::path(mesh_path).stem().string()) + "-" +
         suffix + ".json";
}

std::string autosave_mesh_reference(const std::string& autosave, const std::string& mesh_path) {
  if (is_valid_utf8(mesh_path)) return mesh_path;
  const std::string link = mesh_link_path(autosave, mesh_path);
  std::error_code ec;
  const fs::path target = fs::absolute(mesh_path, ec);
  fs::create_directories(fs::path(autosave).parent_path(), ec);
  fs::remove(link, ec);
  fs::create_symlink(target, link, ec);
  if (ec)
    throw Error("cannot link to the mesh \"" + escape_invalid_utf8(mesh_path) + "\" from " + link +
                ": " + ec.message());
  return link;
}

std::string recovered_mesh_path(const std::string& mesh_path) {
  std::error_code ec;
  const fs::path path(mesh_path);
  const bool ours = fs::path(path).remove_filename() == fs::path(autosave_folder() + "/") &&
                    path.stem().extension() == kMeshLinkInfix;
  if (!ours || !fs::is_symlink(path, ec)) return mesh_path;
  const fs::path target = fs::read_symlink(path, ec);
  return ec ? mesh_path : target.string();
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
  // Its mesh link, whatever the mesh's extension.
  const fs::path autosave(path);
  for (const auto& entry : fs::directory_iterator(autosave.parent_path(), ec)) {
    const fs::path other = entry.path();
    if (other.stem().stem() == autosave.stem() && other.stem().extension() == kMeshLinkInfix &&
        entry.is_symlink(ec))
      fs::remove(other, ec);
  }
}

}  // namespace primo::editor
