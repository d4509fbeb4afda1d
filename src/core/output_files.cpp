#include "primo/output_files.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "primo/error.h"

namespace fs = std::filesystem;

namespace primo {
namespace {

// Lower-case extension with the dot (".obj"), or "" when there is none.
std::string extension_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace

void check_mesh_output_path(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl" && ext != ".om" &&
      ext != ".gltf" && ext != ".glb")
    throw Error(path + ": unknown output format '" + ext +
                "' (use .obj, .off, .ply, .stl, .om, .gltf or .glb)");
  const fs::path folder = fs::absolute(fs::path(path)).parent_path();
  if (!fs::is_directory(folder)) throw Error(path + ": the folder " + folder.string() + " does not exist");
}

void write_text_atomically(const std::string& path, const std::string& text) {
  const fs::path target = fs::absolute(fs::path(path));
  if (!fs::is_directory(target.parent_path()))
    throw Error(path + ": the folder " + target.parent_path().string() + " does not exist");
  const fs::path temp = target.parent_path() /
                        ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()));
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(temp, ignored);
      throw Error(path + ": cannot write the file");
    }
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw Error(path + ": cannot write the file");
  }
}

}  // namespace primo
