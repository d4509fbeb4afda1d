#include "data_dir.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace fs = std::filesystem;

namespace primo {
namespace {

bool is_folder(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

}  // namespace

std::string data_dir(const char* env_var, const char* name) {
  const char* value = std::getenv(env_var);
  if (value && *value) return value;
  // Relative to the executable first: an install staged with DESTDIR, given another --prefix
  // at install time or unpacked from the .deb elsewhere uses its own files, not those of the
  // prefix the build was configured with. A build-tree binary has no share/ beside it.
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = (exe.parent_path() / PRIMO_BIN_TO_DATA_DIR / name).lexically_normal();
    if (is_folder(installed)) return installed.string();
  }
  // The build tree reads the source tree's files, so an edited shader or scenario counts
  // without an install.
  const fs::path source = fs::path(PRIMO_SOURCE_DIR) / name;
  if (is_folder(source)) return source.string();
  return (fs::path(PRIMO_INSTALL_DATA_DIR) / name).string();
}

}  // namespace primo
