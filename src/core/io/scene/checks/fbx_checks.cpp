#include "fbx_checks.h"

#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "node_graph_limits.h"
#include "primo/util/error.h"

namespace primo::detail {
namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& rule) {
  throw Error(path + ": cannot read: not an FBX file PriMo accepts (" + rule + ")");
}

constexpr std::string_view kBinaryMagic = "Kaydara FBX Binary  ";
constexpr size_t kBinaryHeader = 27;  // magic, 0x00 0x1A 0x00, version (uint32)

// The models and their "OO" connections (child, parent) that Assimp turns into its node tree.
struct ModelGraph {
  std::vector<int64_t> models;
  std::vector<std::pair<int64_t, int64_t>> connections;
};

template <typename T>
T read_le(std::string_view bytes, size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof value);
  return value;  // FBX is little-endian, as every machine PriMo builds for
}

// One property of a binary record at `at`: its type, and its value when an integer ('I', 'L')
// or a string ('S'). False when it runs past `end`.
bool read_property(std::string_view bytes, size_t& at, size_t end, char& type, int64_t& integer,
                   std::string_view& text) {
  if (at >= end) return false;
  type = bytes[at++];
  size_t size = 0;
  switch (type) {
    case 'C': size = 1; break;
    case 'Y': size = 2; break;
    case 'I': case 'F': size = 4; break;
    case 'L': case 'D': size = 8; break;
    case 'S': case 'R': {
      if (end - at < 4) return false;
      size = read_le<uint32_t>(bytes, at);
      at += 4;
      if (end - at < size) return false;
      text = bytes.substr(at, size);
      at += size;
      return true;
    }
    case 'b': case 'c': case 'i': case 'f': case 'l': case 'd': {
      if (end - at < 12) return false;
      const uint64_t count = read_le<uint32_t>(bytes, at);
      const uint32_t encoding = read_le<uint32_t>(bytes, at + 4);
      const uint64_t compressed = read_le<uint32_t>(bytes, at + 8);
      const uint64_t element = (type == 'b' || type == 'c') ? 1 : (type == 'i' || type == 'f') ? 4 : 8;
      const uint64_t stored = encoding ? compressed : count * element;
      at += 12;
      if (end - at < stored) return false;
      at += size_t(stored);
      return true;
    }
    default: return false;
  }
  if (end - at < size) return false;
  if (type == 'I') integer = read_le<int32_t>(bytes, at);
  if (type == 'L') integer = read_le<int64_t>(bytes, at);
  at += size;
  return true;
}

// The record tree of a binary FBX, walked without recursion.
ModelGraph walk_binary(std::string_view bytes, const std::string& path) {
  ModelGraph graph;
  if (bytes.size() < kBinaryHeader) return graph;  // Assimp names a truncated header
  const uint32_t version = read_le<uint32_t>(bytes, 23);
  const bool wide = version >= 7500;  // 64-bit offsets
  const size_t header = wide ? 25 : 13;
  enum class Kind { kOther, kObjects, kConnections };
  struct Level {
    size_t end;
    Kind kind;
  };
  std::vector<Level> open;
  size_t at = kBinaryHeader;
  for (;;) {
    const size_t level_end = open.empty() ? bytes.size() : open.back().end;
    if (!open.empty() && at >= level_end) {
      at = open.back().end;
      open.pop_back();
      continue;
    }
    if (level_end - at < header) {
      if (open.empty()) break;  // the footer, or a truncation Assimp names
      refuse(path, "the record list at byte " + std::to_string(at) + " runs past its parent");
    }
    const uint64_t end = wide ? read_le<uint64_t>(bytes, at) : read_le<uint32_t>(bytes, at);
    const uint64_t property_bytes =
        wide ? read_le<uint64_t>(bytes, at + 16) : read_le<uint32_t>(bytes, at + 8);
    const size_t name_length = uint8_t(bytes[at + header - 1]);
    if (end == 0) {  // the null record that closes a list
      if (open.empty()) break;
      at = open.back().end;
      open.pop_back();
      continue;
    }
    const size_t properties = at + header + name_length;
    if (end > level_end || end <= at || properties > end || end - properties < property_bytes)
      refuse(path, "the record at byte " + std::to_string(at) + " runs past " +
                       (open.empty() ? std::string("the file") : std::string("its parent")));
    const std::string_view name = bytes.substr(at + header, name_length);
    const Kind parent = open.empty() ? Kind::kOther : open.back().kind;
    size_t p = properties;
    const size_t properties_end = properties + size_t(property_bytes);
    char type = 0;
    int64_t integer = 0;
    std::string_view text;
    if (parent == Kind::kObjects && name == "Model" &&
        read_property(bytes, p, properties_end, type, integer, text) && type == 'L') {
      graph.models.push_back(integer);
    } else if (parent == Kind::kConnections && name == "C" &&
               read_property(bytes, p, properties_end, type, integer, text) && type == 'S' &&
               text == "OO") {
      int64_t child = 0;
      if (read_property(bytes, p, properties_end, type, child, text) && type == 'L' &&
          read_property(bytes, p, properties_end, type, integer, text) && type == 'L')
        graph.connections.emplace_back(child, integer);
    }
    if (properties_end < end) {  // nested records
      if (open.size() >= size_t(kMaxFbxNesting))
        refuse(path, "its records nest deeper than " + std::to_string(kMaxFbxNesting) + " levels");
      const Kind kind = !open.empty() ? Kind::kOther
                        : name == "Objects" ? Kind::kObjects
                        : name == "Connections" ? Kind::kConnections
                                                : Kind::kOther;
      open.push_back({size_t(end), kind});
      at = properties_end;
    } else {
      at = size_t(end);
    }
  }
  return graph;
}

