#pragma once
// Internal to the core library: a file a written mesh refers to (an OBJ's material library, a
// glTF's image) named from the written file's folder.

#include <string>

namespace primo::detail {

// `file`, relative to `from_folder` (or absolute), as a path relative to `to_folder`; the
// absolute path when there is no relative one. Forward slashes, as OBJ and glTF want them.
std::string path_from_folder(const std::string& file, const std::string& from_folder,
                             const std::string& to_folder);

// The folder of `path` ("." for a bare file name).
std::string folder_of_file(const std::string& path);

}  // namespace primo::detail
