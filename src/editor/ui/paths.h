#pragma once
// Where the editor finds its run-time files: the GLSL sources and the bundled assets. The
// source-tree folders are compiled in; PRIMO_SHADER_DIR and PRIMO_ASSET_DIR override them.

#include <string>

namespace primo::editor {

std::string shader_dir();
std::string asset_dir();
// assets/meshes/spot_quadrangulated.obj: what `primo` opens without arguments.
std::string default_mesh_path();

}  // namespace primo::editor
