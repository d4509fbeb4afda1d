// Mesh files. Every format is read by PriMo's own readers (OBJ and OFF here, in double
// precision: OpenMesh 9 reads both through float, which would move every vertex by up to 1e-8
// relative; PLY, STL, OM and binary OFF in mesh_readers.cpp, because OpenMesh's readers crash
// or hang on hostile bytes, docs/mesh-io.md), scene formats through Assimp; input files are
// opened through read_input_file. OBJ and OFF are written here, PLY, STL and OM through
// OpenMesh's writers. Whatever the format, the result is validated by mesh_from_soup, so every
// format is held to the same rules.

// OpenMesh's IO must be included before the mesh type (it registers readers and writers).
// clang-format off
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include "primo/io/mesh_io.h"
// clang-format on

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

#include "mesh_export_gltf.h"
#include "mesh_export_obj.h"
#include "scene/mesh_import_assimp.h"
#include "obj_material_library.h"
#include "mesh_readers.h"
#include "primo/util/error.h"
#include "primo/io/input_files.h"
#include "primo/io/mesh_import.h"
#include "primo/io/output_files.h"
#include "../mesh/mesh_validation.h"
#include "../mesh/silence_openmesh.h"

namespace fs = std::filesystem;

namespace primo {
namespace {

// Gltf and Glb are read through Assimp (mesh_import_assimp.cpp) and written by
// mesh_export_gltf.cpp; Scene (FBX, COLLADA, 3MF) is only read, through Assimp.
enum class Format { Obj, Off, Ply, Stl, Om, Gltf, Glb, Scene };

const char* const kSupportedExtensions =
    ".obj, .off, .ply, .stl, .om, .gltf, .glb, .fbx, .dae or .3mf";

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

[[noreturn]] void fail_at_line(const std::string& path, int line, const std::string& what) {
  fail(path, "line " + std::to_string(line) + ": " + what);
}

std::string lowercase(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string extension_of(const std::string& path) {
  return lowercase(fs::path(path).extension().string());
}

std::optional<Format> format_of(const std::string& extension) {
  if (extension == ".obj") return Format::Obj;
  if (extension == ".off") return Format::Off;
  if (extension == ".ply") return Format::Ply;
  if (extension == ".stl") return Format::Stl;
  if (extension == ".om") return Format::Om;
  if (extension == ".gltf") return Format::Gltf;
  if (extension == ".glb") return Format::Glb;
  if (extension == ".fbx" || extension == ".dae" || extension == ".3mf") return Format::Scene;
  return std::nullopt;
}

Format format_or_fail(const std::string& path, const std::string& action) {
  const std::string extension = extension_of(path);
  if (extension.empty())
    fail(path, action + ": the file name has no extension (expected " + kSupportedExtensions + ")");
  const std::optional<Format> format = format_of(extension);
  if (!format)
    fail(path, action + ": unknown mesh file extension '" + fs::path(path).extension().string() +
                   "' (expected " + kSupportedExtensions + ")");
  return *format;
}

std::string in_quotes(std::string_view text) { return detail::quoted(text); }

// ---------------------------------------------------------------------------------------------
// Splitting text into lines

// Physical lines with 1-based numbers, without the line break (LF or CRLF) and without a
// '#' comment. A UTF-8 byte order mark at the start is skipped.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") position_ = 3;
  }

  bool next(std::string_view& line) {
    if (position_ >= text_.size()) return false;
    // LF, CRLF or a lone CR (old Mac files): a CR-only file is not one long comment line.
    size_t end = text_.find_first_of("\r\n", position_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(position_, end - position_);
    position_ = end + 1;
    if (end + 1 < text_.size() && text_[end] == '\r' && text_[end + 1] == '\n') ++position_;
    ++number_;
    const size_t comment = line.find('#');
    if (comment != std::string_view::npos) line = line.substr(0, comment);
    return true;
  }

  int number() const { return number_; }
  size_t position() const { return std::min(position_, text_.size()); }

 private:
  std::string_view text_;
  size_t position_ = 0;
  int number_ = 0;
};

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

void split_words(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const size_t begin = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > begin) words.push_back(line.substr(begin, i - begin));
  }
}

