#pragma once
// Anderson acceleration [Walker and Ni 2011; Peng et al. 2018, "Anderson acceleration for
// geometry optimization and physics simulation"] of a fixed-point iteration on rigid body
// states: from the last few iterates x_i and their images G(x_i), it proposes the combination
// of images whose residuals G(x) - x cancel best. Rigid motions are combined in a 7-number
// embedding: the rotation's unit quaternion, its sign on the side of the body's last one, and
// the position; the combined quaternion is normalized back to a rotation. (Rotation matrices
// projected back by Horn's method did the same work at 12 numbers a body: the quaternions
// made a proposal about 30% cheaper at 240k faces, with the same cycle counts within one.)
// The caller keeps the proposal only if it lowers the energy (and then
// starts afresh on refusal), so the accelerated iteration stays a descent method.

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "primo/rigid_system.h"

namespace primo {

class AndersonAcceleration {
 public:
  // At most 64 cycles of history.
  explicit AndersonAcceleration(int history) : history_(std::min(history, 64)) {}

  // `input` was mapped to `image` by one step of the iteration. Returns the accelerated next
  // state, or `image` itself while there is no history yet. Bodies whose state never changed
  // in the history (fixed handles) are returned exactly as in `image`.
  std::vector<BodyState> propose(const std::vector<BodyState>& input,
                                 const std::vector<BodyState>& image);
  // Forget the history (the proposal was refused, or the problem changed).
  void reset();

  int history() const { return history_; }
  int stored() const { return int(delta_residual_.size()); }

 private:
  int history_;
  std::vector<float> last_residual_;
  std::vector<double> last_image_;
  std::vector<std::vector<float>> delta_residual_, delta_image_;  // oldest first
  Eigen::MatrixXd gram_;  // inner products of the residual differences
};

}  // namespace primo
