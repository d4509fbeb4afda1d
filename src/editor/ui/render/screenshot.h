#pragma once
// Screenshots: a rectangle of the back buffer (before the swap) as a PNG.

#include <string>

namespace primo::editor {

// (x, y, width, height) in GL window coordinates (origin bottom-left). Writes through a
// temporary file renamed into place. Throws primo::Error naming the file.
void save_screenshot(const std::string& path, int x, int y, int width, int height);

}  // namespace primo::editor
