#pragma once
// Internal to the core library: reading the scene formats (glTF 2.0, FBX, COLLADA, 3MF) through
// Assimp into one polygon soup (docs/mesh-io.md, "Scene formats"). primo/io/mesh_import.h is the
// public side.

#include <string>
#include <string_view>

#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"

namespace primo::detail {

struct ReaderProcessLimits;  // scene_reader_process.h

// A scene baked into one soup, with what was merged and left out.
struct SceneSoup {
  PolygonSoup soup;
  std::string note;   // one line, "" when there is nothing to say
  std::string parts;  // for validation errors of several joined meshes: "faces 0-11 'Cube', ..."
};

// Reads the file through Assimp, so that buffers and files it refers to (a .gltf's .bin) are
// found beside it; Assimp runs in a child process (scene_reader_process.h). Throws Error
// "<path>: ..." when a check before Assimp or Assimp rejects the file, Assimp crashes or
// outgrows its limits, or the scene holds no mesh.
// `limits` replaces reader_process_limits' for the file's size (the fuzz targets' shorter time).
SceneSoup read_scene_file(const std::string& path, const ReaderProcessLimits* limits = nullptr);

// The same from bytes in memory (for the fuzz targets): `path` picks the format by extension
// and names the file in errors; files the bytes refer to are not read.
SceneSoup read_scene_bytes(std::string_view bytes, const std::string& path,
                           const ReaderProcessLimits* limits = nullptr);

// load_mesh_noted for the formats PriMo parses itself (mesh_io.cpp): an OBJ's attributes and
// material libraries, the others' mesh alone.
LoadedMesh load_polygon_file(const std::string& path);

// mesh_from_soup, and when several meshes were joined, the error says which faces came from
// which.
Mesh mesh_from_scene_soup(const SceneSoup& scene, const std::string& path);

}  // namespace primo::detail
