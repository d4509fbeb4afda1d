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

#include "primo/model/rigid_system.h"

namespace primo {

class AndersonAcceleration {
 public:
  // At most 64 cycles of history.
  explicit AndersonAcceleration(int history) : history_(std::min(history, 64)) {}

  // `input` was mapped to `image` by one step of the iteration; null: the input is the state
  // the last call left (knows_input()), whose embedding is kept, so that the caller need not
  // keep a copy of it and no rotation is embedded twice. Writes the accelerated next state to
  // `next` and returns true, or returns false (nothing written) while there is no history
  // yet. Bodies whose state never changed in the history (fixed handles) are written exactly
  // as in `image`. The proposal is taken to be kept unless refuse() is called.
  bool propose(const std::vector<BodyState>* input, const std::vector<BodyState>& image,
               std::vector<BodyState>& next);
  // As above, returning `image` itself while there is no history.
  std::vector<BodyState> propose(const std::vector<BodyState>& input,
                                 const std::vector<BodyState>& image);
  // The proposal was refused: the caller kept `image`. Forgets the history.
  void refuse();
  // Forget everything (the problem or the state changed outside the iteration).
  void reset();
  // Whether the state the last call left is known (then propose may be given a null input).
  bool knows_input() const { return kept_ != Kept::None; }

  int history() const { return history_; }
  int stored() const { return int(delta_residual_.size()); }

 private:
  enum class Kept { None, Image, Proposal };
  void forget_history();
  std::vector<float> spare_buffer();  // one of spare_, or an empty one

  int history_;
  Kept kept_ = Kept::None;
  // Large buffers live across calls (the history's in spare_ after a restart): allocating
  // them per call cost page faults on every cycle.
  std::vector<double> residual_;
  std::vector<double> proposal_embedding_;  // the last proposal, as it was normalized
  std::vector<float> last_residual_;
  std::vector<double> last_image_;
  std::vector<std::vector<float>> delta_residual_, delta_image_;  // oldest first
  std::vector<std::vector<float>> spare_;
  Eigen::MatrixXd gram_;  // inner products of the residual differences
};

}  // namespace primo
