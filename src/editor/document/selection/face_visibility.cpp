#include "face_visibility.h"

#include <algorithm>

namespace primo::editor {

int hide_selected(FaceMask& hidden, FaceMask& selection) {
  int n = 0;
  for (size_t f = 0; f < selection.size() && f < hidden.size(); ++f) {
    if (!selection[f]) continue;
    n += hidden[f] ? 0 : 1;
    hidden[f] = 1;
    selection[f] = 0;
  }
  return n;
}

int hide_unselected(FaceMask& hidden, const FaceMask& selection) {
  int n = 0;
  for (size_t f = 0; f < selection.size() && f < hidden.size(); ++f)
    if (!selection[f] && !hidden[f]) {
      hidden[f] = 1;
      ++n;
    }
  return n;
}

int reveal_all(FaceMask& hidden, FaceMask& selection) {
  int n = 0;
  for (size_t f = 0; f < hidden.size(); ++f) {
    if (!hidden[f]) continue;
    hidden[f] = 0;
    if (f < selection.size()) selection[f] = 1;
    ++n;
  }
  return n;
}

bool is_hidden(const HiddenFaces& hidden, int face) {
  return hidden && face >= 0 && face < int(hidden->size()) && (*hidden)[size_t(face)];
}

int count_hidden(const HiddenFaces& hidden) { return hidden ? count_selected(*hidden) : 0; }

bool same_hidden(const HiddenFaces& a, const HiddenFaces& b) {
  if (a == b) return true;
  if (a && b) return *a == *b;
  return count_hidden(a ? a : b) == 0;
}

void drop_hidden(std::vector<int>& faces, const HiddenFaces& hidden) {
  if (!hidden) return;
  faces.erase(std::remove_if(faces.begin(), faces.end(),
                             [&](int f) { return is_hidden(hidden, f); }),
              faces.end());
}

void deselect_hidden(FaceMask& selection, const HiddenFaces& hidden) {
  if (!hidden) return;
  for (size_t f = 0; f < selection.size() && f < hidden->size(); ++f)
    if ((*hidden)[f]) selection[f] = 0;
}

}  // namespace primo::editor
