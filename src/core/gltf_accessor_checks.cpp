#include "gltf_accessor_checks.h"

#include <cstdint>
#include <cstring>

#include "primo/error.h"
#include "primo/input_files.h"

namespace primo::detail {
namespace {

using Json = nlohmann::json;

[[noreturn]] void refuse(const std::string& path, const std::string& rule) {
  throw Error(path + ": cannot read: not a glTF file PriMo accepts (" + rule + ")");
}

// An accessor without a buffer view is zeros: no bytes bound its count, this does.
constexpr uint64_t kMaxViewlessCount = uint64_t(1) << 24;
// More than any real asset declares; keeps every product below of 64-bit range.
constexpr uint64_t kMaxCount = uint64_t(1) << 32;

uint32_t u32_le(std::string_view bytes, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | uint8_t(bytes[at + size_t(k)]);
  return v;
}

// A .glb's BIN chunk (the second chunk), or nullopt.
std::optional<std::string> glb_binary_chunk(std::string_view bytes) {
  if (bytes.size() < 20 || bytes.substr(0, 4) != "glTF") return std::nullopt;
  const uint64_t json_end = 20 + uint64_t(u32_le(bytes, 12));
  if (json_end + 8 > bytes.size() || u32_le(bytes, size_t(json_end) + 4) != 0x004E4942)
    return std::nullopt;
  const uint64_t length = u32_le(bytes, size_t(json_end));
  const uint64_t begin = json_end + 8;
  return std::string(bytes.substr(size_t(begin), size_t(std::min<uint64_t>(length, bytes.size() - begin))));
}

// The bytes of a base64 data: URI, or nullopt for any other form.
std::optional<std::string> data_uri_bytes(const std::string& uri) {
  const size_t comma = uri.find(',');
  if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos)
    return std::nullopt;
  std::string out;
  out.reserve((uri.size() - comma) / 4 * 3);
  uint32_t bits = 0;
  int n_bits = 0;
  for (size_t i = comma + 1; i < uri.size(); ++i) {
    const char c = uri[i];
    int v;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '+') v = 62;
    else if (c == '/') v = 63;
    else if (c == '=') break;
    else return std::nullopt;
    bits = (bits << 6) | uint32_t(v);
    n_bits += 6;
    if (n_bits >= 8) {
      n_bits -= 8;
      out += char((bits >> n_bits) & 0xFF);
    }
  }
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
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
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

struct View {
  uint64_t buffer = 0, offset = 0, length = 0, stride = 0;  // stride 0: none given
};

struct Accessor {
  bool has_view = false;
  uint64_t view = 0, offset = 0, count = 0, component = 0, element = 0;
  std::string type;
  bool sparse = false;
};

class Checker {
 public:
  Checker(const Json& outline, const std::vector<std::optional<std::string>>& buffers,
          const std::string& path)
      : outline_(outline), data_(buffers), path_(path) {}

  void run() {
    read_buffers();
    read_views();
    read_accessors();
    check_meshes();
  }

