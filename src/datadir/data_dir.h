#pragma once
// Where `primo` finds its run-time files (the GLSL sources, the bundled assets). One lookup for
// the editor and the benchmarks, so that a build-tree binary and an installed one each find
// their own copy without being told.

#include <string>

namespace primo {

// The folder `name` ("shaders", "assets") of PriMo's data: the environment variable `env_var`
// when set; else the installed copy beside the running executable (bin/../share/primo/name);
// else the source tree's; else the configured install folder (named in errors when it is
// missing too).
std::string data_dir(const char* env_var, const char* name);

}  // namespace primo
