#pragma once
// The benchmark meshes of ../shared/meshes (third-party, not shipped with the repository),
// found from wherever `primo` runs.

#include <string>

namespace primo::app {

// The path of `name` in a `shared/meshes` folder above the working directory or the
// executable (either may be inside the repository), or "" when there is none.
std::string find_shared_mesh(const std::string& name);

// `mesh` as given when it is a file, else a bare file name looked up with find_shared_mesh;
// "" if neither.
std::string locate_mesh(const std::string& mesh);

}  // namespace primo::app
