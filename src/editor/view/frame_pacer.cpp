#include "frame_pacer.h"

#include <algorithm>
#include <cmath>

namespace primo::editor {

void FramePacer::frame_drawn(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return;
  // Smoothed over about five frames: one slow frame (a mesh upload, a menu opening) does not
  // slow the next ones down, a lasting change in cost shows within a few frames.
  frame_seconds_ = frame_seconds_ == 0.0 ? seconds : 0.8 * frame_seconds_ + 0.2 * seconds;
}

double FramePacer::interval(bool solver_busy) const {
  if (!solver_busy) return kFrameSeconds;
  // At most 4 frames a second, however slow drawing is: the handle must still follow.
  return std::clamp(kSolverShare * frame_seconds_, kFrameSeconds, 0.25);
}

}  // namespace primo::editor
