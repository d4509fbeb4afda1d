#include "face_colors.h"

#include <algorithm>
#include <cmath>

namespace primo::editor {
namespace {

struct Rgba {
  float r = 0, g = 0, b = 0, a = 0;
};

// Porter-Duff "over" with non-premultiplied colours.
void over(Rgba& dst, const Rgb& c, float alpha) {
  const float a = alpha + dst.a * (1.0f - alpha);
  if (a <= 0) return;
  dst.r = (c[0] * alpha + dst.r * dst.a * (1.0f - alpha)) / a;
  dst.g = (c[1] * alpha + dst.g * dst.a * (1.0f - alpha)) / a;
  dst.b = (c[2] * alpha + dst.b * dst.a * (1.0f - alpha)) / a;
  dst.a = a;
}

std::uint32_t pack(const Rgba& c) {
  auto byte = [](float v) { return std::uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  return byte(c.r) | byte(c.g) << 8 | byte(c.b) << 16 | byte(c.a) << 24;
}

Rgb rgb(int r, int g, int b) { return {r / 255.0f, g / 255.0f, b / 255.0f}; }

}  // namespace

Rgb handle_color(const HandleGroup& group) {
  if (group.mode == HandleMode::Fixed) return rgb(125, 135, 155);
  static const Rgb palette[] = {rgb(66, 165, 245), rgb(102, 187, 106), rgb(255, 202, 40),
                                rgb(239, 83, 80),  rgb(171, 71, 188),  rgb(38, 198, 218),
                                rgb(255, 112, 67), rgb(236, 64, 122)};
  return palette[((group.color % 8) + 8) % 8];
}

Rgb selection_color() { return rgb(255, 152, 28); }

// Dark rather than a hue: every hue already means something (handles, paint, selection), and
// darker reads as "left out" over any of them.
Rgb without_twin_color() { return rgb(16, 14, 28); }

Rgb heat_color(double t) {
  static const Rgb stops[] = {rgb(48, 62, 150), rgb(40, 150, 230), rgb(30, 210, 170),
                              rgb(165, 230, 60), rgb(250, 185, 50), rgb(215, 40, 25)};
  const int n = int(std::size(stops)) - 1;
  const double x = std::clamp(t, 0.0, 1.0) * n;
  const int i = std::min(int(x), n - 1);
  const float u = float(x - i);
  return {stops[i][0] + u * (stops[i + 1][0] - stops[i][0]),
          stops[i][1] + u * (stops[i + 1][1] - stops[i][1]),
          stops[i][2] + u * (stops[i + 1][2] - stops[i][2])};
}

Rgb factor_color(PaintLayer layer, double factor, float& opacity) {
  if (factor == 1.0 || !(factor > 0.0)) {
    opacity = factor == 1.0 ? 0.0f : 0.85f;
    return rgb(20, 40, 230);
  }
  // Half a step of opacity per halving or doubling, from 0.35 up.
  const double octaves = std::abs(std::log2(factor));
  opacity = float(std::min(0.85, 0.35 + 0.25 * octaves));
  // Paint shows under handles (55% over them), so no paint colour may pass for a handle's:
  // each is more than 100 RGB units from every colour of the handles' palette. Hence softer
  // joints in indigo (not the palette's sky blue), stiffer in a deep red (not its coral red),
  // and the width layer's purple and green darker than the palette's.
  if (layer == PaintLayer::Height) return factor < 1.0 ? rgb(60, 40, 200) : rgb(180, 0, 0);
  return factor < 1.0 ? rgb(90, 0, 130) : rgb(0, 130, 30);
}

std::vector<std::uint32_t> face_overlay_colors(const OverlayInputs& in) {
  std::vector<Rgba> c(size_t(in.n_faces));
  const EditState& s = *in.state;
  if (in.face_energy && int(in.face_energy->size()) == in.n_faces) {
    for (int f = 0; f < in.n_faces; ++f) {
      // Square root: the energy is quadratic in the displacement.
      const double t = std::sqrt(std::max(0.0, double((*in.face_energy)[f]) / in.energy_scale));
      over(c[f], heat_color(t), 1.0f);
    }
  } else if (in.paint_overlay) {
    const FactorArray& factors = layer_factors(s, in.paint_layer);
    if (factors)
      for (int f = 0; f < in.n_faces; ++f) {
        float opacity = 0.0f;
        const Rgb color = factor_color(in.paint_layer, (*factors)[f], opacity);
        if (opacity > 0) over(c[f], color, opacity);
      }
  }
  if (in.without_twin && int(in.without_twin->size()) == in.n_faces)
    for (int f = 0; f < in.n_faces; ++f)
      if ((*in.without_twin)[size_t(f)]) over(c[f], without_twin_color(), 0.55f);
  // Over the heat map, handles and the selection are lighter so the energy shows through.
  const float dim = in.face_energy ? 0.5f : 1.0f;
  // The active handle's falloff, shaded by weight (soft_selection.h).
  if (s.active >= 0 && s.active < int(s.handles.size()) && s.handles[size_t(s.active)].falloff)
    for (const FalloffFace& f : *s.handles[size_t(s.active)].falloff)
      if (f.face >= 0 && f.face < in.n_faces)
        over(c[size_t(f.face)], handle_color(s.handles[size_t(s.active)]), dim * float(0.6 * f.weight));
  for (size_t g = 0; g < s.handles.size(); ++g) {
    const HandleGroup& h = s.handles[g];
    float alpha = dim * (int(g) == s.active ? 0.8f : 0.55f);
    if (int(g) == in.hovered_handle) alpha = std::min(1.0f, alpha + 0.2f);
    const Rgb color = handle_color(h);
    for (int f : *h.faces)
      if (f >= 0 && f < in.n_faces) over(c[f], color, alpha);
  }
  if (s.selection)
    for (int f = 0; f < in.n_faces && f < int(s.selection->size()); ++f)
      if ((*s.selection)[f]) over(c[f], selection_color(), dim * 0.7f);
  std::vector<std::uint32_t> packed(c.size());
  std::transform(c.begin(), c.end(), packed.begin(), pack);
  if (s.hidden)
    for (int f = 0; f < in.n_faces && f < int(s.hidden->size()); ++f)
      if ((*s.hidden)[size_t(f)]) packed[size_t(f)] = kHiddenFaceColor;
  return packed;
}

}  // namespace primo::editor