 private:
  void read_buffers() {
    const Json& buffers = array_of(outline_, "buffers");
    for (size_t k = 0; k < buffers.size(); ++k) {
      const std::string item = "buffer " + std::to_string(k);
      if (!buffers[k].is_object()) refuse(path_, item + " is not an object");
      const uint64_t declared = whole(buffers[k], "byteLength", 0, path_, item);
      if (k < data_.size() && data_[k] && declared > data_[k]->size())
        refuse(path_, item + " declares " + std::to_string(declared) + " bytes but holds " +
                          std::to_string(data_[k]->size()));
      buffer_length_.push_back(declared);
    }
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
        refuse(path_, item + (has(views[k], "buffer") ? " names buffer " + std::to_string(v.buffer) : " names no buffer") +
                          "; the file has " + std::to_string(buffer_length_.size()));
      if (v.offset > buffer_length_[v.buffer] || v.length > buffer_length_[v.buffer] - v.offset)
        refuse(path_, item + " (bytes " + std::to_string(v.offset) + " + " + std::to_string(v.length) +
                          ") runs past buffer " + std::to_string(v.buffer) + " (" +
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

  void check_span(const View& v, uint64_t offset, uint64_t count, uint64_t stride,
                  uint64_t element, const std::string& item) {
    // count, stride and element are bounded, and offset checked first: no sum overflows.
    const uint64_t end = offset > v.length ? UINT64_MAX : offset + (count - 1) * stride + element;
    if (end > v.length)
      refuse(path_, item + " reads " + std::to_string(end) + " bytes (offset " + std::to_string(offset) +
                        ", " + std::to_string(count) + " elements of " + std::to_string(element) +
                        " bytes, stride " + std::to_string(stride) + ") from a buffer view of " +
                        std::to_string(v.length));
  }

  // The bytes of view `v` when its buffer's bytes can be seen.
  std::optional<std::string_view> bytes_of(const View& v) const {
    if (v.buffer >= data_.size() || !data_[v.buffer]) return std::nullopt;
    return std::string_view(*data_[v.buffer]).substr(size_t(v.offset), size_t(v.length));
  }

  static uint64_t unsigned_at(std::string_view bytes, uint64_t at, uint64_t size) {
    uint64_t value = 0;
    for (uint64_t k = size; k-- > 0;) value = (value << 8) | uint8_t(bytes[size_t(at + k)]);
    return value;
  }

  void read_accessors() {
    const Json& accessors = array_of(outline_, "accessors");
    for (size_t k = 0; k < accessors.size(); ++k) {
      const std::string item = "accessor " + std::to_string(k);
      const Json& a = accessors[k];
      if (!a.is_object()) refuse(path_, item + " is not an object");
      Accessor acc;
      acc.component = whole(a, "componentType", 0, path_, item);
      const auto type = a.find("type");
      acc.type = type != a.end() && type->is_string() ? type->get<std::string>() : "";
      const uint64_t size = component_bytes(acc.component);
      if (size == 0) refuse(path_, item + ": componentType " + std::to_string(acc.component) + " is not one glTF has");
      if (components(acc.type) == 0) refuse(path_, item + ": type '" + acc.type.substr(0, 20) + "' is not one glTF has");
      acc.element = size * components(acc.type);
      acc.count = whole(a, "count", 0, path_, item);
      acc.offset = whole(a, "byteOffset", 0, path_, item);
      if (acc.count < 1 || acc.count > kMaxCount)
        refuse(path_, item + ": count " + std::to_string(acc.count) + " is not from 1 to " + std::to_string(kMaxCount));
      acc.has_view = has(a, "bufferView");
      uint64_t stride = acc.element;
      if (acc.has_view) {
        acc.view = whole(a, "bufferView", 0, path_, item);
        const View& v = view_of(acc.view, item);
        if (v.stride) {
          if (v.stride < acc.element)
            refuse(path_, item + " has elements of " + std::to_string(acc.element) +
                              " bytes, but its buffer view's byteStride is " + std::to_string(v.stride) +
                              " (its elements would overlap)");
          stride = v.stride;
        }
        check_span(v, acc.offset, acc.count, stride, acc.element, item);
      } else if (acc.count > kMaxViewlessCount && !has(a, "sparse")) {
        refuse(path_, item + " has no buffer view and a count of " + std::to_string(acc.count) +
                          " (more than " + std::to_string(kMaxViewlessCount) + " zeros)");
      }
      if (const auto sparse = a.find("sparse"); sparse != a.end()) {
        acc.sparse = true;
        check_sparse(*sparse, acc, stride, item);
      }
      accessors_.push_back(acc);
    }
  }

  void check_sparse(const Json& sparse, const Accessor& acc, uint64_t stride, const std::string& item) {
    const std::string where = item + "'s sparse part";
    if (!sparse.is_object()) refuse(path_, where + " is not an object");
    if (acc.has_view && stride != acc.element)
      refuse(path_, item + " is sparse on a strided buffer view (Assimp 5.2 reads its base as packed)");
    if (acc.count > kMaxViewlessCount && !acc.has_view)
      refuse(path_, item + " has no buffer view and a count of " + std::to_string(acc.count));
    const uint64_t count = whole(sparse, "count", 0, path_, where);
    if (count < 1 || count > acc.count)
      refuse(path_, where + ": count " + std::to_string(count) + " is not from 1 to the accessor's " +
                        std::to_string(acc.count));
    const auto indices = sparse.find("indices"), values = sparse.find("values");
    if (indices == sparse.end() || !indices->is_object() || values == sparse.end() || !values->is_object())
      refuse(path_, where + " lacks its indices or values");
    const uint64_t index_type = whole(*indices, "componentType", 0, path_, where);
    if (index_type != 5121 && index_type != 5123 && index_type != 5125)
      refuse(path_, where + ": its indices are not unsigned integers");
    const uint64_t index_size = component_bytes(index_type);
    const View& index_view = view_of(whole(*indices, "bufferView", UINT64_MAX, path_, where), where + " indices");
    const uint64_t index_offset = whole(*indices, "byteOffset", 0, path_, where);
    check_span(index_view, index_offset, count, index_size, index_size, where + " indices");
    const View& value_view = view_of(whole(*values, "bufferView", UINT64_MAX, path_, where), where + " values");
    check_span(value_view, whole(*values, "byteOffset", 0, path_, where), count, acc.element, acc.element,
               where + " values");
    // Each index names an element of the accessor: Assimp writes there unchecked.
    if (const auto bytes = bytes_of(index_view))
      for (uint64_t i = 0; i < count; ++i) {
        const uint64_t index = unsigned_at(*bytes, index_offset + i * index_size, index_size);
        if (index >= acc.count)
          refuse(path_, where + ": index " + std::to_string(i) + " is " + std::to_string(index) +
                            ", past the accessor's " + std::to_string(acc.count) + " elements");
      }
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
        check_primitive((*primitives)[p], "mesh " + std::to_string(m) + " primitive " + std::to_string(p));
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
      refuse(path_, item + ": its POSITION accessor is not float VEC3");
    // Assimp reads every attribute, and every morph target, for POSITION's count of vertices.
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
    if (const auto targets = primitive.find("targets"); targets != primitive.end() && targets->is_array())
      for (size_t t = 0; t < targets->size(); ++t)
        same_count((*targets)[t], item + " morph target " + std::to_string(t));
    uint64_t corners = position.count;
    if (const auto indices = primitive.find("indices"); indices != primitive.end()) {
      const Accessor& a = accessor_of(*indices, item + " indices");
      if (a.type != "SCALAR" || (a.component != 5121 && a.component != 5123 && a.component != 5125))
        refuse(path_, item + ": its indices are not unsigned SCALAR");
      corners = a.count;
      check_indices(a, position.count, item);
    }
    if ((mode == 5 || mode == 6) && corners < 3)
      refuse(path_, item + " is a triangle " + (mode == 5 ? "strip" : "fan") + " of " +
                        std::to_string(corners) + " vertices (at least 3)");
  }

  void check_indices(const Accessor& a, uint64_t n_vertices, const std::string& item) {
    if (!a.has_view || a.sparse) return;
    const View& v = views_[size_t(a.view)];
    const auto bytes = bytes_of(v);
    if (!bytes) return;
    const uint64_t size = component_bytes(a.component);
    const uint64_t stride = v.stride ? v.stride : size;
    for (uint64_t i = 0; i < a.count; ++i) {
      const uint64_t index = unsigned_at(*bytes, a.offset + i * stride, size);
      if (index >= n_vertices)
        refuse(path_, item + ": index " + std::to_string(i) + " is " + std::to_string(index) +
                          ", past its " + std::to_string(n_vertices) + " vertices");
    }
  }

  const Json& outline_;
  const std::vector<std::optional<std::string>>& data_;
  const std::string& path_;
  std::vector<uint64_t> buffer_length_;
  std::vector<View> views_;
  std::vector<Accessor> accessors_;
};

}  // namespace

std::vector<std::optional<std::string>> gltf_buffer_bytes(const nlohmann::json& outline,
                                                          std::string_view bytes,
                                                          const std::optional<std::string>& folder) {
  std::vector<std::optional<std::string>> data;
  if (outline.is_discarded() || !outline.is_object()) return data;
  const Json& buffers = array_of(outline, "buffers");
  for (const Json& buffer : buffers) {
    std::optional<std::string> bytes_of_buffer;
    const auto uri = buffer.is_object() ? buffer.find("uri") : buffer.end();
    if (buffer.is_object() && uri == buffer.end()) {
      bytes_of_buffer = glb_binary_chunk(bytes);
    } else if (buffer.is_object() && uri->is_string()) {
      const std::string& name = uri->get_ref<const std::string&>();
      if (name.rfind("data:", 0) == 0) {
        bytes_of_buffer = data_uri_bytes(name);
      } else if (folder) {
        try {  // as Assimp finds it: the name as written, in the asset's folder
          bytes_of_buffer = read_input_file(folder->empty() ? name : *folder + "/" + name);
        } catch (const Error&) {
          // check_gltf_buffer_files names what is wrong with the file.
        }
      }
    }
    data.push_back(std::move(bytes_of_buffer));
  }
  return data;
}

void check_gltf_accessors(const nlohmann::json& outline,
                          const std::vector<std::optional<std::string>>& buffers,
                          const std::string& path) {
  if (outline.is_discarded() || !outline.is_object()) return;
  Checker(outline, buffers, path).run();
}

}  // namespace primo::detail
