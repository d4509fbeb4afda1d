#pragma once
// Writing result files so that a failure never leaves a partial file behind.

#include <string>

namespace primo::app {

// Lower-case extension with the dot (".obj"), or "" when there is none.
std::string extension_of(const std::string& path);

// Throws primo::Error unless `path` has a mesh extension we can write and its folder exists.
void check_mesh_output_path(const std::string& path);

// Writes `text` to a temporary file beside `path` and renames it into place.
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace primo::app