// The first integer in `text` from `at` (after spaces and commas), or false.
bool next_integer(std::string_view text, size_t& at, int64_t& value) {
  while (at < text.size() && (text[at] == ' ' || text[at] == '\t' || text[at] == ',')) ++at;
  const bool negative = at < text.size() && text[at] == '-';
  if (negative) ++at;
  const size_t begin = at;
  uint64_t magnitude = 0;
  while (at < text.size() && text[at] >= '0' && text[at] <= '9' && magnitude < (1ull << 62))
    magnitude = magnitude * 10 + uint64_t(text[at++] - '0');
  value = negative ? -int64_t(magnitude) : int64_t(magnitude);
  return at > begin;
}

// The scopes of an ASCII FBX ("Key: values {" ... "}"), line by line.
ModelGraph walk_ascii(std::string_view bytes, const std::string& path) {
  ModelGraph graph;
  std::vector<std::string_view> scopes;  // the keys of the open braces
  size_t line_begin = 0;
  while (line_begin < bytes.size()) {
    size_t line_end = bytes.find('\n', line_begin);
    if (line_end == std::string_view::npos) line_end = bytes.size();
    const std::string_view line = bytes.substr(line_begin, line_end - line_begin);
    line_begin = line_end + 1;
    size_t at = line.find_first_not_of(" \t\r");
    if (at == std::string_view::npos || line[at] == ';') continue;
    // "Key:" at the start of the line.
    std::string_view key;
    const size_t colon = line.find(':', at);
    if (colon != std::string_view::npos &&
        line.substr(at, colon - at).find_first_of(" \t\",{}") == std::string_view::npos) {
      key = line.substr(at, colon - at);
      const bool in_objects = scopes.size() == 1 && scopes[0] == "Objects";
      const bool in_connections = scopes.size() == 1 && scopes[0] == "Connections";
      size_t value = colon + 1;
      int64_t id = 0, child = 0, parent = 0;
      if (in_objects && key == "Model" && next_integer(line, value, id)) graph.models.push_back(id);
      if (in_connections && key == "C") {
        const size_t type = line.find("\"OO\"", value);
        size_t after = type == std::string_view::npos ? 0 : type + 4;
        if (type != std::string_view::npos &&
            line.substr(value, type - value).find_first_not_of(" \t") == std::string_view::npos &&
            next_integer(line, after, child) && next_integer(line, after, parent))
          graph.connections.emplace_back(child, parent);
      }
    }
    // Braces outside strings and comments open and close scopes.
    bool in_string = false;
    for (; at < line.size(); ++at) {
      const char c = line[at];
      if (c == '"') in_string = !in_string;
      if (in_string) continue;
      if (c == ';') break;
      if (c == '{') {
        if (scopes.size() >= size_t(kMaxFbxNesting))
          refuse(path, "its scopes nest deeper than " + std::to_string(kMaxFbxNesting) + " levels");
        scopes.push_back(key);
        key = {};
      } else if (c == '}' && !scopes.empty()) {
        scopes.pop_back();
      }
    }
  }
  return graph;
}

}  // namespace

void check_fbx_before_assimp(std::string_view bytes, const std::string& path) {
  const bool binary = bytes.substr(0, kBinaryMagic.size()) == kBinaryMagic;
  const ModelGraph graph = binary ? walk_binary(bytes, path) : walk_ascii(bytes, path);
  // Node 0 is the scene's root (id 0); then the models, in file order.
  std::unordered_map<int64_t, size_t> node_of;
  std::vector<int64_t> id_of = {0};
  node_of.emplace(0, 0);
  for (const int64_t id : graph.models)
    if (node_of.emplace(id, id_of.size()).second) id_of.push_back(id);
  std::vector<std::vector<size_t>> children(id_of.size());
  for (const auto& [child, parent] : graph.connections) {
    const auto c = node_of.find(child), p = node_of.find(parent);
    if (c != node_of.end() && p != node_of.end() && c->second != 0) children[p->second].push_back(c->second);
  }
  const std::string problem = node_graph_problem(children, [&](size_t v) {
    return v == 0 ? std::string("the root") : "model " + std::to_string(id_of[v]);
  });
  if (!problem.empty()) refuse(path, problem);
}

}  // namespace primo::detail
