#pragma once
// Hidden faces (Blender's hide and reveal): a matter of the view and the selection only. A
// hidden face is not drawn, cannot be picked, brushed, box- or lasso-selected, and is never
// selected; it still deforms with the mesh, since the solver's input never reads this mask.

#include <memory>
#include <vector>

#include "selection.h"

namespace primo::editor {

// One byte per face, 1 where hidden; a null mask hides nothing.
using HiddenFaces = std::shared_ptr<const FaceMask>;

// Hides the selected faces and deselects them (H). Returns how many faces became hidden.
int hide_selected(FaceMask& hidden, FaceMask& selection);
// Hides every shown face that is not selected (Shift+H), the selection stays: isolation.
int hide_unselected(FaceMask& hidden, const FaceMask& selection);
// Shows every face again and selects the ones that were hidden, as Blender's Alt+H does, so
// that they can be hidden again at once. Returns how many faces came back.
int reveal_all(FaceMask& hidden, FaceMask& selection);

bool is_hidden(const HiddenFaces& hidden, int face);
int count_hidden(const HiddenFaces& hidden);
// By content, a null mask equal to one that hides nothing.
bool same_hidden(const HiddenFaces& a, const HiddenFaces& b);
// Removes the hidden faces from `faces`.
void drop_hidden(std::vector<int>& faces, const HiddenFaces& hidden);
// Deselects the hidden faces of `selection`.
void deselect_hidden(FaceMask& selection, const HiddenFaces& hidden);

}  // namespace primo::editor
