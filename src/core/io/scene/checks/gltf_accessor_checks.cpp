#include "gltf_accessor_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "primo/util/error.h"
#include "primo/io/input_files.h"

namespace primo::detail {
namespace {

using Json = nlohmann::json;

[[noreturn]] void refuse(const std::string& path, const std::string& rule) {
  throw Error(path + ": cannot read: not a glTF file PriMo accepts (" + rule + ")");
}

constexpr uint32_t kGlbBinChunk = 0x004E4942;  // "BIN\0", little-endian

uint32_t u32_le(std::string_view bytes, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | uint8_t(bytes[at + size_t(k)]);
  return v;
}

// A .glb's binary chunk where Assimp 5.2 looks for it: after the JSON chunk padded to 4 bytes,
// and only when the header's total length reaches past that chunk's header (else there is
// none: empty). nullopt where Assimp refuses the file itself (no room for the chunk's header,
// a chunk of another type). No more than the file holds, whatever the chunk's length says.
std::optional<std::string_view> glb_binary_chunk(std::string_view bytes) {
  if (bytes.size() < 20) return std::nullopt;
  const uint64_t json_length = u32_le(bytes, 12);
  const uint64_t chunk_header = 20 + ((json_length + 3) & ~uint64_t(3));
  const uint64_t body = chunk_header + 8;
  if (u32_le(bytes, 8) < body) return std::string_view();
  if (body > bytes.size() || u32_le(bytes, size_t(chunk_header) + 4) != kGlbBinChunk)
    return std::nullopt;
  const uint64_t length = u32_le(bytes, size_t(chunk_header));
  return bytes.substr(size_t(body), size_t(std::min<uint64_t>(length, bytes.size() - body)));
}

// Assimp 5.2's base64 table (Base64.cpp): characters outside the alphabet count as 0, '=' as 64.
constexpr std::array<uint8_t, 128> kBase64 = [] {
  std::array<uint8_t, 128> t{};
  for (int c = 'A'; c <= 'Z'; ++c) t[size_t(c)] = uint8_t(c - 'A');
  for (int c = 'a'; c <= 'z'; ++c) t[size_t(c)] = uint8_t(c - 'a' + 26);
  for (int c = '0'; c <= '9'; ++c) t[size_t(c)] = uint8_t(c - '0' + 52);
  t['+'] = 62;
  t['/'] = 63;
  t['='] = 64;
  return t;
}();

// The bytes of a data: URI as Assimp 5.2 decodes them (glTFCommon's ParseDataURI,
// Base64::Decode): the data follow the first comma (without one: everything after "data:",
// each ';' a NUL), and are base64 when a parameter before that comma starts with "base64".
// nullopt where Assimp refuses the URI (base64 whose length is not a multiple of 4, or with a
// byte above 127).
std::optional<std::string> data_uri_bytes(const std::string& uri) {
  const size_t comma = uri.find(',');
  if (comma == std::string::npos) {
    std::string raw = uri.substr(5);
    std::replace(raw.begin(), raw.end(), ';', '\0');
    return raw;
  }
  bool base64 = false;
  for (size_t at = uri.find(';', 5); at < comma; at = uri.find(';', at + 1))
    if (uri.compare(at + 1, 6, "base64") == 0) base64 = true;
  const std::string_view in = std::string_view(uri).substr(comma + 1);
  if (!base64) return std::string(in);
  const size_t n = in.size();
  if (n % 4 != 0) return std::nullopt;
  if (n < 4) return std::string();
  for (const char c : in)
    if (uint8_t(c) & 0x80) return std::nullopt;
  std::string out(n / 4 * 3 - size_t(in[n - 1] == '=') - size_t(in[n - 2] == '='), '\0');
  const auto at = [&](size_t i) { return kBase64[uint8_t(in[i])]; };
  size_t j = 0, i = 0;
  for (; i + 4 < n; i += 4) {
    const uint8_t b0 = at(i), b1 = at(i + 1), b2 = at(i + 2), b3 = at(i + 3);
    out[j++] = char(uint8_t((b0 << 2) | (b1 >> 4)));
    out[j++] = char(uint8_t((b1 << 4) | (b2 >> 2)));
    out[j++] = char(uint8_t((b2 << 6) | b3));
  }
  // The last group: one byte, and one more for each of its last two characters that is not '='
  // (exactly the '=' the size above left out).
  const uint8_t b0 = at(i), b1 = at(i + 1), b2 = at(i + 2), b3 = at(i + 3);
  out[j++] = char(uint8_t((b0 << 2) | (b1 >> 4)));
  if (b2 < 64) out[j++] = char(uint8_t((b1 << 4) | (b2 >> 2)));
  if (b3 < 64) out[j++] = char(uint8_t((b2 << 6) | b3));
  return out;
}

// A field that must be a whole number when present: its value, `fallback` when absent.
uint64_t whole(const Json& object, const char* key, uint64_t fallback, const std::string& path,
               const std::string& item) {
  const auto it = object.find(key);
  if (it == object.end()) return fallback;
  if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<int64_t>() >= 0))
    refuse(path, item + ": " + key + " is not a whole number");
  return it->get<uint64_t>();
}

