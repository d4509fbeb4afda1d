#include "paths.h"

#include <cstdlib>

namespace primo::editor {
namespace {

std::string from_env(const char* name, const char* fallback) {
  const char* value = std::getenv(name);
  return value && *value ? std::string(value) : std::string(fallback);
}

}  // namespace

std::string shader_dir() { return from_env("PRIMO_SHADER_DIR", PRIMO_SOURCE_SHADER_DIR); }

std::string asset_dir() { return from_env("PRIMO_ASSET_DIR", PRIMO_SOURCE_ASSET_DIR); }

std::string default_mesh_path() { return asset_dir() + "/meshes/spot_quadrangulated.obj"; }

}  // namespace primo::editor
