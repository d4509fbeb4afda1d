#pragma once
// Where the editor finds its run-time files: the GLSL sources and the bundled assets, beside an
// installed primo or in the source tree (data_dir.h); PRIMO_SHADER_DIR and PRIMO_ASSET_DIR
// override them.

#include <string>

namespace primo::editor {

std::string shader_dir();
std::string asset_dir();
// assets/meshes/spot_quadrangulated.obj: what `primo` opens without arguments.
std::string default_mesh_path();

}  // namespace primo::editor
