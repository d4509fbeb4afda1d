#include "paths.h"

#include "data_dir.h"

namespace primo::editor {

std::string shader_dir() { return data_dir("PRIMO_SHADER_DIR", "shaders"); }

std::string asset_dir() { return data_dir("PRIMO_ASSET_DIR", "assets"); }

std::string default_mesh_path() { return asset_dir() + "/meshes/spot_quadrangulated.obj"; }

}  // namespace primo::editor