bool has(const Json& object, const char* key) { return object.find(key) != object.end(); }

const Json& array_of(const Json& outline, const char* key) {
  static const Json empty = Json::array();
  const auto it = outline.find(key);
  return it != outline.end() && it->is_array() ? *it : empty;
}

uint64_t component_bytes(uint64_t type) {
  switch (type) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

uint64_t components(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

bool unsigned_index_type(uint64_t type) { return type == 5121 || type == 5123 || type == 5125; }

struct View {
  uint64_t buffer = 0, offset = 0, length = 0, stride = 0;  // stride 0: none given
};

// Where a sparse accessor's substitutions are (checked to lie within their views).
struct Sparse {
  uint64_t count = 0, index_view = 0, index_offset = 0, index_size = 0, value_view = 0,
           value_offset = 0;
};

struct Accessor {
  bool has_view = false;
  uint64_t view = 0, offset = 0, count = 0, component = 0, element = 0;
  std::string type;
  std::optional<Sparse> sparse;
};

class Checker {
 public:
  Checker(const Json& outline, const GltfBufferBytes& buffers, const std::string& path)
      : outline_(outline), data_(buffers), path_(path) {}

  void run() {
    read_buffers();
    read_views();
    read_accessors();
    check_meshes();
    check_nodes();
    check_animations();
  }

 private:
  void read_buffers() {
    const Json& buffers = array_of(outline_, "buffers");
    for (size_t k = 0; k < buffers.size(); ++k) {
      const std::string item = "buffer " + std::to_string(k);
      if (!buffers[k].is_object()) refuse(path_, item + " is not an object");
      const uint64_t declared = whole(buffers[k], "byteLength", 0, path_, item);
      // Assimp 5.2 keeps where a data: URI's data begin in a char: past 127 it reads from
      // before the URI or from the wrong place in it.
      if (const auto uri = buffers[k].find("uri");
          !(data_.glb && k == 0) && uri != buffers[k].end() && uri->is_string()) {
        const std::string& name = uri->get_ref<const std::string&>();
        const size_t comma = name.find(',');
        if (name.rfind("data:", 0) == 0 && comma != std::string::npos && comma + 1 > 127)
          refuse(path_, item + "'s data: URI begins its data after " + std::to_string(comma + 1) +
                            " characters (Assimp 5.2 finds them only within the first 127)");
      }
      if (const auto bytes = seen(k); bytes && declared > bytes->size())
        refuse(path_, item + " declares " + std::to_string(declared) + " bytes but " +
                          data_.source[k] + " holds " + std::to_string(bytes->size()));
      buffer_length_.push_back(declared);
    }
  }

  std::optional<std::string_view> seen(uint64_t buffer) const {
    return buffer < data_.bytes.size() ? data_.bytes[size_t(buffer)] : std::nullopt;
  }

  void read_views() {
    const Json& views = array_of(outline_, "bufferViews");
    for (size_t k = 0; k < views.size(); ++k) {
      const std::string item = "buffer view " + std::to_string(k);
      if (!views[k].is_object()) refuse(path_, item + " is not an object");
      View v;
      v.buffer = whole(views[k], "buffer", UINT64_MAX, path_, item);
      v.offset = whole(views[k], "byteOffset", 0, path_, item);
      v.length = whole(views[k], "byteLength", 0, path_, item);
      v.stride = whole(views[k], "byteStride", 0, path_, item);
      if (v.buffer >= buffer_length_.size())
        refuse(path_, item +
                          (has(views[k], "buffer") ? " names buffer " + std::to_string(v.buffer)
                                                   : " names no buffer") +
                          "; the file has " + std::to_string(buffer_length_.size()));
      if (v.offset > buffer_length_[v.buffer] || v.length > buffer_length_[v.buffer] - v.offset)
        refuse(path_, item + " (bytes " + std::to_string(v.offset) + " + " +
                          std::to_string(v.length) + ") runs past buffer " +
                          std::to_string(v.buffer) + " (" +
                          std::to_string(buffer_length_[v.buffer]) + " bytes)");
      if (has(views[k], "byteStride") && (v.stride < 4 || v.stride > 252 || v.stride % 4 != 0))
        refuse(path_, item + ": byteStride " + std::to_string(v.stride) +
                          " is not a multiple of 4 from 4 to 252");
      views_.push_back(v);
    }
  }

  const View& view_of(uint64_t index, const std::string& item) {
    if (index >= views_.size())
      refuse(path_, item + " names buffer view " + std::to_string(int64_t(index)) +
                        ", but the file has " + std::to_string(views_.size()));
    return views_[size_t(index)];
  }

  void check_span(const View& v, uint64_t offset, uint64_t count, uint64_t stride, uint64_t element,
                  const std::string& item) {
    // count (below 2^32), stride and element (below 2^8) are bounded: the span is below 2^40.
    const uint64_t span = (count - 1) * stride + element;
    const uint64_t end = offset > UINT64_MAX - span ? UINT64_MAX : offset + span;
    if (end > v.length)
      refuse(path_, item + " reads " + std::to_string(end) + " bytes (offset " +
                        std::to_string(offset) + ", " + std::to_string(count) + " elements of " +
                        std::to_string(element) + " bytes, stride " + std::to_string(stride) +
                        ") from a buffer view of " + std::to_string(v.length));
  }

  // The bytes of view `v` when its buffer's bytes can be seen (the buffer holds the view: its
  // declared length does, and read_buffers checked that it holds that much).
  std::optional<std::string_view> bytes_of(const View& v) const {
    const auto bytes = seen(v.buffer);
    if (!bytes) return std::nullopt;
    return bytes->substr(size_t(v.offset), size_t(v.length));
  }

  static uint64_t unsigned_at(std::string_view bytes, uint64_t at, uint64_t size) {
    uint64_t value = 0;
    for (uint64_t k = size; k-- > 0;) value = (value << 8) | uint8_t(bytes[size_t(at + k)]);
    return value;
  }

  void read_accessors() {
    const Json& accessors = array_of(outline_, "accessors");
    find_draco_accessors(accessors.size());
    for (size_t k = 0; k < accessors.size(); ++k) {
      const Json& a = accessors[k];
      if (a.is_object() && (has(a, "bufferView") || draco_[k])) {
        const auto count = a.find("count");
        if (count != a.end() && count->is_number_unsigned())
          largest_with_view_ = std::max(largest_with_view_, count->get<uint64_t>());
      }
    }
    for (size_t k = 0; k < accessors.size(); ++k) {
      const std::string item = "accessor " + std::to_string(k);
      const Json& a = accessors[k];
      if (!a.is_object()) refuse(path_, item + " is not an object");
      Accessor acc;
      acc.component = whole(a, "componentType", 0, path_, item);
      const auto type = a.find("type");
      acc.type = type != a.end() && type->is_string() ? type->get<std::string>() : "";
      const uint64_t size = component_bytes(acc.component);
      if (size == 0)
        refuse(path_,
               item + ": componentType " + std::to_string(acc.component) + " is not one glTF has");
      if (components(acc.type) == 0)
        refuse(path_, item + ": type '" + acc.type.substr(0, 20) + "' is not one glTF has");
      acc.element = size * components(acc.type);
      acc.count = whole(a, "count", 0, path_, item);
      acc.offset = whole(a, "byteOffset", 0, path_, item);
      if (acc.count < 1 || acc.count > kMaxGltfAccessorCount)
        refuse(path_, item + ": count " + std::to_string(acc.count) + " is not from 1 to " +
                          std::to_string(kMaxGltfAccessorCount));
      acc.has_view = has(a, "bufferView");
      uint64_t stride = acc.element;
      if (acc.has_view) {
        acc.view = whole(a, "bufferView", 0, path_, item);
        const View& v = view_of(acc.view, item);
        if (v.stride) {
          if (v.stride < acc.element)
            refuse(path_, item + " has elements of " + std::to_string(acc.element) +
                              " bytes, but its buffer view's byteStride is " +
                              std::to_string(v.stride) + " (its elements would overlap)");
          stride = v.stride;
        }
        check_span(v, acc.offset, acc.count, stride, acc.element, item);
      } else if (!draco_[k] || has(a, "sparse")) {
        // Zeros, which Assimp allocates for a sparse accessor: no bytes bound their count, so
        // these do (they stand for elements that other accessors of the mesh hold).
        if (acc.count > largest_with_view_)
          refuse(path_, item + " has no buffer view and " + std::to_string(acc.count) +
                            " elements, more than the " + std::to_string(largest_with_view_) +
                            " of the largest accessor with data");
        if (acc.count * acc.element > kMaxGltfViewlessBytes)
          refuse(path_, item + " has no buffer view and " + std::to_string(acc.count) +
                            " elements of " + std::to_string(acc.element) + " bytes (more than " +
                            std::to_string(kMaxGltfViewlessBytes) + " bytes of zeros)");
      }
      if (const auto sparse = a.find("sparse"); sparse != a.end())
        acc.sparse = read_sparse(*sparse, acc, stride, item);
      accessors_.push_back(std::move(acc));
    }
  }

  // The accessors of primitives compressed with KHR_draco_mesh_compression (their indices and
  // attributes), which Assimp 5.2 fills from the decoded Draco mesh, not from a buffer view.
  void find_draco_accessors(size_t n_accessors) {
    draco_.assign(n_accessors, false);
    const auto mark = [&](const Json& index) {
      if (index.is_number_unsigned() && index.get<uint64_t>() < n_accessors)
        draco_[index.get<size_t>()] = true;
    };
    for (const Json& mesh : array_of(outline_, "meshes")) {
      const auto primitives = mesh.find("primitives");
      if (primitives == mesh.end() || !primitives->is_array()) continue;
      for (const Json& primitive : *primitives) {
        const auto extensions = primitive.find("extensions");
        if (extensions == primitive.end() || !extensions->is_object() ||
            !has(*extensions, "KHR_draco_mesh_compression"))
          continue;
        if (const auto indices = primitive.find("indices"); indices != primitive.end())
          mark(*indices);
        if (const auto attributes = primitive.find("attributes");
            attributes != primitive.end() && attributes->is_object())
          for (const auto& [name, index] : attributes->items()) mark(index);
      }
    }
  }

  Sparse read_sparse(const Json& sparse, const Accessor& acc, uint64_t stride,
                     const std::string& item) {
    const std::string where = item + "'s sparse part";
    if (!sparse.is_object()) refuse(path_, where + " is not an object");
    // Assimp 5.2 copies the base as count x element bytes and reads it with the view's stride.
    if (acc.has_view && stride != acc.element)
      refuse(path_,
             item + " is sparse on a strided buffer view (Assimp 5.2 reads its base as packed)");
    Sparse s;
    s.count = whole(sparse, "count", 0, path_, where);
    if (s.count < 1 || s.count > acc.count)
      refuse(path_, where + ": count " + std::to_string(s.count) +
                        " is not from 1 to the accessor's " + std::to_string(acc.count));
    const auto indices = sparse.find("indices"), values = sparse.find("values");
    if (indices == sparse.end() || !indices->is_object() || values == sparse.end() ||
        !values->is_object())
      refuse(path_, where + " lacks its indices or values");
    const uint64_t index_type = whole(*indices, "componentType", 0, path_, where);
    if (!unsigned_index_type(index_type))
      refuse(path_, where + ": its indices are not unsigned integers");
    s.index_size = component_bytes(index_type);
    s.index_view = whole(*indices, "bufferView", UINT64_MAX, path_, where);
    s.index_offset = whole(*indices, "byteOffset", 0, path_, where);
    s.value_view = whole(*values, "bufferView", UINT64_MAX, path_, where);
    s.value_offset = whole(*values, "byteOffset", 0, path_, where);
    // glTF forbids a byteStride on these views, and Assimp reads them packed.
    const View& index_view = view_of(s.index_view, where + " indices");
    const View& value_view = view_of(s.value_view, where + " values");
    if (index_view.stride || value_view.stride)
      refuse(path_, where + ": the buffer view of its " +
                        (index_view.stride ? "indices" : "values") +
                        " has a byteStride (glTF forbids it; Assimp 5.2 reads them packed)");
    check_span(index_view, s.index_offset, s.count, s.index_size, s.index_size, where + " indices");
    check_span(value_view, s.value_offset, s.count, acc.element, acc.element, where + " values");
    // Each index names an element of the accessor: Assimp writes there.
    if (const auto bytes = bytes_of(index_view))
      for (uint64_t i = 0; i < s.count; ++i) {
        const uint64_t index = unsigned_at(*bytes, s.index_offset + i * s.index_size, s.index_size);
        if (index >= acc.count)
          refuse(path_, where + ": index " + std::to_string(i) + " is " + std::to_string(index) +
                            ", past the accessor's " + std::to_string(acc.count) + " elements");
      }
    return s;
  }

  const Accessor& accessor_of(const Json& index, const std::string& item) {
    if (!index.is_number_unsigned() || index.get<uint64_t>() >= accessors_.size())
      refuse(path_, item + " names accessor " + index.dump().substr(0, 20) + ", but the file has " +
                        std::to_string(accessors_.size()));
    return accessors_[index.get<size_t>()];
  }

  void check_meshes() {
    const Json& meshes = array_of(outline_, "meshes");
    for (size_t m = 0; m < meshes.size(); ++m) {
      if (!meshes[m].is_object()) refuse(path_, "mesh " + std::to_string(m) + " is not an object");
      const auto primitives = meshes[m].find("primitives");
      if (primitives == meshes[m].end() || !primitives->is_array()) continue;  // Assimp says
      for (size_t p = 0; p < primitives->size(); ++p)
        check_primitive((*primitives)[p],
                        "mesh " + std::to_string(m) + " primitive " + std::to_string(p));
    }
  }

  void check_primitive(const Json& primitive, const std::string& item) {
    if (!primitive.is_object()) refuse(path_, item + " is not an object");
    const uint64_t mode = whole(primitive, "mode", 4, path_, item);
    if (mode > 6) refuse(path_, item + ": mode " + std::to_string(mode) + " is not one glTF has");
    const auto attributes = primitive.find("attributes");
    if (attributes == primitive.end() || !attributes->is_object() || !has(*attributes, "POSITION"))
      refuse(path_, item + " has no POSITION attribute");
    const Accessor& position = accessor_of((*attributes)["POSITION"], item + " POSITION");
    if (position.component != 5126 || position.type != "VEC3")
      refuse(path_, item +
                        ": its POSITION accessor is not float VEC3 (Assimp 5.2 reads other "
                        "positions, such as quantized ones, as garbage)");
    // glTF gives every attribute and morph target POSITION's count. Assimp 5.2 drops other
    // normals, coordinates and targets without a word, and reads JOINTS_n and WEIGHTS_n for
    // the count of the first set, past the end of a shorter one.
    const auto same_count = [&](const Json& list, const std::string& where) {
      if (!list.is_object()) refuse(path_, where + " is not an object");
      for (const auto& [name, index] : list.items()) {
        const Accessor& a = accessor_of(index, where + " " + name.substr(0, 30));
        if (a.count != position.count)
          refuse(path_, where + " " + name.substr(0, 30) + " has " + std::to_string(a.count) +
                            " elements, POSITION " + std::to_string(position.count));
      }
    };
    same_count(*attributes, item + " attribute");
    if (const auto targets = primitive.find("targets");
        targets != primitive.end() && targets->is_array())
      for (size_t t = 0; t < targets->size(); ++t)
        same_count((*targets)[t], item + " morph target " + std::to_string(t));
    uint64_t corners = position.count;
    if (const auto indices = primitive.find("indices"); indices != primitive.end()) {
      const Accessor& a = accessor_of(*indices, item + " indices");
      if (a.type != "SCALAR" || !unsigned_index_type(a.component))
        refuse(path_, item + ": its indices are not unsigned SCALAR");
      corners = a.count;
      check_indices(a, position.count, item);
    }
    // Assimp 5.2 makes count - 1 line strip segments and count - 2 triangles of a strip or fan
    // (of 1 index: 2^64 - 1 of them), writes a strip's first segment and a loop's closing one
    // unchecked, and drops the corners left over after the last whole triangle.
    if ((mode == 2 || mode == 3) && corners < 2)
      refuse(path_, item + " is a line " + (mode == 2 ? "loop" : "strip") + " of " +
                        std::to_string(corners) + " vertex (at least 2)");
    if ((mode == 5 || mode == 6) && corners < 3)
      refuse(path_, item + " is a triangle " + (mode == 5 ? "strip" : "fan") + " of " +
                        std::to_string(corners) + " vertices (at least 3)");
    if (mode == 4 && corners % 3 != 0)
      refuse(path_, item + " has " + std::to_string(corners) +
                        " triangle corners, not a multiple of 3 "
                        "(Assimp 5.2 drops the last " +
                        std::to_string(corners % 3) + ")");
  }

  // Every index, as Assimp reads it (the view's bytes, or zeros without one; a sparse
  // accessor's substitutions over them), is below `n_vertices`: Assimp drops the faces of
  // the others without a word.
  void check_indices(const Accessor& a, uint64_t n_vertices, const std::string& item) {
    const uint64_t size = component_bytes(a.component);
    std::vector<uint64_t> replaced;  // the elements a sparse accessor substitutes, sorted
    if (a.sparse) {
      const Sparse& s = *a.sparse;
      const auto positions = bytes_of(views_[size_t(s.index_view)]);
      const auto values = bytes_of(views_[size_t(s.value_view)]);
      if (!positions || !values) return;
      replaced.reserve(size_t(s.count));
      for (uint64_t i = 0; i < s.count; ++i) {
        const uint64_t at =
            unsigned_at(*positions, s.index_offset + i * s.index_size, s.index_size);
        const uint64_t index = unsigned_at(*values, s.value_offset + i * size, size);
        if (index >= n_vertices)
          refuse(path_, item + ": index " + std::to_string(at) + " is " + std::to_string(index) +
                            " (a sparse substitution), past its " + std::to_string(n_vertices) +
                            " vertices");
        replaced.push_back(at);
      }
      std::sort(replaced.begin(), replaced.end());
    }
    if (!a.has_view) return;  // zeros
    const View& v = views_[size_t(a.view)];
    const auto bytes = bytes_of(v);
    if (!bytes) return;
    const uint64_t stride = v.stride ? v.stride : size;
    size_t next = 0;
    for (uint64_t i = 0; i < a.count; ++i) {
      while (next < replaced.size() && replaced[next] < i) ++next;
      if (next < replaced.size() && replaced[next] == i) continue;
      const uint64_t index = unsigned_at(*bytes, a.offset + i * stride, size);
      if (index >= n_vertices)
        refuse(path_, item + ": index " + std::to_string(i) + " is " + std::to_string(index) +
                          ", past its " + std::to_string(n_vertices) + " vertices");
    }
  }

  // Nodes name existing meshes; a node with a mesh and a skin gets its inverse bind matrices
  // read by Assimp 5.2 without a check: missing, it crashes; short, it reads past them.
  void check_nodes() {
    const Json& nodes = array_of(outline_, "nodes");
    const Json& skins = array_of(outline_, "skins");
    const size_t n_meshes = array_of(outline_, "meshes").size();
    for (size_t v = 0; v < nodes.size(); ++v) {
      const auto mesh = nodes[v].find("mesh");
      if (mesh == nodes[v].end() || !mesh->is_number_unsigned()) continue;  // Assimp ignores it
      if (mesh->get<uint64_t>() >= n_meshes)
        refuse(path_, "node " + std::to_string(v) + " names mesh " +
                          std::to_string(mesh->get<uint64_t>()) + ", but the file has " +
                          std::to_string(n_meshes));
      const auto skin = nodes[v].find("skin");
      if (skin == nodes[v].end() || !skin->is_number_unsigned() ||
          skin->get<uint64_t>() >= skins.size())
        continue;  // Assimp leaves the mesh unskinned
      const std::string item =
          "node " + std::to_string(v) + "'s skin " + std::to_string(skin->get<uint64_t>());
      check_skin(skins[skin->get<size_t>()], item);
      check_skinned_vertices(array_of(outline_, "meshes")[mesh->get<size_t>()],
                             skins[skin->get<size_t>()], item);
    }
  }

  // Calls `check(value, element)` for every component of every element of `a` as Assimp reads
  // it: the view's elements, then a sparse accessor's substituted ones.
  template <typename Check>
  void for_each_component(const Accessor& a, Check check) {
    const uint64_t size = component_bytes(a.component), n = components(a.type);
    const auto read = [&](std::string_view bytes, uint64_t at, uint64_t element) {
      for (uint64_t k = 0; k < n; ++k) {
        const uint64_t bits = unsigned_at(bytes, at + k * size, size);
        if (a.component == 5126) {
          float value;
          const uint32_t word = uint32_t(bits);
          std::memcpy(&value, &word, 4);
          check(double(value), element);
        } else {
          check(double(bits), element);
        }
      }
    };
    if (a.has_view)
      if (const auto bytes = bytes_of(views_[size_t(a.view)])) {
        const uint64_t stride = views_[size_t(a.view)].stride ? views_[size_t(a.view)].stride
                                                               : a.element;
        for (uint64_t i = 0; i < a.count; ++i) read(*bytes, a.offset + i * stride, i);
      }
    if (a.sparse)
      if (const auto values = bytes_of(views_[size_t(a.sparse->value_view)]))
        for (uint64_t i = 0; i < a.sparse->count; ++i)
          read(*values, a.sparse->value_offset + i * a.element, i);
  }

  // A skinned primitive's JOINTS_n name joints of its skin and its float WEIGHTS_n are finite
  // and not negative: Assimp 5.2 drops the influences of other joints and of weights it finds
  // no larger than 0 without a word, and passes a NaN on.
  void check_skinned_vertices(const Json& mesh, const Json& skin, const std::string& item) {
    if (!mesh.is_object() || !skin.is_object()) return;
    const auto primitives = mesh.find("primitives");
    const auto joints = skin.find("joints");
    if (primitives == mesh.end() || !primitives->is_array() || joints == skin.end() ||
        !joints->is_array())
      return;  // Assimp says
    const uint64_t n_joints = joints->size();
    for (const Json& primitive : *primitives) {
      if (!primitive.is_object() || !has(primitive, "attributes")) continue;
      for (const auto& [name, index] : primitive["attributes"].items()) {
        const bool joint = name.rfind("JOINTS_", 0) == 0, weight = name.rfind("WEIGHTS_", 0) == 0;
        if (!joint && !weight) continue;
        // A named copy: C++17 lambdas cannot capture a structured binding.
        const std::string attribute = name.substr(0, 30);
        const Accessor& a = accessor_of(index, item + " " + attribute);
        for_each_component(a, [&](double value, uint64_t element) {
          if (joint && value >= double(n_joints))
            refuse(path_, item + ": vertex " + std::to_string(element) + " names joint " +
                              std::to_string(uint64_t(value)) + " in " + attribute +
                              ", but the skin has " + std::to_string(n_joints) + " joints");
          if (weight && !(value >= 0 && std::isfinite(value)))
            refuse(path_, item + ": vertex " + std::to_string(element) + " has the weight " +
                              std::to_string(value) + " in " + attribute +
                              " (weights are finite and not negative)");
        });
      }
    }
  }

  void check_skin(const Json& skin, const std::string& item) {
    if (!skin.is_object()) return;  // Assimp says
    uint64_t joints = 0;
    if (const auto list = skin.find("joints"); list != skin.end() && list->is_array())
      joints = uint64_t(std::count_if(list->begin(), list->end(),
                                      [](const Json& j) { return j.is_number_unsigned(); }));
    const auto matrices = skin.find("inverseBindMatrices");
    if (matrices == skin.end() || !matrices->is_number_unsigned())
      refuse(path_,
             item + " has no inverseBindMatrices (Assimp 5.2 needs them for a skinned mesh)");
    const Accessor& m = accessor_of(*matrices, item + " inverseBindMatrices");
    if (m.component != 5126 || m.type != "MAT4")
      refuse(path_, item + ": its inverseBindMatrices are not float MAT4");
    if (m.count < joints)
      refuse(path_, item + " has " + std::to_string(joints) + " joints but " +
                        std::to_string(m.count) + " inverseBindMatrices");
  }

  // Assimp 5.2 reads a CUBICSPLINE sampler's outputs 3 per input (in-tangent, value,
  // out-tangent) without a check, and for morph weights allocates (outputs / inputs - 2) values
  // per key: 2^32 of them when there are fewer than 2 outputs per input.
  void check_animations() {
    const Json& animations = array_of(outline_, "animations");
    for (size_t n = 0; n < animations.size(); ++n) {
      const auto samplers = animations[n].find("samplers");
      if (samplers == animations[n].end() || !samplers->is_array()) continue;
      for (size_t s = 0; s < samplers->size(); ++s) {
        const Json& sampler = (*samplers)[s];
        const std::string item = "animation " + std::to_string(n) + " sampler " + std::to_string(s);
        const auto input = sampler.find("input"), output = sampler.find("output");
        if (input == sampler.end() || output == sampler.end() || !input->is_number_unsigned() ||
            !output->is_number_unsigned())
          continue;  // Assimp skips it
        const uint64_t inputs = accessor_of(*input, item + " input").count;
        const uint64_t outputs = accessor_of(*output, item + " output").count;
        const auto interpolation = sampler.find("interpolation");
        if (interpolation != sampler.end() && *interpolation == "CUBICSPLINE" &&
            outputs < 3 * inputs)
          refuse(path_, item + " is CUBICSPLINE with " + std::to_string(outputs) + " outputs for " +
                            std::to_string(inputs) + " inputs (3 per input at least)");
      }
    }
  }

  const Json& outline_;
  const GltfBufferBytes& data_;
  const std::string& path_;
  std::vector<uint64_t> buffer_length_;
  std::vector<View> views_;
  std::vector<Accessor> accessors_;
  std::vector<bool> draco_;         // per accessor: filled from Draco data
  uint64_t largest_with_view_ = 0;  // the count of the largest accessor with a view or Draco data
};

}  // namespace

GltfBufferBytes gltf_buffer_bytes(const nlohmann::json& outline, std::string_view bytes,
                                  const std::optional<std::string>& folder) {
  GltfBufferBytes data;
  if (outline.is_discarded() || !outline.is_object()) return data;
  const Json& buffers = array_of(outline, "buffers");
  const bool glb = data.glb = bytes.substr(0, 4) == "glTF";
  for (size_t k = 0; k < buffers.size(); ++k) {
    std::optional<std::string_view> seen;
    std::string source = "it";
    const auto uri = buffers[k].find("uri");
    if (glb && k == 0) {
      // Assimp 5.2 makes a .glb's binary chunk its buffer 0, whatever that buffer's uri says.
      seen = glb_binary_chunk(bytes);
      source = "the GLB's binary chunk";
    } else if (uri != buffers[k].end() && uri->is_string()) {
      const std::string& name = uri->get_ref<const std::string&>();
      std::optional<std::string> decoded;
      if (name.rfind("data:", 0) == 0) {
        decoded = data_uri_bytes(name);
        source = "its data: URI";
      } else if (folder) {
        try {  // as Assimp finds it: the name as written, in the asset's folder
          decoded = read_input_file(folder->empty() ? name : *folder + "/" + name);
        } catch (const Error&) {
          // check_gltf_buffer_files names what is wrong with the file.
        }
        source = "its file";
      }
      if (decoded) seen = data.storage.emplace_back(std::move(*decoded));
    }
    data.bytes.push_back(seen);
    data.source.push_back(std::move(source));
  }
  return data;
}

void check_gltf_accessors(const nlohmann::json& outline, const GltfBufferBytes& buffers,
                          const std::string& path) {
  if (outline.is_discarded() || !outline.is_object()) return;
  Checker(outline, buffers, path).run();
}

}  // namespace primo::detail
