#pragma once
// Writing result files so that a failure never leaves a partial file behind: the commands, the
// editor (scenarios, sessions, preferences, autosaves) and the benchmarks all write through
// these. Meshes have their own atomic writer, save_mesh (primo/mesh_io.h).

#include <string>

namespace primo {

// Throws primo::Error unless `path` has a mesh extension we can write and its folder exists:
// a command checks this before minutes of work rather than after them.
void check_mesh_output_path(const std::string& path);

// Writes `text` to a temporary file beside `path` and renames it into place. Throws
// primo::Error naming `path` when its folder does not exist or the file cannot be written.
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace primo
