#pragma once
// Parts and colours for Gauss-Seidel sweeps on every core with the same result on any number
// of threads: bodies are cut into parts by recursive bisection of their positions along the
// longest axis (how many parts depends on the number of bodies alone), and parts are coloured
// so that no two parts of a colour contain coupled bodies. A sweep then matches the parts of
// one colour in parallel, colour after colour, each part in index order: a Gauss-Seidel
// ordering that does not depend on the threads. Local matching (local_solver.h) and the
// smoother of the Newton-Krylov preconditioner (rigid_multigrid.h) sweep this way.

#include <utility>
#include <vector>

#include "primo/util/types.h"

namespace primo {

struct BodyPartition {
  std::vector<std::vector<int>> parts;    // each part's bodies, in index order
  std::vector<std::vector<int>> colours;  // each colour's parts, in index order
};

// Bodies a part should have: a part is one task, and a task needs about a millisecond of
// matching to pay for itself.
inline constexpr size_t kBodiesPerPart = 2000;
inline constexpr int kMaxPartLevels = 7;  // at most 2^7 = 128 parts

// `bodies` (those that move) split about `bodies_per_part` a part, at most 2^max_levels parts
// (0: one part); `edges` are the coupled pairs of bodies (any order, repeats allowed; a pair
// with a negative end, a coupling to a body that does not move, is ignored), `position` is
// indexed by body.
BodyPartition partition_bodies(std::vector<int> bodies, const std::vector<Vec3>& position,
                               const std::vector<std::pair<int, int>>& edges,
                               size_t bodies_per_part = kBodiesPerPart,
                               int max_levels = kMaxPartLevels);

}  // namespace primo
