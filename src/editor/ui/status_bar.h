#pragma once
// The status bar along the window's bottom: on the left the newest message (or the tool and
// the F1 hint), on the right the tool, the solver's state, the energy and the frame time. Both
// are laid out in the bar's width: the right side whole, the message cut before it with "..."
// and shown whole as a tooltip, so the two never draw over each other.

#include <string>

#include "editor.h"
#include "panels.h"

namespace primo::editor {

// `text` as it fits in `width` pixels of the current font: whole, or its longest start (at a
// UTF-8 character boundary) followed by "..."; "" when not even "..." fits.
std::string text_that_fits(const std::string& text, float width);

struct StatusBarLayout {
  std::string left;       // the message as shown
  bool cut = false;       // shortened: its whole text is the tooltip
  float left_end = 0.0f;  // where the shown message ends (window x)
  float right_x = 0.0f;   // where the right side starts (window x)
};

// The two sides in a bar `width` wide whose message starts at `left_x`; `left_reserved` is
// taken after the message (a button beside it).
StatusBarLayout status_bar_layout(const std::string& left, const std::string& right, float left_x,
                                  float width, float left_reserved = 0.0f);

void draw_status_bar(Editor& editor, UiState& ui);

}  // namespace primo::editor