// from_chars (locale-independent, exact) for the whole word; a leading '+' is allowed.
bool parse_double(std::string_view word, double& value) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-' && word[1] != '+') word.remove_prefix(1);
  const char* end = word.data() + word.size();
  const auto result = std::from_chars(word.data(), end, value);
  if (result.ptr != end || word.empty()) return false;
  if (result.ec == std::errc::result_out_of_range) {
    // Too large overflows to infinity (reported as non-finite later); too small is zero.
    const size_t exponent = word.find_first_of("eE");
    const bool tiny = exponent != std::string_view::npos && exponent + 1 < word.size() &&
                      word[exponent + 1] == '-';
    const double magnitude = tiny ? 0.0 : HUGE_VAL;
    value = word[0] == '-' ? -magnitude : magnitude;
    return true;
  }
  return result.ec == std::errc();
}

bool parse_integer(std::string_view word, long long& value) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-' && word[1] != '+') word.remove_prefix(1);
  const char* end = word.data() + word.size();
  const auto result = std::from_chars(word.data(), end, value);
  return !word.empty() && result.ec == std::errc() && result.ptr == end;
}

// ---------------------------------------------------------------------------------------------
// OBJ

// Statements that carry nothing a polygon mesh or its attributes need (grouping, the material
// library's name, display attributes, points and lines): kept in the text an OBJ is written
// back from (obj_text), not parsed.
bool is_ignored_obj_statement(std::string_view keyword) {
  static const char* const kIgnored[] = {
      "vp",       "g",          "o",         "s",      "mg",     "mtllib",
      "l",        "p",          "lod",       "bevel",  "c_interp",
      "d_interp", "shadow_obj", "trace_obj", "maplib", "usemap", "ctech", "stech"};
  for (const char* ignored : kIgnored)
    if (keyword == ignored) return true;
  return false;
}

bool is_free_form_obj_statement(std::string_view keyword) {
  static const char* const kFreeForm[] = {"cstype", "deg",  "bmat", "step", "curv", "curv2",
                                          "surf",   "parm", "trim", "hole", "scrv", "sp",
                                          "end",    "con",  "call", "csh"};
  for (const char* free_form : kFreeForm)
    if (keyword == free_form) return true;
  return false;
}

// One face corner: "i", "i/t", "i//n" or "i/t/n": the vertex, texture coordinate and normal
// references as written (0 for the ones the corner does not give).
struct ObjCorner {
  long long vertex = 0, texcoord = 0, normal = 0;
};

bool parse_obj_corner(std::string_view word, ObjCorner& corner) {
  corner = ObjCorner();
  const size_t slash = word.find('/');
  if (!parse_integer(word.substr(0, slash), corner.vertex)) return false;
  if (slash == std::string_view::npos) return true;
  const std::string_view rest = word.substr(slash + 1);
  const size_t second_slash = rest.find('/');
  const std::string_view texture = rest.substr(0, second_slash);
  if (second_slash == std::string_view::npos)
    return parse_integer(texture, corner.texcoord);
  if (!texture.empty() && !parse_integer(texture, corner.texcoord)) return false;
  return parse_integer(rest.substr(second_slash + 1), corner.normal);
}

// A texture coordinate or normal reference of a face corner as an index into what was read so
// far (`count`), -1 when the corner has none; relative (negative) references are resolved
// here, positive ones are checked at the end of the file.
int obj_attribute_index(long long reference, size_t count, const char* kind,
                        const std::string& path, int line_number) {
  if (reference == 0) return -1;
  const long long index = reference < 0 ? (long long)count + reference : reference - 1;
  if (index < 0)
    fail_at_line(path, line_number,
                 std::string("relative ") + kind + " index " + std::to_string(reference) +
                     " points before the first one (" + std::to_string(count) + " read so far)");
  if (index > INT_MAX)
    fail_at_line(path, line_number,
                 std::string(kind) + " index " + std::to_string(reference) + " is too large");
  return int(index);
}

