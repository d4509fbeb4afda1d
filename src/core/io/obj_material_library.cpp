// Reading .mtl files: only what glTF's materials can hold (diffuse colour, opacity, diffuse
// texture); the .mtl itself stays as it is, and an OBJ written back names it unchanged.

#include "obj_material_library.h"

#include <charconv>
#include <filesystem>
#include <sstream>
#include <string_view>
#include <vector>

#include "primo/util/error.h"
#include "primo/io/input_files.h"

namespace fs = std::filesystem;

namespace primo::detail {
namespace {

std::vector<std::string> words_of(const std::string& line) {
  std::string text = line.substr(0, line.find('#'));
  for (char& c : text)
    if (c == '\t' || c == '\r') c = ' ';
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

bool number(const std::string& word, double& value) {
  const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
  return result.ec == std::errc() && result.ptr == word.data() + word.size();
}

void read_library(MeshAttributes& attributes, const std::string& library) {
  const std::string text = read_input_file(library);
  std::istringstream lines(text);
  MeshMaterial* material = nullptr;
  for (std::string line; std::getline(lines, line);) {
    const std::vector<std::string> words = words_of(line);
    if (words.empty()) continue;
    if (words[0] == "newmtl") {
      material = nullptr;
      const std::string name = words.size() > 1 ? words[1] : "";
      for (MeshMaterial& m : attributes.materials)
        if (m.name == name) material = &m;
      continue;
    }
    if (!material) continue;  // a material no face uses
    double value;
    if (words[0] == "Kd" && words.size() >= 4) {
      for (int k = 0; k < 3; ++k)
        if (number(words[size_t(k) + 1], value)) material->base_color[size_t(k)] = value;
    } else if (words[0] == "d" && words.size() >= 2 && number(words[1], value)) {
      material->base_color[3] = value;
      if (value < 1) material->alpha_mode = "BLEND";
    } else if (words[0] == "map_Kd" && words.size() >= 2) {
      // Options (-s, -o, ...) come first; the file name is last.
      MeshImage image;
      image.uri = words.back();
      image.name = fs::path(image.uri).stem().string();
      image.folder = fs::path(library).parent_path().string();
      material->base_color_texture.image = int(attributes.images.size());
      attributes.images.push_back(std::move(image));
    }
  }
}

}  // namespace

std::string read_obj_material_libraries(MeshAttributes& attributes, const std::string& obj_path) {
  if (attributes.materials.empty()) return "";
  std::istringstream lines(attributes.obj_text);
  std::vector<std::string> unread;
  for (std::string line; std::getline(lines, line);) {
    const std::vector<std::string> words = words_of(line);
    if (words.empty() || words[0] != "mtllib") continue;
    for (size_t i = 1; i < words.size(); ++i) {
      const std::string library = (fs::path(obj_path).parent_path() / words[i]).string();
      try {
        read_library(attributes, library);
      } catch (const Error& e) {
        unread.push_back(e.what());
      }
    }
  }
  if (unread.empty()) return "";
  std::string note = obj_path + ": materials keep their names only: ";
  for (size_t i = 0; i < unread.size(); ++i) note += (i ? "; " : "") + unread[i];
  return note;
}

}  // namespace primo::detail
