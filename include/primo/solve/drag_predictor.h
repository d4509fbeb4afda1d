#pragma once
// The predictor of a drag. While a handle is dragged, every frame moves the targets a little
// and the solver runs one iteration (a hierarchical cycle) from the last frame's state. The
// minimum moves with the targets, and an iteration only removes a fraction of the distance to
// it, so the state trails the hand: a constant lag of about v·ρ/(1−ρ) for targets moving by v
// per frame and an iteration that keeps a fraction ρ of the error. Starting each frame from
// the last state moved on by its last change (a secant predictor, as continuation methods use)
// cancels that lag for a steady drag: the error then obeys e' = ρ(e + (m−1)v), which settles
// at zero for m = 1. It is also a heavy-ball step: the error left by a change of speed decays
// by about √(ρm) per frame instead of ρ.
//
// The prediction is scaled by how much of the last target move the new one repeats (the
// projection of the new move on the last, clamped to [0, 1]): none after a settling solve, a
// reversal or a jump, less when the hand slows down. The caller keeps it only where it
// lowers the energy.

#include <vector>

#include "primo/model/rigid_system.h"

namespace primo {

class DragPredictor {
 public:
  // The state was set from outside (reset, a pose loaded): the next solve has no last frame.
  // (A deformer moved into another's place keeps its system's address: forgetting, as it
  // does then, also drops the kinds copied from the system that was there.)
  void forget() {
    has_previous_ = false;
    previous_move_.clear();
    kinds_of_ = nullptr;
  }

  // At the start of a solve: the fraction of the last frame's change to add to the state
  // (0: none). `target_move`: how the targets moved since the state was solved, as a vector
  // whose entries weigh alike (Deformer::target_move).
  double fraction(const std::vector<double>& target_move, double multiplier) const;

  // `state` moved on by `fraction` of its change since the state remembered last, into
  // `predicted`: positions on the line, rotations on the great circle through both. Bodies
  // whose position (rotation) a handle prescribes keep it.
  void predict(const RigidSystem& system, const std::vector<BodyState>& state, double fraction,
               std::vector<BodyState>& predicted);

  // Remembers the state a solve starts from (before any prediction) and the target move
  // before it, for the next frame. A solve without a target move (settling) is no frame of a
  // drag: its change is convergence, not to be repeated, and nothing is remembered.
  // `remember` copies the state; `take` swaps it in, leaving `state` with storage to reuse.
  void remember(const std::vector<double>& target_move, const std::vector<BodyState>& state);
  void take(const std::vector<double>& target_move, std::vector<BodyState>& state);

 private:
  bool has_previous_ = false;
  std::vector<double> previous_move_;
  std::vector<BodyState> previous_state_;  // the state the last frame's solve started from
  // The bodies' kinds, copied from the system predicted for last (kinds never change in a
  // system): reading them from each 232-byte Body cost a cache line a body, about a third of
  // a steady drag's prediction (DragPrediction/4800/2 median 3.8-4.3 ms against 2.6-2.8).
  const RigidSystem* kinds_of_ = nullptr;
  std::vector<BodyKind> kinds_;
};

}  // namespace primo
