#pragma once
// The false colours drawn over the surface, one RGBA per face: energy heat map, painted
// factors, the shade of faces without a mirror twin, handle groups and the selection,
// composited in that order (later on top).

#include <array>
#include <cstdint>
#include <vector>

#include "document/edit_state.h"
#include "document/paint.h"

namespace primo::editor {

using Rgb = std::array<float, 3>;  // 0..1

Rgb handle_color(const HandleGroup& group);
Rgb selection_color();
// Darkens faces a mirror that is on has no twin for (mirror.h), under handles and selection.
Rgb without_twin_color();
// Heat-map colour of t in [0, 1] (blue - cyan - green - yellow - red).
Rgb heat_color(double t);
// Colour and opacity of a painted factor on a layer (opacity 0 for 1).
Rgb factor_color(PaintLayer layer, double factor, float& opacity);

struct OverlayInputs {
  const EditState* state = nullptr;
  int n_faces = 0;
  bool paint_overlay = true;
  PaintLayer paint_layer = PaintLayer::Height;
  const std::vector<float>* face_energy = nullptr;  // heat map when not null
  double energy_scale = 1.0;
  int hovered_handle = -1;
  // Per face, 1 where a mirror that is on has no twin (Editor::faces_without_twin); null or
  // empty: none shaded.
  const std::vector<char>* without_twin = nullptr;
};

// A hidden face's overlay (face_visibility.h): the surface and pick shaders discard it. No
// other face has it: a face nothing covers is all 0.
constexpr std::uint32_t kHiddenFaceColor = 0x000000FFu;
inline bool is_hidden_color(std::uint32_t c) { return c == kHiddenFaceColor; }

// RGBA8 per face packed as R | G << 8 | B << 16 | A << 24 (A = how much it covers the
// material colour), or kHiddenFaceColor.
std::vector<std::uint32_t> face_overlay_colors(const OverlayInputs& in);

}  // namespace primo::editor