PolygonSoup parse_obj(const std::string& path, std::string_view text) {
  PolygonSoup soup;
  MeshAttributes& attributes = soup.attributes;
  CornerValues<2> texcoords;
  size_t n_normals = 0;
  int material = -1;
  std::vector<int> face_lines;             // for index errors, which can only be judged at the end
  std::vector<long long> face_references;  // the 1-based (or relative) indices as written
  LineReader lines(text);
  std::string_view line;
  std::string continued;
  std::vector<std::string_view> words;
  while (lines.next(line)) {
    const int line_number = lines.number();
    // A trailing backslash continues the statement on the next line.
    if (!line.empty() && line.back() == '\\') {
      continued.assign(line.substr(0, line.size() - 1));
      continued += ' ';
      std::string_view more;
      while (lines.next(more)) {
        const bool continues = !more.empty() && more.back() == '\\';
        continued.append(more.substr(0, more.size() - (continues ? 1 : 0)));
        continued += ' ';
        if (!continues) break;
      }
      line = continued;
    }
    split_words(line, words);
    if (words.empty()) continue;
    const std::string_view keyword = words[0];

    if (keyword == "v") {
      if (words.size() < 4) fail_at_line(path, line_number, "expected 3 coordinates after 'v'");
      double values[3];
      for (size_t i = 1; i < words.size(); ++i) {
        double value;
        if (!parse_double(words[i], value))
          fail_at_line(path, line_number, in_quotes(words[i]) + " is not a number");
        if (i <= 3) values[i - 1] = value;  // then an optional weight or color: ignored
      }
      soup.points.emplace_back(values[0], values[1], values[2]);
    } else if (keyword == "vt") {
      if (words.size() < 2) fail_at_line(path, line_number, "expected a coordinate after 'vt'");
      std::array<double, 2> uv{0, 0};
      for (size_t i = 1; i < words.size(); ++i) {
        double value;
        if (!parse_double(words[i], value))
          fail_at_line(path, line_number, in_quotes(words[i]) + " is not a number");
        if (!std::isfinite(value))
          fail_at_line(path, line_number,
                       "texture coordinate " + in_quotes(words[i]) + " is not finite");
        if (i <= 2) uv[i - 1] = value;  // then an optional w: kept in the text only
      }
      texcoords.values.push_back(uv);
    } else if (keyword == "vn") {
      if (words.size() < 4) fail_at_line(path, line_number, "expected 3 numbers after 'vn'");
      double value;
      for (size_t i = 1; i < words.size(); ++i)
        if (!parse_double(words[i], value))
          fail_at_line(path, line_number, in_quotes(words[i]) + " is not a number");
      ++n_normals;  // its value is recomputed from the faces whenever the mesh is written
    } else if (keyword == "usemtl") {
      const std::string name = words.size() > 1 ? std::string(words[1]) : std::string();
      const auto known = std::find_if(attributes.materials.begin(), attributes.materials.end(),
                                      [&](const MeshMaterial& m) { return m.name == name; });
      material = int(known - attributes.materials.begin());
      if (known == attributes.materials.end()) {
        attributes.materials.emplace_back();
        attributes.materials.back().name = name;
      }
    } else if (keyword == "f" || keyword == "fo") {
      if (words.size() < 2) fail_at_line(path, line_number, "expected vertex indices after 'f'");
      std::vector<int> face;
      face.reserve(words.size() - 1);
      const long long n_points = static_cast<long long>(soup.points.size());
      for (size_t i = 1; i < words.size(); ++i) {
        ObjCorner corner;
        if (!parse_obj_corner(words[i], corner))
          fail_at_line(
              path, line_number,
              in_quotes(words[i]) + " is not a face vertex (expected i, i/t, i//n or i/t/n)");
        texcoords.corner.push_back(obj_attribute_index(corner.texcoord, texcoords.values.size(),
                                                       "texture coordinate", path, line_number));
        attributes.normal_corner.push_back(
            obj_attribute_index(corner.normal, n_normals, "normal", path, line_number));
        const long long reference = corner.vertex;
        if (reference == 0)
          fail_at_line(path, line_number, "vertex index 0 is invalid (OBJ indices start at 1)");
        // Negative indices count back from the last vertex read so far.
        const long long index = reference < 0 ? n_points + reference : reference - 1;
        if (index < 0)
          fail_at_line(path, line_number,
                       "relative vertex index " + std::to_string(reference) + " points before " +
                           "the first vertex (" + std::to_string(n_points) + " read so far)");
        if (index > INT_MAX)
          fail_at_line(path, line_number,
                       "vertex index " + std::to_string(reference) + " is too large");
        face.push_back(int(index));
        face_references.push_back(reference);
      }
      soup.faces.push_back(std::move(face));
      face_lines.push_back(line_number);
      attributes.face_material.push_back(material);
    } else if (is_ignored_obj_statement(keyword)) {
      continue;
    } else if (is_free_form_obj_statement(keyword)) {
      fail_at_line(
          path, line_number,
          "free-form geometry (" + in_quotes(keyword) + ") is not supported, only polygons");
    } else {
      fail_at_line(path, line_number, "unknown OBJ statement " + in_quotes(keyword));
    }
  }

  // Positive indices may refer to vertices listed later, so the range is checked here, with
  // the line and the index as the file writes them (1-based).
  size_t reference = 0;
  for (size_t f = 0; f < soup.faces.size(); ++f)
    for (int index : soup.faces[f]) {
      const long long written = face_references[reference++];
      if (index < int(soup.points.size())) continue;
      fail_at_line(path, face_lines[f],
                   "face " + std::to_string(f) + ": vertex index " + std::to_string(written) +
                       " is out of range (the file has " + std::to_string(soup.points.size()) +
                       " vertices)");
    }
  // The same for texture coordinates and normals, which a file without them must not name.
  reference = 0;
  for (size_t f = 0; f < soup.faces.size(); ++f)
    for (size_t k = 0; k < soup.faces[f].size(); ++k, ++reference) {
      const int t = texcoords.corner[reference], n = attributes.normal_corner[reference];
      if (t >= int(texcoords.values.size()))
        fail_at_line(path, face_lines[f],
                     "face " + std::to_string(f) + ": texture coordinate index " +
                         std::to_string(t + 1) + " is out of range (the file has " +
                         std::to_string(texcoords.values.size()) + " 'vt' lines)");
      if (n >= int(n_normals))
        fail_at_line(path, face_lines[f],
                     "face " + std::to_string(f) + ": normal index " + std::to_string(n + 1) +
                         " is out of range (the file has " + std::to_string(n_normals) +
                         " 'vn' lines)");
    }
  if (std::any_of(texcoords.corner.begin(), texcoords.corner.end(), [](int t) { return t >= 0; }))
    attributes.texcoords.push_back(std::move(texcoords));
  attributes.n_normals = int(n_normals);
  if (std::none_of(attributes.normal_corner.begin(), attributes.normal_corner.end(),
                   [](int n) { return n >= 0; })) {
    attributes.normal_corner.clear();
    attributes.n_normals = 0;
  }
  if (attributes.materials.empty()) attributes.face_material.clear();
  attributes.obj_text.assign(text);
  attributes.obj_path = path;
  return soup;
}

