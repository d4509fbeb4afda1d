#pragma once
// A fingerprint of what Dear ImGui would draw this frame: its vertices, indices, textures and
// clip rectangles. Two frames with the same fingerprint draw the same panels, so a frame
// whose panels and 3D view did not change need not be drawn again (view/shown_picture.h).

#include <cstdint>

struct ImDrawData;

namespace primo::editor {

std::uint64_t draw_data_fingerprint(const ImDrawData& data);

}  // namespace primo::editor
