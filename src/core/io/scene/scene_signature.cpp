#include "scene_signature.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "primo/util/error.h"

namespace primo::detail {
namespace {

std::string lowercase(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return out;
}

// The bytes after a UTF-8 byte order mark and leading white space.
std::string_view trimmed(std::string_view head) {
  if (head.substr(0, 3) == "\xEF\xBB\xBF") head.remove_prefix(3);
  while (!head.empty() && std::isspace(static_cast<unsigned char>(head.front()))) head.remove_prefix(1);
  return head;
}

bool starts_with(std::string_view text, std::string_view prefix) {
  return text.substr(0, prefix.size()) == prefix;
}

bool contains_word(std::string_view head, std::string_view word) {
  return lowercase(head).find(word) != std::string::npos;
}

// Assimp's FBX reader looks for "fbx" in the first 200 bytes (binary files begin with
// "Kaydara FBX Binary", text ones with a "; FBX 7.x project file" comment).
bool looks_like_fbx(std::string_view head) {
  return starts_with(head, "Kaydara FBX Binary") || contains_word(head.substr(0, 200), "fbx");
}

bool looks_like_collada(std::string_view head) {
  return starts_with(trimmed(head), "<") && contains_word(head, "<collada");
}

bool looks_like_obj(std::string_view head) {
  // Lines of OBJ statements: "v x y z", "f ...", "vn", "vt", "o", "g", "#", "mtllib".
  size_t statements = 0;
  size_t at = 0;
  while (at < head.size()) {
    const size_t end = std::min(head.find('\n', at), head.size());
    const std::string_view line = trimmed(head.substr(at, end - at));
    at = end + 1;
    if (line.empty() || line.front() == '#') continue;
    if (starts_with(line, "v ") || starts_with(line, "vn ") || starts_with(line, "vt ") ||
        starts_with(line, "f ") || starts_with(line, "o ") || starts_with(line, "g ") ||
        starts_with(line, "mtllib ") || starts_with(line, "usemtl ") || starts_with(line, "s "))
      ++statements;
    else
      return false;
  }
  return statements > 0;
}

struct Format {
  const char* name;
  const char* extension;  // what to rename the file to, "" when PriMo does not read it
};

Format sniff(std::string_view head) {
  const std::string_view text = trimmed(head);
  if (starts_with(head, "glTF")) return {"GLB (binary glTF)", ".glb"};
  if (starts_with(head, "Kaydara FBX Binary")) return {"FBX", ".fbx"};
  if (starts_with(head, "PK\x03\x04")) return {"a zip archive (3MF?)", ".3mf"};
  if (starts_with(text, "ply")) return {"PLY", ".ply"};
  if (starts_with(text, "OFF") || starts_with(text, "COFF") || starts_with(text, "NOFF"))
    return {"OFF", ".off"};
  if (starts_with(text, "solid")) return {"STL", ".stl"};
  if (looks_like_collada(head)) return {"COLLADA", ".dae"};
  if (starts_with(text, "{") && contains_word(head, "\"asset\"")) return {"glTF", ".gltf"};
  if (starts_with(text, "{")) return {"JSON", ""};
  if (starts_with(text, "<")) return {"XML", ""};
  if (starts_with(text, "HIERARCHY")) return {"BVH (a skeleton, no mesh)", ""};
  if (starts_with(text, "*3DSMAX_ASCIIEXPORT")) return {"ASE", ""};
  if (starts_with(text, "Metric") || starts_with(text, "GeometryNode")) return {"OpenGEX", ""};
  if (contains_word(head.substr(0, 200), "; fbx")) return {"FBX", ".fbx"};
  if (looks_like_obj(head)) return {"OBJ", ".obj"};
  return {"", ""};
}

}  // namespace

std::string format_of_bytes(std::string_view head) { return sniff(head).name; }

void check_scene_signature(std::string_view head, const std::string& path) {
  const std::string ext = lowercase(std::filesystem::path(path).extension().string());
  bool matches = true;
  const char* format = "";
  if (ext == ".gltf") {
    format = "glTF";
    matches = starts_with(trimmed(head), "{");
  } else if (ext == ".glb") {
    format = "GLB (binary glTF)";
    matches = starts_with(head, "glTF");
  } else if (ext == ".fbx") {
    format = "FBX";
    matches = looks_like_fbx(head);
  } else if (ext == ".dae") {
    format = "COLLADA";
    matches = looks_like_collada(head);
  } else if (ext == ".3mf") {
    format = "3MF";
    matches = starts_with(head, "PK\x03\x04");
  }
  if (matches) return;
  const Format seen = sniff(head);
  std::string why;
  if (seen.name[0] == '\0')
    why = "its first bytes match no format PriMo reads";
  else if (seen.extension[0] == '\0')
    why = std::string("it looks like ") + seen.name + ", which PriMo does not read";
  else
    why = std::string("it looks like ") + seen.name + ": rename it " + seen.extension;
  const char* article = format[0] == 'F' ? "an" : "a";  // "an FBX file"
  throw Error(path + ": cannot read: not " + article + " " + format + " file (" + why + ")");
}

}  // namespace primo::detail
