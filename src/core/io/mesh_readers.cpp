// PriMo's readers of PLY, STL, OM and binary OFF (see mesh_readers.h). They replace OpenMesh's,
// which a fuzzing pass crashed (a PLY 'property' before any 'element', mutated OM files: heap
// overflows, use-after-free, an assertion), hung (a PLY header without 'end_header', counts of
// -1e308 or INT_MAX) and misread (binary OFF in the wrong byte order, per-face colour counts,
// truncated files loading short). Rules common to all of them:
//  - a count is checked against the bytes left in the file before anything is reserved or
//    looped over (every element takes at least one byte);
//  - a file that ends early is an error naming what was being read, never a short mesh;
//  - indices are range-checked here or by mesh_from_soup, never used to address memory first.

#include "mesh_readers.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <vector>

#include "primo/util/error.h"

namespace primo::detail {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

std::string str(long long n) { return std::to_string(n); }

// Little-endian or big-endian scalars from a byte buffer, every read bounds-checked.
class ByteReader {
 public:
  ByteReader(std::string_view data, const std::string& path, bool big_endian)
      : data_(data), path_(path), big_endian_(big_endian) {}

  size_t left() const { return data_.size() - position_; }
  size_t position() const { return position_; }

  void need(size_t n, const std::string& what) const {
    if (n > left()) fail(path_, "the file ends early (truncated?) in " + what);
  }
  void skip(size_t n, const std::string& what) {
    need(n, what);
    position_ += n;
  }