// ---------------------------------------------------------------------------------------------
// OFF

struct OffHeader {
  bool valid = false;
  std::string unsupported;  // why a valid keyword cannot be read, if it cannot
};

// [ST][C][N][4][n]OFF. Texture coordinates, colors and normals follow the coordinates of each
// vertex and are skipped; 4D and n-dimensional OFF are not meshes in 3D.
OffHeader parse_off_keyword(std::string_view word) {
  OffHeader header;
  if (word.size() < 3 || word.substr(word.size() - 3) != "OFF") return header;
  std::string_view prefix = word.substr(0, word.size() - 3);
  const auto take = [&prefix](std::string_view part) {
    if (prefix.substr(0, part.size()) != part) return false;
    prefix.remove_prefix(part.size());
    return true;
  };
  take("ST");
  take("C");
  take("N");
  const bool four_d = take("4");
  const bool n_d = take("n");
  if (!prefix.empty()) return header;
  header.valid = true;
  if (four_d || n_d) header.unsupported = "only 3D OFF is supported, not " + in_quotes(word);
  return header;
}

// Binary OFF ("OFF BINARY") is read by detail::read_binary_off from the byte after that line.
PolygonSoup parse_off(const std::string& path, std::string_view text) {
  LineReader lines(text);
  std::string_view line;
  std::vector<std::string_view> words;
  const auto next_words = [&] {
    while (lines.next(line)) {
      split_words(line, words);
      if (!words.empty()) return true;
    }
    return false;
  };

  if (!next_words()) fail(path, "the file is empty (expected an 'OFF' header)");
  // The header keyword is optional in the OFF format; the counts may share its line.
  size_t counts_start = 0;
  double ignored_number;
  if (!parse_double(words[0], ignored_number)) {
    const OffHeader header = parse_off_keyword(words[0]);
    if (!header.valid)
      fail_at_line(path, lines.number(), "expected the 'OFF' header, found " + in_quotes(words[0]));
    if (!header.unsupported.empty()) fail_at_line(path, lines.number(), header.unsupported);
    if (words.size() > 1 && words[1] == "BINARY")
      return detail::read_binary_off(path, words[0], text.substr(lines.position()));
    counts_start = 1;
    if (words.size() == 1) {
      if (!next_words()) fail(path, "the file ends after the header (expected the counts 'V F E')");
      counts_start = 0;
    }
  }
  const size_t n_counts = words.size() - counts_start;
  long long counts[3] = {0, 0, 0};
  bool counts_ok = n_counts == 2 || n_counts == 3;
  for (size_t i = 0; counts_ok && i < n_counts; ++i)
    counts_ok =
        parse_integer(words[counts_start + i], counts[i]) && counts[i] >= 0 && counts[i] <= INT_MAX;
  if (!counts_ok)
    fail_at_line(path, lines.number(),
                 "expected the counts 'V F E' (vertices, faces, edges) as non-negative integers");
  const long long n_vertices = counts[0], n_faces = counts[1];

  PolygonSoup soup;
  // A corrupt count must not allocate gigabytes: a vertex takes at least 6 bytes of text.
  soup.points.reserve(size_t(std::min<long long>(n_vertices, (long long)text.size() / 6)));
  for (long long v = 0; v < n_vertices; ++v) {
    if (!next_words())
      fail(path, "expected " + std::to_string(n_vertices) + " vertices, but the file ends after " +
                     std::to_string(v));
    if (words.size() < 3)
      fail_at_line(path, lines.number(),
                   "vertex " + std::to_string(v) + ": expected 3 coordinates, found " +
                       std::to_string(words.size()));
    double values[3];
    for (size_t i = 0; i < words.size(); ++i) {
      double value;
      if (!parse_double(words[i], value))
        fail_at_line(
            path, lines.number(),
            "vertex " + std::to_string(v) + ": " + in_quotes(words[i]) + " is not a number");
      if (i < 3) values[i] = value;  // then texture coordinates, normal or color: skipped
    }
    soup.points.emplace_back(values[0], values[1], values[2]);
  }

  soup.faces.reserve(size_t(std::min<long long>(n_faces, (long long)text.size() / 8)));
  for (long long f = 0; f < n_faces; ++f) {
    if (!next_words())
      fail(path, "expected " + std::to_string(n_faces) + " faces, but the file ends after " +
                     std::to_string(f));
    long long degree;
    if (!parse_integer(words[0], degree) || degree < 0)
      fail_at_line(path, lines.number(),
                   "face " + std::to_string(f) + ": expected the vertex count, found " +
                       in_quotes(words[0]));
    if (degree > static_cast<long long>(words.size()) - 1)
      fail_at_line(path, lines.number(),
                   "face " + std::to_string(f) + ": expected " + std::to_string(degree) +
                       " vertex indices, found " + std::to_string(words.size() - 1));
    std::vector<int> face(static_cast<size_t>(degree));
    for (size_t i = 1; i < words.size(); ++i) {
      if (i <= size_t(degree)) {
        long long index;
        if (!parse_integer(words[i], index) || index < INT_MIN || index > INT_MAX)
          fail_at_line(
              path, lines.number(),
              "face " + std::to_string(f) + ": " + in_quotes(words[i]) + " is not a vertex index");
        face[i - 1] = int(index);
      } else if (!parse_double(words[i], ignored_number)) {  // a color: skipped
        fail_at_line(path, lines.number(),
                     "face " + std::to_string(f) + ": " + in_quotes(words[i]) + " is not a number");
      }
    }
    soup.faces.push_back(std::move(face));
  }

  if (next_words())
    fail_at_line(path, lines.number(),
                 "unexpected data after the last of the " + std::to_string(n_faces) +
                     " faces the header declares");
  return soup;
}

