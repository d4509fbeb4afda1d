#pragma once
// Internal to the core library: PriMo's own readers of the binary and OpenMesh-era formats
// (PLY ascii and binary, STL ascii and binary, OM, binary OFF). OpenMesh's readers crash, hang
// or read short on hostile bytes (docs/mesh-io.md, "Hostile files"), so no file is handed to
// them. Every reader takes the whole file in memory, checks each count against the bytes that
// are left before it allocates or loops, and throws primo::Error "<path>: <problem>".

#include <string>
#include <string_view>

#include "primo/io/mesh_io.h"

namespace primo::detail {

PolygonSoup read_ply(const std::string& path, std::string_view bytes);
PolygonSoup read_stl(const std::string& path, std::string_view bytes);
PolygonSoup read_om(const std::string& path, std::string_view bytes);
// `keyword` is the header word ("OFF", "COFF", "NOFF", ...: it says which extra numbers follow
// each vertex); `data` starts right after the "OFF BINARY" line.
PolygonSoup read_binary_off(const std::string& path, std::string_view keyword,
                            std::string_view data);

// `text` quoted for a message, at most 40 characters, control and non-ASCII bytes as \xNN: a
// file's bytes never reach the terminal raw.
std::string quoted(std::string_view text);

}  // namespace primo::detail
