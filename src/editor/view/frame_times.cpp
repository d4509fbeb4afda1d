#include "frame_times.h"

#include <algorithm>
#include <cmath>

namespace primo::editor {

void FrameTimes::add(double ms) {
  if (!std::isfinite(ms) || ms < 0.0) return;
  ms_.push_back(ms);
  total_ms_ += ms;
}

double FrameTimes::per_second() const {
  return total_ms_ > 0.0 ? 1000.0 * double(ms_.size()) / total_ms_ : 0.0;
}

double FrameTimes::quantile(double fraction) const {
  if (ms_.empty()) return 0.0;
  const double f = std::clamp(fraction, 0.0, 1.0);
  const size_t rank = size_t(std::max(1.0, std::ceil(f * double(ms_.size())))) - 1;
  std::vector<double> sorted = ms_;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(rank), sorted.end());
  return sorted[rank];
}

}  // namespace primo::editor
