#include "screenshot.h"

#include <stb_image_write.h>  // implementation in libstb

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "gl.h"
#include "primo/util/error.h"
#include "primo/io/output_files.h"

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

  // Encoded in memory and written through the core's staged writer: a special file at the
  // path (a pipe, a device) is refused instead of replaced by a regular file, and the
  // temporary file is created exclusively, so a link planted under its name is refused, not
  // followed (a fixed temporary name beside the target, written through, followed one).
  check_output_path(path);
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, flipped.data(), int(row)))
    throw Error(path + ": cannot encode the PNG");
  StagedOutputs out;
  out.stage(path, png);
  out.commit();
}

}  // namespace primo::editor
