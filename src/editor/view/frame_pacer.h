#pragma once
// How soon the editor's main loop draws the next frame while something animates. With a GPU a
// frame costs a few milliseconds and the loop keeps to 60 frames a second (what vsync does;
// Xvfb has none). Drawn in software (Mesa's llvmpipe: machines without a GPU, remote
// desktops, CI), a frame of a big mesh costs 20 ms of CPU or more, and at 60 frames a second
// drawing alone takes a core from the solver, so on two cores the mesh changed 5 to 6 times a
// second during a 240k-face drag while the handle moved at 50 frames a second. While the
// solver works, frames are therefore spaced so that drawing takes at most a share of the time
// (docs/editor.md, "Frame rate").

namespace primo::editor {

class FramePacer {
 public:
  static constexpr double kFrameSeconds = 1.0 / 60.0;
  // While the solver works, drawing takes at most 1/kSolverShare of the wall time.
  static constexpr double kSolverShare = 2.0;

  // The CPU time the last frame took to build and draw (without the wait before it).
  void frame_drawn(double seconds);
  // The least time from one frame's start to the next.
  double interval(bool solver_busy) const;
  double frame_seconds() const { return frame_seconds_; }  // smoothed

 private:
  double frame_seconds_ = 0.0;
};

}  // namespace primo::editor
