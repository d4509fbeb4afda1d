#pragma once
// Where the benchmarks find their inputs: the meshes of ../shared/meshes (third-party, not
// shipped with the repository) from wherever `primo` runs, and the shipped assets.

#include <string>

namespace primo::bench {

// The path of `name` in a `shared/meshes` folder above the working directory or the
// executable (either may be inside the repository), or "" when there is none.
std::string find_shared_mesh(const std::string& name);

// `mesh` as given when it is a file, else a bare file name looked up with find_shared_mesh;
// "" if neither.
std::string locate_mesh(const std::string& mesh);

// The assets folder the editor uses too (data_dir.h: installed or the repository's;
// PRIMO_ASSET_DIR overrides it): `primo bench quality` runs the scenarios of assets/scenarios/quality by default.
std::string asset_dir();

}  // namespace primo::bench
