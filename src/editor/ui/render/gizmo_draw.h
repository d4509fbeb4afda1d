#pragma once
// What the viewport draws over the mesh with ImGui's background draw list: handle labels,
// the brush circle, the box or lasso being drawn, and the move/rotate gizmo.

struct ImDrawList;

namespace primo::editor {

class Editor;

void draw_viewport_overlays(const Editor& editor, ImDrawList* draw_list);

}  // namespace primo::editor
