#include "screenshot.h"

#include <stb_image_write.h>  // implementation in libstb

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "gl.h"
#include "primo/error.h"

namespace primo::editor {

void save_screenshot(const std::string& path, int x, int y, int width, int height) {
  if (width <= 0 || height <= 0) throw Error(path + ": nothing to capture (empty viewport)");
  std::vector<unsigned char> pixels(size_t(width) * height * 3);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  std::vector<unsigned char> flipped(pixels.size());
  const size_t row = size_t(width) * 3;
  for (int r = 0; r < height; ++r)
    std::copy_n(pixels.begin() + size_t(height - 1 - r) * row, row, flipped.begin() + size_t(r) * row);

  namespace fs = std::filesystem;
  const fs::path target = fs::absolute(path);
  if (!fs::is_directory(target.parent_path()))
    throw Error(path + ": the folder " + target.parent_path().string() + " does not exist");
  const fs::path temp = target.parent_path() / ("." + target.filename().string() + ".tmp.png");
  if (!stbi_write_png(temp.c_str(), width, height, 3, flipped.data(), int(row))) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw Error(path + ": cannot write the PNG");
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) throw Error(path + ": cannot write the PNG (" + ec.message() + ")");
}

}  // namespace primo::editor
