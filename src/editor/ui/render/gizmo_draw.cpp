#include "gizmo_draw.h"

#include <algorithm>
#include <array>
#include <imgui.h>

#include <cmath>

#include "editor.h"
#include "view/face_colors.h"

namespace primo::editor {
namespace {

struct ToWindow {
  const ViewportRect& vp;
  ImVec2 operator()(const glm::dvec2& p) const {
    return ImVec2(float(vp.x + p.x / vp.scale), float(vp.y + p.y / vp.scale));
  }
  ImVec2 operator()(const glm::dvec3& p) const { return (*this)(glm::dvec2(p.x, p.y)); }
};

ImU32 rgba(float r, float g, float b, float a = 1.0f) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, a));
}

ImU32 axis_color(GizmoPart part, bool hot) {
  if (hot) return rgba(1.0f, 0.85f, 0.2f);
  switch (part) {
    case GizmoPart::X: return rgba(0.93f, 0.30f, 0.30f);
    case GizmoPart::Y: return rgba(0.45f, 0.85f, 0.30f);
    case GizmoPart::Z: return rgba(0.30f, 0.55f, 0.98f);
    default: return rgba(0.9f, 0.9f, 0.9f, 0.85f);
  }
}

void draw_gizmo(const Editor& e, ImDrawList* dl, const ToWindow& to_window) {
  GizmoKind kind;
  glm::dvec3 center;
  if (!e.gizmo_visible(kind, center)) return;
  const Camera& cam = e.camera();
  const GizmoPart active = e.gizmo_active();
  const GizmoPart hover = active != GizmoPart::None ? active : e.gizmo_hover();
  const ImVec2 c = to_window(cam.project(center));
  const glm::dmat3 axes = e.gizmo_axes();
  if (kind == GizmoKind::Translate) {
    const double size = gizmo_world_size(cam, center);
    for (GizmoPart p : {GizmoPart::X, GizmoPart::Y, GizmoPart::Z}) {
      const ImVec2 tip = to_window(cam.project(center + size * gizmo_axis(p, cam, axes)));
      const ImU32 col = axis_color(p, hover == p);
      dl->AddLine(c, tip, col, hover == p ? 4.0f : 3.0f);
      // Arrow head.
      ImVec2 d(tip.x - c.x, tip.y - c.y);
      const float len = std::sqrt(d.x * d.x + d.y * d.y);
      if (len > 1.0f) {
        d = ImVec2(d.x / len, d.y / len);
        const ImVec2 n(-d.y, d.x);
        dl->AddTriangleFilled(ImVec2(tip.x + d.x * 12, tip.y + d.y * 12),
                              ImVec2(tip.x + n.x * 6, tip.y + n.y * 6),
                              ImVec2(tip.x - n.x * 6, tip.y - n.y * 6), col);
      }
    }
    const float s = float(kGizmoHitPixels);
    dl->AddRectFilled(ImVec2(c.x - s, c.y - s), ImVec2(c.x + s, c.y + s),
                      hover == GizmoPart::View ? rgba(1.0f, 0.85f, 0.2f, 0.9f) : rgba(1, 1, 1, 0.35f));
    dl->AddRect(ImVec2(c.x - s, c.y - s), ImVec2(c.x + s, c.y + s), rgba(1, 1, 1, 0.9f));
    return;
  }
  for (GizmoPart p : {GizmoPart::View, GizmoPart::X, GizmoPart::Y, GizmoPart::Z}) {
    const std::vector<glm::dvec2> ring = gizmo_ring(cam, center, p, axes);
    std::vector<ImVec2> points;
    for (const auto& q : ring) points.push_back(to_window(q));
    dl->AddPolyline(points.data(), int(points.size()), axis_color(p, hover == p), ImDrawFlags_Closed,
                    hover == p ? 4.0f : 2.5f);
  }
  dl->AddCircleFilled(c, 3.0f, rgba(1, 1, 1, 0.9f));
}

}  // namespace