// ---------------------------------------------------------------------------------------------
// Writing

using detail::append_point;

std::string off_text(const Mesh& mesh) {
  std::string out = "OFF\n" + std::to_string(mesh.n_vertices()) + " " +
                    std::to_string(mesh.n_faces()) + " " + std::to_string(mesh.n_edges()) + "\n";
  for (auto v : mesh.vertices()) {
    append_point(out, mesh.point(v));
    out += '\n';
  }
  for (auto f : mesh.faces()) {
    out += std::to_string(f.valence());
    for (auto v : f.vertices()) {
      out += ' ';
      out += std::to_string(v.idx());
    }
    out += '\n';
  }
  return out;
}

// STL holds triangles only (OpenMesh silently skips other faces), so each face becomes a fan
// around its first corner.
Mesh fan_triangulated(const Mesh& mesh) {
  Mesh triangles;
  for (auto v : mesh.vertices()) triangles.add_vertex(mesh.point(v));
  std::vector<Mesh::VertexHandle> corners;
  for (auto f : mesh.faces()) {
    corners.clear();
    for (auto v : f.vertices()) corners.push_back(Mesh::VertexHandle(v.idx()));
    for (size_t k = 1; k + 1 < corners.size(); ++k)
      triangles.add_face(corners[0], corners[k], corners[k + 1]);
  }
  return triangles;
}

