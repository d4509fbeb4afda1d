#include "user_folders.h"

#include <cstdlib>

namespace primo::editor {
namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? std::string(v) : std::string();
}

std::string folder(const char* override_name, const char* xdg_name, const char* fallback) {
  if (std::string o = env(override_name); !o.empty()) return o;
  if (std::string x = env(xdg_name); !x.empty()) return x + "/primo";
  const std::string home = env("HOME");
  return (home.empty() ? std::string(".") : home) + "/" + fallback + "/primo";
}

}  // namespace

std::string state_folder() { return folder("PRIMO_STATE_DIR", "XDG_STATE_HOME", ".local/state"); }
std::string config_folder() { return folder("PRIMO_CONFIG_DIR", "XDG_CONFIG_HOME", ".config"); }

}  // namespace primo::editor