void draw_viewport_overlays(const Editor& e, ImDrawList* dl) {
  const Document* doc = e.document();
  if (!doc) return;
  const ToWindow to_window{e.viewport()};
  const Camera& cam = e.camera();
  const ViewportRect& vp = e.viewport();
  dl->PushClipRect(ImVec2(float(vp.x), float(vp.y)),
                   ImVec2(float(vp.x + vp.width), float(vp.y + vp.height)), true);

  // 1. Handle labels at their pivots.
  const EditState& s = doc->state;
  for (size_t i = 0; i < s.handles.size(); ++i) {
    const glm::dvec3 p = cam.project(e.handle_pivot(int(i)));
    if (p.z < 0.0 || p.z > 1.0) continue;
    const ImVec2 at = to_window(p);
    const Rgb col = handle_color(s.handles[i]);
    const bool active = int(i) == s.active;
    dl->AddCircleFilled(at, active ? 5.0f : 4.0f, rgba(col[0], col[1], col[2]));
    dl->AddCircle(at, active ? 5.0f : 4.0f, rgba(0, 0, 0, 0.8f));
    const char* name = s.handles[i].name.c_str();
    const ImVec2 text(at.x + 8, at.y - 8);
    dl->AddText(ImVec2(text.x + 1, text.y + 1), rgba(0, 0, 0, 0.7f), name);
    dl->AddText(text, active ? rgba(1, 1, 1) : rgba(0.85f, 0.85f, 0.85f, 0.85f), name);
  }

  // 2. Gestures and tools.
  const ImVec2 cursor = to_window(e.cursor_pixels());
  switch (e.gesture()) {
    case Editor::Gesture::SelectBox: {
      const ImVec2 a = to_window(e.gesture_start());
      dl->AddRectFilled(ImVec2(std::min(a.x, cursor.x), std::min(a.y, cursor.y)),
                        ImVec2(std::max(a.x, cursor.x), std::max(a.y, cursor.y)),
                        rgba(1.0f, 0.6f, 0.1f, 0.12f));
      dl->AddRect(a, cursor, rgba(1.0f, 0.7f, 0.2f, 0.9f), 0.0f, 0, 1.5f);
      break;
    }
    case Editor::Gesture::SelectLasso: {
      std::vector<ImVec2> points;
      for (const auto& q : e.lasso()) points.push_back(to_window(q));
      points.push_back(cursor);
      dl->AddPolyline(points.data(), int(points.size()), rgba(1.0f, 0.7f, 0.2f, 0.95f),
                      ImDrawFlags_Closed, 1.5f);
      break;
    }
    default: break;
  }
  if (e.brush_visible() && e.cursor_in_viewport() && !ImGui::GetIO().WantCaptureMouse) {
    const float r = float(e.tools.brush_radius);
    ImU32 col = rgba(1, 1, 1, 0.85f);
    if (e.tools.tool == Tool::Paint) {
      float opacity = 0;
      const double value = e.tools.paint_layer == PaintLayer::Height ? e.tools.paint_height
                                                                     : e.tools.paint_width;
      const Rgb c = factor_color(e.tools.paint_layer, value, opacity);
      col = rgba(c[0], c[1], c[2], 0.95f);
    }
    dl->AddCircle(cursor, r + 1.0f, rgba(0, 0, 0, 0.5f), 48, 1.0f);
    dl->AddCircle(cursor, r, col, 48, 1.5f);
  }
  draw_gizmo(e, dl, to_window);

  // 3. The world axes in the bottom-left corner, the far ones first and dimmer.
  const ImVec2 origin(float(vp.x) + 42.0f, float(vp.y + vp.height) - 42.0f);
  const std::array<glm::dvec3, 3> axes = cam.axes_on_screen();
  const char* names[3] = {"X", "Y", "Z"};
  const float colors[3][3] = {{0.95f, 0.35f, 0.35f}, {0.45f, 0.85f, 0.35f}, {0.35f, 0.55f, 1.0f}};
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return axes[size_t(a)].z > axes[size_t(b)].z; });
  dl->AddCircleFilled(origin, 34.0f, rgba(0, 0, 0, 0.25f));
  for (int k : order) {
    const glm::dvec3& a = axes[size_t(k)];
    const float alpha = a.z > 0.2 ? 0.45f : 1.0f;  // pointing away: behind the centre
    const ImVec2 tip(origin.x + float(a.x) * 26.0f, origin.y + float(a.y) * 26.0f);
    const ImU32 col = rgba(colors[k][0], colors[k][1], colors[k][2], alpha);
    dl->AddLine(origin, tip, col, 2.0f);
    dl->AddText(ImVec2(tip.x - 4.0f, tip.y - 7.0f), col, names[k]);
  }
  dl->PopClipRect();
}

}  // namespace primo::editor
