#pragma once
// The times between a gesture's frames, kept so that the editor can say how smooth it was as
// a user sees it: the median and the 90th percentile tell a steady pace from one broken by
// a few long frames, which a mean hides.

#include <vector>

namespace primo::editor {

class FrameTimes {
 public:
  void add(double ms);
  int count() const { return int(ms_.size()); }
  double total_ms() const { return total_ms_; }
  // Frames a second over the gesture (0 when none).
  double per_second() const;
  // The smallest time that `fraction` (in [0, 1]) of the frames took at most (nearest rank;
  // 0 when none): 0.5 the median, 0.9 the 90th percentile.
  double quantile(double fraction) const;

 private:
  std::vector<double> ms_;
  double total_ms_ = 0.0;
};

}  // namespace primo::editor