  template <typename T>
  T get(const std::string& what) {
    need(sizeof(T), what);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    if (big_endian_) std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  // Throws unless `count` items of at least `min_bytes` each fit in what is left.
  void check_count(uint64_t count, size_t min_bytes, const std::string& what) const {
    if (min_bytes > 0 && count > left() / min_bytes)
      fail(path_, what + ": the file declares " + std::to_string(count) +
                      " but has room for at most " + std::to_string(left() / min_bytes) +
                      " (corrupt count or truncated file)");
  }

 private:
  std::string_view data_;
  const std::string& path_;
  bool big_endian_;
  size_t position_ = 0;
};

bool parse_number(std::string_view word, double& value) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-') word.remove_prefix(1);
  const char* end = word.data() + word.size();
  const auto result = std::from_chars(word.data(), end, value);
  if (word.empty() || result.ptr != end) return false;
  if (result.ec == std::errc::result_out_of_range) {  // huge: infinite (rejected later); tiny: 0
    const size_t e = word.find_first_of("eE");
    const bool tiny = e != std::string_view::npos && e + 1 < word.size() && word[e + 1] == '-';
    value = (word[0] == '-' ? -1.0 : 1.0) * (tiny ? 0.0 : HUGE_VAL);
    return true;
  }
  return result.ec == std::errc();
}

bool parse_count(std::string_view word, long long& value) {
  const char* end = word.data() + word.size();
  const auto result = std::from_chars(word.data(), end, value);
  return !word.empty() && result.ec == std::errc() && result.ptr == end;
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// Whitespace-separated words of a text, with the line each starts on.
class WordReader {
 public:
  explicit WordReader(std::string_view text) : text_(text) {}
  std::optional<std::string_view> next() {
    while (position_ < text_.size() && is_space(text_[position_])) {
      if (text_[position_] == '\n') ++line_;
      ++position_;
    }
    if (position_ >= text_.size()) return std::nullopt;
    const size_t begin = position_;
    while (position_ < text_.size() && !is_space(text_[position_])) ++position_;
    return text_.substr(begin, position_ - begin);
  }
  int line() const { return line_; }
  size_t left() const { return text_.size() - position_; }
  // The rest of the current line (an STL solid's name).
  void skip_line() {
    while (position_ < text_.size() && text_[position_] != '\n') ++position_;
  }

 private:
  std::string_view text_;
  size_t position_ = 0;
  int line_ = 1;
};

// ---------------------------------------------------------------------------------------------
// PLY

enum class PlyType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

std::optional<PlyType> ply_type(std::string_view name) {
  static const std::pair<const char*, PlyType> kTypes[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::Uint8},
      {"uint8", PlyType::Uint8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::Uint16},  {"uint16", PlyType::Uint16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::Uint32},     {"uint32", PlyType::Uint32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [word, type] : kTypes)
    if (name == word) return type;
  return std::nullopt;
}

size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::Uint8:
      return 1;
    case PlyType::Int16:
    case PlyType::Uint16:
      return 2;
    case PlyType::Int32:
    case PlyType::Uint32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

bool ply_integral(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;
  bool is_list = false;
  PlyType count_type = PlyType::Uint8;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

// One value of a PLY body, ascii or binary.
class PlyValues {
 public:
  PlyValues(const std::string& path, std::string_view body, PlyFormat format)
      : path_(path),
        format_(format),
        words_(body),
        bytes_(body, path, format == PlyFormat::BinaryBig) {}

  double get(PlyType type, const std::string& what) {
    if (format_ == PlyFormat::Ascii) {
      const std::optional<std::string_view> word = words_.next();
      if (!word) fail(path_, "the file ends early (truncated?) in " + what);
      double value;
      if (!parse_number(*word, value))
        fail(path_, what + ": " + quoted(*word) + " is not a number");
      if (ply_integral(type) && (value != std::floor(value) || std::abs(value) > 4294967295.0))
        fail(path_, what + ": " + quoted(*word) + " is not an integer");
      return type == PlyType::Float32 ? double(float(value)) : value;
    }
    switch (type) {
      case PlyType::Int8:
        return bytes_.get<int8_t>(what);
      case PlyType::Uint8:
        return bytes_.get<uint8_t>(what);
      case PlyType::Int16:
        return bytes_.get<int16_t>(what);
      case PlyType::Uint16:
        return bytes_.get<uint16_t>(what);
      case PlyType::Int32:
        return bytes_.get<int32_t>(what);
      case PlyType::Uint32:
        return bytes_.get<uint32_t>(what);
      case PlyType::Float32:
        return bytes_.get<float>(what);
      case PlyType::Float64:
        return bytes_.get<double>(what);
    }
    return 0.0;
  }

  // Fails unless `count` more items of `min_bytes` binary bytes (or one ascii word each) fit.
  void check_count(uint64_t count, size_t min_bytes, const std::string& what) const {
    if (format_ != PlyFormat::Ascii) return bytes_.check_count(count, min_bytes, what);
    if (min_bytes > 0 && count > (words_.left() + 1) / 2)
      fail(path_, what + ": the file declares " + std::to_string(count) +
                      " values but is too short for them (corrupt count or truncated file)");
  }

  void check_end() {
    if (format_ == PlyFormat::Ascii) {
      if (const auto word = words_.next())
        fail(path_,
             "unexpected data " + quoted(*word) + " after the last element the header declares");
    } else if (bytes_.left() > 0) {
      fail(path_, std::to_string(bytes_.left()) +
                      " bytes of unexpected data after the last element the header declares");
    }
  }

 private:
  const std::string& path_;
  PlyFormat format_;
  WordReader words_;
  ByteReader bytes_;
};

std::string_view next_line(std::string_view text, size_t& position) {
  const size_t end = std::min(text.find('\n', position), text.size());
  std::string_view line = text.substr(position, end - position);
  position = end + 1;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

void split(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  WordReader reader(line);
  while (const auto word = reader.next()) words.push_back(*word);
}

}  // namespace

std::string quoted(std::string_view text) {
  constexpr size_t kMaxShown = 40;
  std::string out = "'";
  for (size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += char(c);
    } else {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\x%02X", c);
      out += buffer;
    }
  }
  if (text.size() > kMaxShown) out += "...";
  return out + "'";
}

PolygonSoup read_ply(const std::string& path, std::string_view bytes) {
  size_t position = 0;
  std::vector<std::string_view> words;
  int line_number = 1;
  if (next_line(bytes, position) != "ply")
    fail(path, "not a PLY file: it does not start with a 'ply' line");
  std::optional<PlyFormat> format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (position < bytes.size()) {
    const std::string_view line = next_line(bytes, position);
    ++line_number;
    const std::string at = "PLY header line " + std::to_string(line_number);
    split(line, words);
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "end_header") {
      ended = true;
      break;
    }
    if (words[0] == "format") {
      if (words.size() != 3 || words[2] != "1.0")
        fail(path, at + ": expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (words[1] == "ascii")
        format = PlyFormat::Ascii;
      else if (words[1] == "binary_little_endian")
        format = PlyFormat::BinaryLittle;
      else if (words[1] == "binary_big_endian")
        format = PlyFormat::BinaryBig;
      else
        fail(path, at + ": unknown format " + quoted(words[1]));
    } else if (words[0] == "element") {
      long long count;
      if (words.size() != 3 || !parse_count(words[2], count) || count < 0 || count > INT32_MAX)
        fail(path, at + ": expected 'element NAME COUNT' with a count from 0 to 2147483647");
      elements.push_back({std::string(words[1]), count, {}});
    } else if (words[0] == "property") {
      if (elements.empty()) fail(path, at + ": 'property' before any 'element'");
      PlyProperty p;
      const bool list = words.size() == 5 && words[1] == "list";
      if (!list && words.size() != 3)
        fail(path, at + ": expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      const auto type = ply_type(words[list ? 3 : 1]);
      if (!type) fail(path, at + ": unknown property type " + quoted(words[list ? 3 : 1]));
      p.type = *type;
      p.is_list = list;
      if (list) {
        const auto count_type = ply_type(words[2]);
        if (!count_type || !ply_integral(*count_type))
          fail(path, at + ": a list's count type must be an integer type, not " + quoted(words[2]));
        p.count_type = *count_type;
      }
      p.name = std::string(words.back());
      elements.back().properties.push_back(std::move(p));
    } else {
      fail(path, at + ": unknown header keyword " + quoted(words[0]));
    }
  }
  if (!ended) fail(path, "the PLY header has no 'end_header' line (truncated, or not a PLY file)");
  if (!format) fail(path, "the PLY header has no 'format' line");

  PolygonSoup soup;
  PlyValues values(path, bytes.substr(std::min(position, bytes.size())), *format);
  bool have_vertices = false, have_faces = false;
  for (const PlyElement& element : elements) {
    const bool is_vertex = element.name == "vertex", is_face = element.name == "face";
    if ((is_vertex && have_vertices) || (is_face && have_faces))
      fail(path, "the PLY header declares the element '" + element.name + "' twice");
    int xyz[3] = {-1, -1, -1};
    int indices = -1;
    size_t min_bytes = 0;
    for (size_t k = 0; k < element.properties.size(); ++k) {
      const PlyProperty& p = element.properties[k];
      min_bytes += ply_size(p.is_list ? p.count_type : p.type);
      if (is_vertex && !p.is_list)
        for (int c = 0; c < 3; ++c)
          if (p.name == std::string(1, char('x' + c))) xyz[c] = int(k);
      if (is_face && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        indices = int(k);
    }
    if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0))
      fail(path, "the PLY element 'vertex' has no x, y and z properties");
    if (is_face && indices < 0) fail(path, "the PLY element 'face' has no 'vertex_indices' list");
    if (is_face && !ply_integral(element.properties[size_t(indices)].type))
      fail(path, "the PLY face list 'vertex_indices' must hold integers");
    if (element.properties.empty()) continue;  // takes no bytes, however many there are
    values.check_count(uint64_t(element.count), min_bytes, "element '" + element.name + "'");
    if (is_vertex) soup.points.reserve(size_t(element.count));
    if (is_face) soup.faces.reserve(size_t(element.count));
    for (long long i = 0; i < element.count; ++i) {
      const std::string what = element.name + " " + str(i);
      Vec3 point = Vec3::Zero();
      std::vector<int> face;
      for (size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& p = element.properties[k];
        if (!p.is_list) {
          const double v = values.get(p.type, what);
          for (int c = 0; c < 3; ++c)
            if (is_vertex && xyz[c] == int(k)) point[c] = v;
          continue;
        }
        const double n = values.get(p.count_type, what);
        if (n < 0) fail(path, what + ": a list has a negative length (" + str((long long)n) + ")");
        values.check_count(uint64_t(n), ply_size(p.type), what);
        const bool keep = is_face && int(k) == indices;
        if (keep) face.reserve(size_t(n));
        for (uint64_t j = 0; j < uint64_t(n); ++j) {
          const double v = values.get(p.type, what);
          if (!keep) continue;
          if (v < 0 || v > INT32_MAX)
            fail(path, what + ": vertex index " + str((long long)v) + " is out of range");
          face.push_back(int(v));
        }
      }
      if (is_vertex) soup.points.push_back(point);
      if (is_face) soup.faces.push_back(std::move(face));
    }
    have_vertices = have_vertices || is_vertex;
    have_faces = have_faces || is_face;
  }
  values.check_end();
  return soup;
}

// ---------------------------------------------------------------------------------------------
// STL

namespace {

// STL lists each triangle's corners; equal positions become one vertex, in order of first
// appearance (as OpenMesh's reader did).
class StlVertices {
 public:
  explicit StlVertices(PolygonSoup& soup) : soup_(soup) {}
  int add(const std::string& path, const std::array<float, 3>& p, long long facet) {
    for (float c : p)
      if (!std::isfinite(c)) fail(path, "facet " + str(facet) + " has a non-finite coordinate");
    const auto [it, inserted] = index_.emplace(p, int(soup_.points.size()));
    if (inserted) soup_.points.emplace_back(p[0], p[1], p[2]);
    return it->second;
  }

 private:
  PolygonSoup& soup_;
  std::map<std::array<float, 3>, int> index_;
};

PolygonSoup read_ascii_stl(const std::string& path, std::string_view text) {
  PolygonSoup soup;
  StlVertices vertices(soup);
  WordReader words(text);
  auto expect = [&](std::string_view keyword, const std::string& where) {
    const auto word = words.next();
    if (!word)
      fail(path, "line " + str(words.line()) + ": the file ends early (truncated?) in " + where);
    if (*word != keyword)
      fail(path, "line " + str(words.line()) + ": " + where + ": expected '" +
                     std::string(keyword) + "', found " + quoted(*word));
  };
  auto number = [&](const std::string& where) {
    const auto word = words.next();
    if (!word)
      fail(path, "line " + str(words.line()) + ": the file ends early (truncated?) in " + where);
    double v;
    if (!parse_number(*word, v))
      fail(path,
           "line " + str(words.line()) + ": " + where + ": " + quoted(*word) + " is not a number");
    return float(v);
  };
  bool in_solid = false;
  long long facet = 0;
  while (true) {
    const auto word = words.next();
    if (!word) break;
    if (!in_solid) {
      if (*word != "solid")
        fail(path, "line " + str(words.line()) + ": expected 'solid', found " + quoted(*word));
      words.skip_line();  // the solid's name
      in_solid = true;
      continue;
    }
    if (*word == "endsolid") {
      words.skip_line();
      in_solid = false;
      continue;
    }
    if (*word != "facet")
      fail(path, "line " + str(words.line()) + ": expected 'facet' or 'endsolid', found " +
                     quoted(*word));
    const std::string where = "facet " + str(facet);
    expect("normal", where);
    for (int k = 0; k < 3; ++k) number(where);
    expect("outer", where);
    expect("loop", where);
    std::vector<int> face;
    while (true) {
      const auto next = words.next();
      if (!next)
        fail(path, "line " + str(words.line()) + ": the file ends early (truncated?) in " + where);
      if (*next == "endloop") break;
      if (*next != "vertex")
        fail(path, "line " + str(words.line()) + ": " + where +
                       ": expected 'vertex' or 'endloop', found " + quoted(*next));
      std::array<float, 3> p;
      for (float& c : p) c = number(where);
      face.push_back(vertices.add(path, p, facet));
    }
    expect("endfacet", where);
    soup.faces.push_back(std::move(face));
    ++facet;
  }
  if (in_solid)
    fail(path, "the file ends early (truncated?): no 'endsolid' after facet " + str(facet - 1));
  return soup;
}

}  // namespace

PolygonSoup read_stl(const std::string& path, std::string_view bytes) {
  if (bytes.empty()) return {};  // OpenMesh's "empty mesh": reported as such by validation
  const bool sized_as_binary = bytes.size() >= 84 && [&] {
    uint32_t n;
    std::memcpy(&n, bytes.data() + 80, 4);
    return 84 + 50 * uint64_t(n) == bytes.size();
  }();
  size_t start = 0;
  while (start < bytes.size() && is_space(bytes[start])) ++start;
  if (!sized_as_binary && bytes.substr(start, 5) == "solid") return read_ascii_stl(path, bytes);
  if (bytes.size() < 84)
    fail(path, "not an STL file: too short for binary STL (84 bytes) and no 'solid' keyword");
  ByteReader in(bytes, path, false);
  in.skip(80, "the binary STL header");
  const uint32_t n = in.get<uint32_t>("the binary STL header");
  if (84 + 50 * uint64_t(n) != bytes.size())
    fail(path, "binary STL: the header declares " + str(n) + " triangles, which take " +
                   std::to_string(84 + 50 * uint64_t(n)) + " bytes, but the file has " +
                   std::to_string(bytes.size()) + " (truncated or corrupt)");
  PolygonSoup soup;
  StlVertices vertices(soup);
  soup.faces.reserve(n);
  for (uint32_t f = 0; f < n; ++f) {
    const std::string what = "triangle " + str(f);
    in.skip(12, what);  // normal
    std::vector<int> face;
    for (int k = 0; k < 3; ++k) {
      std::array<float, 3> p;
      for (float& c : p) c = in.get<float>(what);
      face.push_back(vertices.add(path, p, f));
    }
    in.skip(2, what);  // attribute byte count
    soup.faces.push_back(std::move(face));
  }
  return soup;
}

// ---------------------------------------------------------------------------------------------
// OM (OpenMesh's binary format, versions 1.x and 2.x as OpenMesh 9 writes them)

namespace {

struct OmChunk {
  bool named = false;
  int entity = 0, type = 0, dim = 0, bits = 0;
  bool is_float = false;
  size_t scalar_size() const { return is_float ? size_t(4) << bits : size_t(1) << bits; }
  size_t vector_size() const { return scalar_size() * size_t(dim + 1); }
};

constexpr int kEntityVertex = 0, kEntityMesh = 1, kEntityFace = 2, kEntityEdge = 4,
              kEntityHalfedge = 6, kEntitySentinel = 7;
constexpr int kTypePos = 0, kTypeCustom = 6, kTypeTopology = 7;

long long om_integer(ByteReader& in, int bits, bool is_signed, const std::string& what) {
  switch (bits) {
    case 0:
      return is_signed ? in.get<int8_t>(what) : in.get<uint8_t>(what);
    case 1:
      return is_signed ? in.get<int16_t>(what) : in.get<uint16_t>(what);
    case 2:
      return is_signed ? in.get<int32_t>(what) : in.get<uint32_t>(what);
    default:
      return is_signed ? in.get<int64_t>(what) : (long long)(in.get<uint64_t>(what) & INT64_MAX);
  }
}

}  // namespace

PolygonSoup read_om(const std::string& path, std::string_view bytes) {
  ByteReader in(bytes, path, false);
  if (bytes.size() < 2 || bytes[0] != 'O' || bytes[1] != 'M')
    fail(path, "not an OM file (no 'OM' signature)");
  in.skip(2, "the OM header");
  const char mesh_kind = char(in.get<uint8_t>("the OM header"));
  if (mesh_kind != 'T' && mesh_kind != 'Q' && mesh_kind != 'P')
    fail(path, "OM header: unknown mesh kind " + quoted(std::string(1, mesh_kind)));
  const int version = in.get<uint8_t>("the OM header");
  const int major = (version >> 5) & 7, minor = version & 31;
  if (major > 2 || (major == 2 && minor > 2))
    fail(path, "OM version " + str(major) + "." + str(minor) + " is newer than PriMo reads (2.2)");
  const uint32_t n_vertices = in.get<uint32_t>("the OM header");
  const uint32_t n_faces = in.get<uint32_t>("the OM header");
  const uint32_t n_edges = in.get<uint32_t>("the OM header");
  if (n_vertices > INT32_MAX || n_faces > INT32_MAX || n_edges > INT32_MAX / 2)
    fail(path, "OM header: the counts are too large (corrupt file)");

  PolygonSoup soup;
  std::vector<int> next, to_vertex, face_of_halfedge, face_halfedge;
  bool have_positions = false, have_halfedges = false, have_face_topology = false;
  while (true) {
    const uint16_t raw = in.get<uint16_t>("a chunk header (no end marker: truncated?)");
    OmChunk chunk;
    chunk.named = (raw >> 1) & 1;
    chunk.entity = (raw >> 2) & 7;
    chunk.type = (raw >> 5) & 15;
    chunk.is_float = (raw >> 10) & 1;
    chunk.dim = (raw >> 11) & 7;
    chunk.bits = (raw >> 14) & 3;
    if (chunk.entity == kEntitySentinel) break;
    const std::string what = "OM chunk at byte " + std::to_string(in.position() - 2);
    if (chunk.named) in.skip(in.get<uint8_t>(what), what);  // the property's name
    uint64_t count = 0;
    switch (chunk.entity) {
      case kEntityVertex:
        count = n_vertices;
        break;
      case kEntityFace:
        count = n_faces;
        break;
      case kEntityEdge:
        count = n_edges;
        break;
      case kEntityHalfedge:
        count = 2 * uint64_t(n_edges);
        break;
      case kEntityMesh:
        count = 1;
        break;
      default:
        fail(path, what + ": unknown entity " + str(chunk.entity));
    }
    if (chunk.type == kTypeCustom) {
      if (version > 0x41) in.skip(in.get<uint8_t>(what), what);  // the property's type name
      in.skip(in.get<uint32_t>(what), what);
      continue;
    }
    if (chunk.entity == kEntityVertex && chunk.type == kTypePos) {
      if (have_positions) fail(path, what + ": a second vertex position chunk");
      if (!chunk.is_float || chunk.dim != 2 || chunk.bits > 1)
        fail(path, what + ": vertex positions must be 3 floats or doubles");
      in.check_count(count, chunk.vector_size(), what);
      soup.points.reserve(count);
      for (uint64_t v = 0; v < count; ++v) {
        Vec3 p;
        for (int c = 0; c < 3; ++c)
          p[c] = chunk.bits == 0 ? double(in.get<float>(what)) : in.get<double>(what);
        soup.points.push_back(p);
      }
      have_positions = true;
      continue;
    }
    if (chunk.type == kTypeTopology && chunk.entity == kEntityFace && major < 2) {
      // Version 1: each face as its vertex indices (a count first for polygonal meshes).
      in.check_count(n_faces, size_t(1) << chunk.bits, what);
      soup.faces.reserve(n_faces);
      for (uint32_t f = 0; f < n_faces; ++f) {
        const std::string where = what + ", face " + str(f);
        const size_t degree = mesh_kind == 'T' ? 3 : mesh_kind == 'Q' ? 4 : in.get<uint16_t>(where);
        in.check_count(degree, size_t(1) << chunk.bits, where);
        std::vector<int> face;
        for (size_t k = 0; k < degree; ++k) {
          const long long v = om_integer(in, chunk.bits, false, where);
          if (v < 0 || v >= n_vertices)
            fail(path, where + ": vertex index " + str(v) + " is out of range");
          face.push_back(int(v));
        }
        soup.faces.push_back(std::move(face));
      }
      have_face_topology = true;
      continue;
    }
    if (chunk.type == kTypeTopology && chunk.entity == kEntityHalfedge) {
      in.check_count(count, 3 * (size_t(1) << chunk.bits), what);
      next.resize(count), to_vertex.resize(count), face_of_halfedge.resize(count);
      for (uint64_t h = 0; h < count; ++h) {
        next[h] = int(std::clamp<long long>(om_integer(in, chunk.bits, true, what), -1, INT32_MAX));
        to_vertex[h] =
            int(std::clamp<long long>(om_integer(in, chunk.bits, true, what), -1, INT32_MAX));
        face_of_halfedge[h] =
            int(std::clamp<long long>(om_integer(in, chunk.bits, true, what), -1, INT32_MAX));
      }
      have_halfedges = true;
      continue;
    }
    if (chunk.type == kTypeTopology && chunk.entity == kEntityFace) {
      in.check_count(count, size_t(1) << chunk.bits, what);
      face_halfedge.resize(count);
      for (uint64_t f = 0; f < count; ++f)
        face_halfedge[f] =
            int(std::clamp<long long>(om_integer(in, chunk.bits, true, what), -1, INT32_MAX));
      have_face_topology = true;
      continue;
    }
    // Anything else (normals, colours, status, vertex halfedges, texture coordinates): skipped.
    // Topology chunks hold integers of 1 << bits bytes whatever their float bit says.
    const size_t size = chunk.type == kTypeTopology ? size_t(1) << chunk.bits : chunk.vector_size();
    in.check_count(count, size, what);
    in.skip(size_t(count * size), what);
  }
  if (in.left() > 0)
    fail(path, std::to_string(in.left()) + " bytes of unexpected data after the OM end marker");
  if (!have_positions && n_vertices > 0) fail(path, "the OM file has no vertex positions");
  if (!have_face_topology && n_faces > 0) fail(path, "the OM file has no face topology");
  if (major >= 2 && n_faces > 0) {
    if (!have_halfedges) fail(path, "the OM file has no halfedge topology");
    const int n_halfedges = int(next.size());
    soup.faces.reserve(n_faces);
    for (uint32_t f = 0; f < n_faces; ++f) {
      const std::string where = "OM face " + str(f);
      std::vector<int> face;
      int h = face_halfedge[f];
      for (int steps = 0;; ++steps) {
        if (h < 0 || h >= n_halfedges)
          fail(path, where + ": halfedge " + str(h) + " is out of range");
        if (face_of_halfedge[size_t(h)] != int(f))
          fail(path, where + ": its halfedge " + str(h) + " belongs to another face");
        if (steps > n_halfedges) fail(path, where + ": its halfedges do not close into a loop");
        const int v = to_vertex[size_t(h)];
        if (v < 0 || v >= int(n_vertices))
          fail(path, where + ": vertex index " + str(v) + " is out of range");
        face.push_back(v);
        h = next[size_t(h)];
        if (h == face_halfedge[f]) break;
      }
      soup.faces.push_back(std::move(face));
    }
  }
  return soup;
}

// ---------------------------------------------------------------------------------------------
// Binary OFF

namespace {

// Geomview's layout: big-endian, and after each face's indices a colour count and that many
// floats. OpenMesh writes little-endian without the colour count. The layout whose parse uses up
// the file exactly is the file's.
PolygonSoup binary_off_layout(const std::string& path, std::string_view data, size_t extra_floats,
                              bool big_endian, bool colour_counts) {
  ByteReader in(data, path, big_endian);
  const int32_t n_vertices = in.get<int32_t>("the binary OFF counts");
  const int32_t n_faces = in.get<int32_t>("the binary OFF counts");
  in.get<int32_t>("the binary OFF counts");
  if (n_vertices < 0 || n_faces < 0)
    fail(path, "binary OFF: negative counts (" + str(n_vertices) + " vertices, " + str(n_faces) +
                   " faces)");
  const size_t vertex_bytes = 4 * (3 + extra_floats);
  in.check_count(uint64_t(n_vertices), vertex_bytes, "binary OFF vertices");
  PolygonSoup soup;
  soup.points.reserve(size_t(n_vertices));
  for (int32_t v = 0; v < n_vertices; ++v) {
    const std::string what = "vertex " + str(v);
    Vec3 p;
    for (int c = 0; c < 3; ++c) p[c] = in.get<float>(what);
    in.skip(4 * extra_floats, what);
    soup.points.push_back(p);
  }
  in.check_count(uint64_t(n_faces), 4, "binary OFF faces");
  soup.faces.reserve(size_t(n_faces));
  for (int32_t f = 0; f < n_faces; ++f) {
    const std::string what = "face " + str(f);
    const int32_t degree = in.get<int32_t>(what);
    if (degree < 0) fail(path, what + ": negative vertex count " + str(degree));
    in.check_count(uint64_t(degree), 4, what);
    std::vector<int> face(static_cast<size_t>(degree), 0);
    for (int& v : face) v = in.get<int32_t>(what);
    if (colour_counts) {
      const int32_t colours = in.get<int32_t>(what);
      if (colours < 0 || colours > 4)
        fail(path, what + ": colour count " + str(colours) + " (expected 0 to 4)");
      in.skip(4 * size_t(colours), what);
    }
    soup.faces.push_back(std::move(face));
  }
  size_t rest = in.position();
  while (rest < data.size() && is_space(data[rest])) ++rest;
  if (rest != data.size())
    fail(path, "binary OFF: " + std::to_string(data.size() - in.position()) +
                   " bytes of unexpected data after the last face");
  return soup;
}

}  // namespace

PolygonSoup read_binary_off(const std::string& path, std::string_view keyword,
                            std::string_view data) {
  size_t extra = 0;
  if (keyword.substr(0, 2) == "ST") extra += 2, keyword.remove_prefix(2);
  if (!keyword.empty() && keyword[0] == 'C') extra += 4, keyword.remove_prefix(1);
  if (!keyword.empty() && keyword[0] == 'N') extra += 3, keyword.remove_prefix(1);
  struct Layout {
    bool big_endian, colour_counts;
  };
  const Layout layouts[] = {{true, true}, {false, false}, {false, true}, {true, false}};
  std::optional<Error> first_error;
  for (const Layout& layout : layouts) {
    try {
      return binary_off_layout(path, data, extra, layout.big_endian, layout.colour_counts);
    } catch (const Error& e) {
      if (!first_error) first_error = e;
    }
  }
  throw *first_error;
}

}  // namespace primo::detail