// OpenMesh's file writers report success even when the disk is full (they do not check the
// stream), so OpenMesh writes into memory and the bytes are written here with every error checked.
std::string openmesh_bytes(const Mesh& mesh, const std::string& path, const std::string& extension,
                           OpenMesh::IO::Options options) {
  silence_openmesh();
  std::ostringstream stream(std::ios::out | std::ios::binary);
  if (!OpenMesh::IO::write_mesh(mesh, stream, extension, options, 17) || !stream)
    fail(path, "cannot save: OpenMesh could not write the " + extension + " data");
  return stream.str();
}

}  // namespace

PolygonSoup parse_mesh_bytes(std::string_view bytes, const std::string& path) {
  switch (format_or_fail(path, "cannot read")) {
    case Format::Obj: return parse_obj(path, bytes);
    case Format::Off: return parse_off(path, bytes);
    case Format::Ply: return detail::read_ply(path, bytes);
    case Format::Stl: return detail::read_stl(path, bytes);
    case Format::Om: return detail::read_om(path, bytes);
    case Format::Gltf:
    case Format::Glb:
    case Format::Scene:
      // A .gltf's buffers lie beside it: scene files are read from the file (load_mesh).
      fail(path, "cannot read: scene formats are read from their file, not from bytes");
  }
  fail(path, "cannot read: unhandled format");
}

Mesh load_mesh(const std::string& path) { return load_mesh_noted(path).mesh; }

namespace detail {

LoadedMesh load_polygon_file(const std::string& path) {
  format_or_fail(path, "cannot read");  // before the file is opened
  try {
    PolygonSoup soup = parse_mesh_bytes(read_input_file(path), path);
    LoadedMesh loaded{mesh_from_soup(soup, path), "", std::move(soup.attributes)};
    loaded.note = read_obj_material_libraries(loaded.attributes, path);
    return loaded;
  } catch (const std::bad_alloc&) {
    fail(path, "cannot read: out of memory");
  }
}

}  // namespace detail

