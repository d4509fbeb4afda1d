#pragma once
// What the window shows, as a fingerprint of the picture last drawn and swapped in: the 3D
// view's scene, the panels' draw lists and where they go. While the solver works, a gesture
// is under way or a script plays, the main loop runs a frame every few milliseconds, but most
// of them would draw the same picture again: with a software renderer (llvmpipe) each costs
// 10-40 ms of the CPU the solver needs. A frame whose fingerprint equals the one shown is
// therefore not drawn (docs/editor.md, "Frame rate").

#include <cstdint>
#include <optional>

namespace primo::editor {

struct PictureFingerprint {
  std::uint64_t scene = 0;   // MeshRenderer::scene_fingerprint
  std::uint64_t panels = 0;  // draw_data_fingerprint of the panels
  int view_x = 0, view_y = 0, view_width = 0, view_height = 0;  // the 3D view, in pixels
  int window_width = 0, window_height = 0;                      // the framebuffer
  bool operator==(const PictureFingerprint& o) const {
    return scene == o.scene && panels == o.panels && view_x == o.view_x && view_y == o.view_y &&
           view_width == o.view_width && view_height == o.view_height &&
           window_width == o.window_width && window_height == o.window_height;
  }
};

class ShownPicture {
 public:
  // Whether a frame that would draw `next` must draw it: the window shows something else, or
  // nothing known (the first frame, or its contents were lost).
  bool needs_drawing(const PictureFingerprint& next) const { return !shown_ || !(*shown_ == next); }
  void drawn(const PictureFingerprint& shown) { shown_ = shown; }
  // The window's contents were lost or overdrawn (exposed, resized, a screenshot's extra
  // pass): the next frame draws whatever it shows.
  void forget() { shown_.reset(); }

 private:
  std::optional<PictureFingerprint> shown_;
};

}  // namespace primo::editor
