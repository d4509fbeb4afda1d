#include "relative_paths.h"

#include <filesystem>
#include <system_error>

namespace fs = std::filesystem;

namespace primo::detail {

std::string path_from_folder(const std::string& file, const std::string& from_folder,
                             const std::string& to_folder) {
  std::error_code error;
  const fs::path target = fs::absolute(fs::path(from_folder) / file, error).lexically_normal();
  const fs::path folder = fs::absolute(to_folder, error).lexically_normal();
  const fs::path relative = target.lexically_relative(folder);
  return relative.empty() ? target.generic_string() : relative.generic_string();
}

std::string folder_of_file(const std::string& path) {
  const fs::path folder = fs::path(path).parent_path();
  return folder.empty() ? "." : folder.string();
}

}  // namespace primo::detail