namespace {

// PLY (as OpenMesh writes it), STL and glTF store 32-bit floats: a mesh whose faces rounding
// to them makes degenerate (or whose coordinates overflow them) would be written and then
// refused by every reader, PriMo's own included. Checked on the faces as they are written.
void check_float_rounding(const Mesh& mesh, const std::string& path, const char* format) {
  PolygonSoup soup;
  soup.points.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const Vec3& p = mesh.point(v);
    soup.points.emplace_back(double(float(p.x())), double(float(p.y())), double(float(p.z())));
  }
  soup.faces.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    std::vector<int> face;
    for (auto v : f.vertices()) face.push_back(v.idx());
    soup.faces.push_back(std::move(face));
  }
  try {
    detail::check_soup_geometry(soup, path);
  } catch (const Error& e) {
    std::string why = e.what();
    if (why.rfind(path + ": ", 0) == 0) why = why.substr(path.size() + 2);
    fail(path, std::string("cannot save: ") + format + " stores 32-bit floats, and rounded to them " +
                   why + "; save as .obj, .off or .om (full precision) instead");
  }
}

}  // namespace

std::string mesh_file_bytes(const Mesh& mesh, const std::string& path) {
  return mesh_file_bytes(mesh, MeshAttributes(), path);
}

std::string mesh_file_bytes(const Mesh& mesh, const MeshAttributes& attributes,
                            const std::string& path) {
  const Format format = format_or_fail(path, "cannot save");
  try {
    check_attributes(mesh, attributes, path + ": cannot save: the attributes do not fit the mesh");
  } catch (const std::bad_alloc&) {
    fail(path, "cannot save: out of memory");
  }
  if (format == Format::Scene)
    fail(path, "cannot save: " + fs::path(path).extension().string() +
                   " files are read, not written (save as .gltf or .glb for the same tools)");
  try {
    switch (format) {
      case Format::Obj: return detail::obj_bytes(mesh, attributes, path);
      case Format::Off: return off_text(mesh);
      case Format::Ply:
        check_float_rounding(mesh, path, "PLY");
        return openmesh_bytes(mesh, path, "ply", OpenMesh::IO::Options::Default);
      case Format::Om: return openmesh_bytes(mesh, path, "om", OpenMesh::IO::Options::Default);
      case Format::Stl:
        // Binary STL: exact float32, a fraction of the size of OpenMesh's 10-digit ASCII.
      {
        const Mesh triangles = fan_triangulated(mesh);
        check_float_rounding(triangles, path, "STL");
        return openmesh_bytes(triangles, path, "stl", OpenMesh::IO::Options::Binary);
      }
      case Format::Gltf:
      case Format::Glb:
        check_float_rounding(mesh, path, "glTF");
        return detail::gltf_bytes(mesh, attributes, format == Format::Glb,
                                  fs::path(path).stem().string(), path);
      case Format::Scene:
        break;  // refused above
    }
  } catch (const std::bad_alloc&) {
    fail(path, "cannot save: out of memory");
  }
  fail(path, "cannot save: unhandled format");
}

std::string save_note(const MeshAttributes& attributes, const std::string& path) {
  if (attributes.skin.empty()) return "";
  const std::optional<Format> format = format_of(extension_of(path));
  if (!format || *format == Format::Gltf || *format == Format::Glb) return "";
  std::string name = fs::path(path).extension().string().substr(1);
  for (char& c : name) c = char(std::toupper(static_cast<unsigned char>(c)));
  const size_t joints = attributes.skin.joints.size();
  return path + ": the skin (" + std::to_string(joints) + (joints == 1 ? " joint" : " joints") +
         ") is not saved: " + name + " holds none; save as .gltf or .glb to keep it";
}

void save_mesh(const Mesh& mesh, const std::string& path) {
  save_mesh(mesh, MeshAttributes(), path);
}

void save_mesh(const Mesh& mesh, const MeshAttributes& attributes, const std::string& path) {
  format_or_fail(path, "cannot save");
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code error;
  if (!fs::is_directory(folder, error))
    fail(path, "cannot save: the folder " + in_quotes(folder.string()) + " does not exist");
  if (fs::is_directory(target, error)) fail(path, "cannot save: this is a folder, not a file");
  StagedOutputs out;
  out.stage_mesh(path, mesh, attributes);
  out.commit();
}

}  // namespace primo
