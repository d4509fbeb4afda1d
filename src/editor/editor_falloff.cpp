// Soft selection: a handle's influence fading over a radius (soft_selection.h).

#include <algorithm>
#include <cstdio>

#include "editor.h"

namespace primo::editor {

void Editor::set_falloff_radius(int index, double radius) {
  if (!doc_ || index < 0 || index >= int(doc_->state.handles.size())) return;
  end_gesture_before_edit();
  EditState& s = doc_->state;
  radius = std::clamp(radius, 0.0, doc_->topology->bbox_diagonal);
  set_falloff(s, *doc_->topology, index, radius);
  if (radius > 0) tools.falloff_radius = radius;
  const HandleGroup& g = s.handles[size_t(index)];
  commit("Falloff of '" + g.name + "'");
  if (radius <= 0) return info("'" + g.name + "' has no falloff: its influence ends at its faces");
  char text[160];
  std::snprintf(text, sizeof text, "'%s' fades over %.3g (%zu free faces; Alt + wheel scales it, O turns it off)",
                g.name.c_str(), radius, g.falloff ? g.falloff->size() : size_t(0));
  info(text);
}

void Editor::toggle_falloff() {
  if (!doc_) return;
  const EditState& s = doc_->state;
  if (s.active < 0 || s.active >= int(s.handles.size()))
    return error_in_status("Make or pick a handle first: its falloff fades its pull over a radius");
  const HandleGroup& g = s.handles[size_t(s.active)];
  const double last = tools.falloff_radius > 0 ? tools.falloff_radius : 0.1 * doc_->topology->bbox_diagonal;
  set_falloff_radius(s.active, g.falloff_radius > 0 ? 0.0 : last);
}

}  // namespace primo::editor
