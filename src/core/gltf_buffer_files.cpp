#include "gltf_buffer_files.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "primo/error.h"
#include "primo/input_files.h"
#include "primo/json_limits.h"

namespace fs = std::filesystem;

namespace primo::detail {
namespace {

constexpr size_t kGlbHeaderBytes = 12;          // magic, version, length
constexpr size_t kGlbChunkHeaderBytes = 8;      // length, type
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON", little-endian

bool is_glb(std::string_view bytes) { return bytes.substr(0, 4) == "glTF"; }

uint32_t little_endian_u32(std::string_view bytes, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | uint8_t(bytes[at + size_t(k)]);
  return v;
}

// Whether a .glb's first chunk, right after its header, is its JSON.
bool has_json_chunk(std::string_view bytes) {
  return bytes.size() >= kGlbHeaderBytes + kGlbChunkHeaderBytes &&
         little_endian_u32(bytes, kGlbHeaderBytes + 4) == kGlbJsonChunk;
}

// The JSON text of a .glb (as much of it as `bytes` hold; empty without a JSON chunk).
std::string_view glb_json(std::string_view bytes) {
  if (!has_json_chunk(bytes)) return {};
  return bytes.substr(kGlbHeaderBytes + kGlbChunkHeaderBytes,
                      little_endian_u32(bytes, kGlbHeaderBytes));
}

}  // namespace

std::string_view gltf_json_text(std::string_view bytes) {
  return is_glb(bytes) ? glb_json(bytes) : bytes;
}

nlohmann::json gltf_outline(std::string_view bytes, const std::string& path) {
  const std::string_view text = gltf_json_text(bytes);
  check_json_depth(text, path);
  using Event = nlohmann::json::parse_event_t;
  return nlohmann::json::parse(
      text,
      [](int depth, Event event, nlohmann::json& parsed) {
        if (event == Event::key && depth == 1)
          return parsed == "buffers" || parsed == "nodes" || parsed == "scenes";
        if (event == Event::value && parsed.is_string() &&
            parsed.get_ref<const std::string&>().rfind("data:", 0) == 0)
          parsed = "data:";
        return true;
      },
      false);
}

void check_gltf_buffer_files(const nlohmann::json& json, const std::string& path) {
  if (json.is_discarded() || !json.is_object()) return;
  const auto buffers = json.find("buffers");
  if (buffers == json.end()) return;
  const fs::path folder = fs::path(path).parent_path();
  // glTF 2 lists buffers in an array, glTF 1 (which Assimp also reads) in an object by id.
  auto check = [&](const std::string& label, const nlohmann::json& buffer) {
    if (!buffer.is_object()) return;
    const auto uri = buffer.find("uri");
    if (uri == buffer.end() || !uri->is_string()) return;
    const std::string& name = uri->get_ref<const std::string&>();
    if (name.rfind("data:", 0) == 0) return;  // the bytes are in the URI itself
    // What Assimp opens: the name as written (not decoding "%20"), appended to the asset's
    // folder (so "/dev/zero" is looked for inside it).
    const std::string file = folder.empty() ? name : folder.string() + "/" + name;
    try {
      check_input_file(file);
    } catch (const Error& e) {
      throw Error(path + ": buffer " + label + " (" + name + "): " + e.what());
    }
  };
  if (buffers->is_array())
    for (size_t k = 0; k < buffers->size(); ++k) check(std::to_string(k), (*buffers)[k]);
  else if (buffers->is_object())
    for (const auto& [id, buffer] : buffers->items()) check("'" + id + "'", buffer);
}

std::string read_gltf_json_part(const std::string& path, bool binary) {
  if (!binary) return read_input_file(path);
  check_input_file(path);
  std::ifstream in(path, std::ios::binary);
  std::string head(kGlbHeaderBytes + kGlbChunkHeaderBytes, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  if (!is_glb(head) || !has_json_chunk(head)) return head;  // Assimp will say what is wrong
  // No more than the file holds, whatever its header says.
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  const std::uintmax_t json_bytes = std::min<std::uintmax_t>(
      little_endian_u32(head, kGlbHeaderBytes), !ec && size > head.size() ? size - head.size() : 0);
  std::string json(size_t(json_bytes), '\0');
  in.read(json.data(), std::streamsize(json.size()));
  json.resize(size_t(in.gcount()));
  return head + json;
}

}  // namespace primo::detail
