#include "paint.h"

#include <cmath>
#include <algorithm>
#include <map>

namespace primo::editor {

FactorArray paint_factors(const FactorArray& factors, int n_faces, const std::vector<int>& faces,
                          double value) {
  std::vector<double> out = factors ? *factors : std::vector<double>(size_t(n_faces), 1.0);
  for (int f : faces)
    if (f >= 0 && f < n_faces) out[f] = value;
  if (std::all_of(out.begin(), out.end(), [](double v) { return v == 1.0; })) return nullptr;
  return std::make_shared<const std::vector<double>>(std::move(out));
}

double falloff_weight(Falloff falloff, double t) {
  if (!(t < 1.0)) return 0.0;
  t = std::max(t, 0.0);
  switch (falloff) {
    case Falloff::Constant: return 1.0;
    case Falloff::Linear: return 1.0 - t;
    case Falloff::Smooth: return (1.0 - t * t) * (1.0 - t * t);
  }
  return 1.0;
}

FactorArray blend_factors(const FactorArray& factors, int n_faces, const std::vector<int>& faces,
                          const std::vector<double>& weights, double value) {
  std::vector<double> out = factors ? *factors : std::vector<double>(size_t(n_faces), 1.0);
  for (size_t i = 0; i < faces.size() && i < weights.size(); ++i) {
    const int f = faces[i];
    if (f < 0 || f >= n_faces || !(weights[i] > 0.0)) continue;
    const double w = std::min(weights[i], 1.0);
    const double blended = out[f] + w * (value - out[f]);
    out[f] = w >= 1.0 ? value : std::round(blended * 100.0) / 100.0;
  }
  if (std::all_of(out.begin(), out.end(), [](double v) { return v == 1.0; })) return nullptr;
  return std::make_shared<const std::vector<double>>(std::move(out));
}

FactorArray smooth_factors(const FactorArray& factors, const MeshTopology& t) {
  if (!factors) return nullptr;
  const std::vector<double>& in = *factors;
  std::vector<double> out(in.size(), 1.0);
  std::vector<int> seen(in.size(), -1);
  for (int f = 0; f < t.n_faces; ++f) {
    double sum = 0.0;
    int n = 0;
    for (int k = t.face_begin[f]; k < t.face_begin[f + 1]; ++k) {
      const int v = t.face_vertices[k];
      for (int i = t.vertex_face_begin[v]; i < t.vertex_face_begin[v + 1]; ++i) {
        const int g = t.vertex_faces[i];
        if (seen[g] == f) continue;  // a neighbour sharing two vertices counts once
        seen[g] = f;
        sum += in[g];
        ++n;
      }
    }
    out[f] = n > 0 ? std::round(sum / n * 100.0) / 100.0 : in[f];
  }
  if (std::all_of(out.begin(), out.end(), [](double v) { return v == 1.0; })) return nullptr;
  return std::make_shared<const std::vector<double>>(std::move(out));
}

FactorArray& layer_factors(EditState& state, PaintLayer layer) {
  return layer == PaintLayer::Height ? state.height_factor : state.width_factor;
}

const FactorArray& layer_factors(const EditState& state, PaintLayer layer) {
  return layer == PaintLayer::Height ? state.height_factor : state.width_factor;
}

std::vector<FactorGroup> group_factors(const FactorArray& factors) {
  std::map<double, std::vector<int>> by_value;
  if (factors)
    for (size_t f = 0; f < factors->size(); ++f)
      if ((*factors)[f] != 1.0) by_value[(*factors)[f]].push_back(int(f));
  std::vector<FactorGroup> groups;
  for (auto& [value, faces] : by_value) groups.push_back({value, std::move(faces)});
  return groups;
}

}  // namespace primo::editor
