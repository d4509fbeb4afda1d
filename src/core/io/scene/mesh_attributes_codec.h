#pragma once
// Internal to the core library: face-corner attributes as bytes, for the scene reader's child
// process to send them to its parent (scene_reader_process.h).

#include <string>
#include <string_view>

#include "primo/mesh/mesh_attributes.h"

namespace primo::detail {

std::string encode_attributes(const MeshAttributes& attributes);

// False when the bytes do not hold together (an incomplete reply); sizes are checked against
// the bytes before anything is allocated.
bool decode_attributes(std::string_view bytes, MeshAttributes& attributes);

}  // namespace primo::detail
