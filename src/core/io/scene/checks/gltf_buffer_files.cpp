#include "gltf_buffer_files.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "primo/util/error.h"
#include "primo/io/input_files.h"
#include "primo/io/json_limits.h"

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
  std::string section;  // the top-level key being parsed
  return nlohmann::json::parse(
      text,
      [&section](int depth, Event event, nlohmann::json& parsed) {
        if (event == Event::key && depth == 1) {
          section = parsed.get<std::string>();
          return section == "buffers" || section == "bufferViews" || section == "accessors" ||
                 section == "meshes" || section == "nodes" || section == "scenes" ||
                 section == "skins" || section == "animations";
        }
        // A buffer's data URI is kept for the accessor checks; images' are not.
        if (event == Event::value && section != "buffers" && parsed.is_string() &&
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

}  // namespace primo::detail
