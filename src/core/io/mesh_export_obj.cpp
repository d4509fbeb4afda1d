// OBJ written by PriMo: from the text the mesh was read from when there is one (so a pose
// changes positions and normals only, and everything else stays byte for byte), else from the
// mesh and its attributes.

#include "mesh_export_obj.h"

#include <charconv>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "relative_paths.h"

namespace fs = std::filesystem;

namespace primo::detail {

void append_number(std::string& out, double value) {
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
  out.append(buffer, result.ptr);
}

void append_point(std::string& out, const Vec3& p) {
  append_number(out, p.x());
  out += ' ';
  append_number(out, p.y());
  out += ' ';
  append_number(out, p.z());
}

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// The words of a statement, up to a '#' comment.
std::vector<std::string_view> words_of(std::string_view statement) {
  const size_t comment = statement.find('#');
  if (comment != std::string_view::npos) statement = statement.substr(0, comment);
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < statement.size()) {
    while (i < statement.size() &&
           (is_blank(statement[i]) || statement[i] == '\\' || statement[i] == '\n'))
      ++i;
    const size_t begin = i;
    while (i < statement.size() && !is_blank(statement[i]) && statement[i] != '\\' &&
           statement[i] != '\n')
      ++i;
    if (i > begin) words.push_back(statement.substr(begin, i - begin));
  }
  return words;
}

// The end of the statement starting at `begin` (a trailing backslash continues it on the next
// line), and where its line break starts.
size_t statement_end(std::string_view text, size_t begin, size_t& line_break) {
  size_t at = begin;
  while (true) {
    size_t end = text.find_first_of("\r\n", at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(at, end - at);
    const size_t comment = line.find('#');
    if (comment != std::string_view::npos) line = line.substr(0, comment);
    line_break = end;
    size_t next = end;
    if (next < text.size() && text[next] == '\r') ++next;
    if (next < text.size() && text[next] == '\n') ++next;
    if (line.empty() || line.back() != '\\' || next >= text.size()) return next;
    at = next;
  }
}

std::optional<std::string> rewritten_obj(const Mesh& mesh, const MeshAttributes& attributes,
                                         const std::string& path) {
  const std::string_view text = attributes.obj_text;
  const std::vector<Vec3> normals = corner_normals(mesh, attributes);
  const std::string source_folder = folder_of_file(attributes.obj_path);
  const std::string output_folder = folder_of_file(path);
  std::error_code error;
  const bool same_folder = fs::equivalent(source_folder, output_folder, error);
  std::string out;
  out.reserve(text.size() + text.size() / 4);
  size_t n_points = 0, n_normals = 0, begin = 0;
  while (begin < text.size()) {
    size_t line_break;
    const size_t end = statement_end(text, begin, line_break);
    const std::string_view statement = text.substr(begin, line_break - begin);
    const std::vector<std::string_view> words = words_of(statement);
    const std::string_view keyword = words.empty() ? std::string_view() : words[0];
    const size_t comment = statement.find('#');
    const std::string_view trailing =
        comment == std::string_view::npos ? std::string_view() : statement.substr(comment);
    if (keyword == "v") {
      if (n_points >= mesh.n_vertices() || words.size() < 4) return std::nullopt;
      out += "v ";
      append_point(out, mesh.point(Mesh::VertexHandle(int(n_points++))));
      for (size_t i = 4; i < words.size(); ++i) (out += ' ') += words[i];  // a colour
      if (!trailing.empty()) (out += ' ') += trailing;
    } else if (keyword == "vn") {
      if (n_normals >= normals.size() && attributes.n_normals > 0) return std::nullopt;
      out += "vn ";
      append_point(out, n_normals < normals.size() ? normals[n_normals] : Vec3(0, 0, 1));
      ++n_normals;
      if (!trailing.empty()) (out += ' ') += trailing;
    } else if (keyword == "mtllib" && !same_folder) {
      out += "mtllib";
      for (size_t i = 1; i < words.size(); ++i)
        (out += ' ') += path_from_folder(std::string(words[i]), source_folder, output_folder);
      if (!trailing.empty()) (out += ' ') += trailing;
    } else {
      out += statement;
    }
    out += text.substr(line_break, end - line_break);
    begin = end;
  }
  if (n_points != mesh.n_vertices()) return std::nullopt;
  return out;
}

}  // namespace

std::string obj_bytes(const Mesh& mesh, const MeshAttributes& attributes, const std::string& path) {
  if (!attributes.obj_text.empty())
    if (std::optional<std::string> text = rewritten_obj(mesh, attributes, path)) return *text;

  std::string out = "# PriMo: " + std::to_string(mesh.n_vertices()) + " vertices, " +
                    std::to_string(mesh.n_faces()) + " faces\n";
  for (auto v : mesh.vertices()) {
    out += "v ";
    append_point(out, mesh.point(v));
    out += '\n';
  }
  const CornerValues<2>* uvs = attributes.texcoords.empty() ? nullptr : &attributes.texcoords[0];
  if (uvs)
    for (const auto& uv : uvs->values) {
      out += "vt ";
      append_number(out, uv[0]);
      out += ' ';
      append_number(out, uv[1]);
      out += '\n';
    }
  for (const Vec3& n : corner_normals(mesh, attributes)) {
    out += "vn ";
    append_point(out, n);
    out += '\n';
  }
  int material = -1;
  size_t c = 0;
  for (auto f : mesh.faces()) {
    const size_t face = size_t(f.idx());
    if (face < attributes.face_material.size() && attributes.face_material[face] != material) {
      material = attributes.face_material[face];
      if (material >= 0) out += "usemtl " + attributes.materials[size_t(material)].name + '\n';
    }
    out += 'f';
    for (auto v : f.vertices()) {
      out += ' ';
      out += std::to_string(v.idx() + 1);
      const int t = uvs ? uvs->corner[c] : -1;
      const int n = c < attributes.normal_corner.size() ? attributes.normal_corner[c] : -1;
      if (t >= 0 || n >= 0) out += '/';
      if (t >= 0) out += std::to_string(t + 1);
      if (n >= 0) (out += '/') += std::to_string(n + 1);
      ++c;
    }
    out += '\n';
  }
  return out;
}

}  // namespace primo::detail
