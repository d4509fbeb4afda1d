#include "primo/solve/drag_predictor.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "primo/util/parallel.h"

namespace primo {
namespace {

bool is_drag_frame(const std::vector<double>& target_move) {
  double now = 0.0;
  for (double d : target_move) now += d * d;
  return now > 0.0 && std::isfinite(now);
}

}  // namespace

double DragPredictor::fraction(const std::vector<double>& target_move, double multiplier) const {
  if (!has_previous_ || previous_move_.size() != target_move.size()) return 0.0;
  double dot = 0.0, last = 0.0;
  for (size_t i = 0; i < target_move.size(); ++i) {
    dot += target_move[i] * previous_move_[i];
    last += previous_move_[i] * previous_move_[i];
  }
  double ratio = dot / last;
  if (!(last > 0.0) || !std::isfinite(ratio)) return 0.0;
  // Equal steps (a drag at a steady speed) give 1 up to rounding: made exactly 1, the
  // prediction takes its cheaper path (DragPredictor::predict).
  ratio = ratio > 1.0 - 1e-9 ? 1.0 : std::max(ratio, 0.0);
  return multiplier * ratio;
}

void DragPredictor::predict(const RigidSystem& system, const std::vector<BodyState>& state,
                            double fraction, std::vector<BodyState>& predicted) {
  predicted.resize(state.size());
  if (previous_state_.size() != state.size()) {
    predicted = state;
    return;
  }
  if (kinds_of_ != &system || int(kinds_.size()) != system.n_bodies()) {
    kinds_.resize(size_t(system.n_bodies()));
    for (int b = 0; b < system.n_bodies(); ++b) kinds_[size_t(b)] = system.bodies[size_t(b)].kind;
    kinds_of_ = &system;
  }
  parallel_chunks(state.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const BodyState& now = state[b];
      const BodyState& before = previous_state_[b];
      BodyState& p = predicted[b];
      p = now;
      const BodyKind kind = kinds_[b];
      if (kind == BodyKind::Fixed) continue;
      if (kind != BodyKind::PinnedPosition)
        p.position = now.position + fraction * (now.position - before.position);
      if (kind == BodyKind::FixedRotation) continue;
      const Mat3 turn = now.rotation * before.rotation.transpose();  // the last frame's
      if (fraction == 1.0) {  // a steady drag: the turn once more
        p.rotation = turn * now.rotation;
        continue;
      }
      // The turn q taken `fraction` further: the normalized blend of 1 and q (on the short
      // side) stays within a few thousandths of a degree of the slerp for the turns of one
      // frame, at a third of its cost.
      Eigen::Quaterniond q(turn);
      if (q.w() < 0.0) q.coeffs() = -q.coeffs();
      Eigen::Quaterniond step(1.0 + fraction * (q.w() - 1.0), fraction * q.x(), fraction * q.y(),
                              fraction * q.z());
      step.normalize();
      p.rotation = step.toRotationMatrix() * now.rotation;
    }
  });
}

void DragPredictor::remember(const std::vector<double>& target_move,
                             const std::vector<BodyState>& state) {
  has_previous_ = is_drag_frame(target_move);
  if (!has_previous_) return;
  previous_move_ = target_move;
  previous_state_.resize(state.size());  // reuses the last frame's storage
  parallel_chunks(state.size(), kParallelGrain, [&](size_t begin, size_t end) {
    std::copy(state.begin() + std::ptrdiff_t(begin), state.begin() + std::ptrdiff_t(end),
              previous_state_.begin() + std::ptrdiff_t(begin));
  });
}

void DragPredictor::take(const std::vector<double>& target_move, std::vector<BodyState>& state) {
  has_previous_ = is_drag_frame(target_move);
  if (!has_previous_) return;
  previous_move_ = target_move;
  previous_state_.swap(state);
}

}  // namespace primo
