#pragma once
// Local shape matching (paper Sect. 4.1, Appendix A): one body at a time is moved to the
// rigid motion that minimizes its joint and spring energy with every other body held fixed,
// in closed form by Horn's method. Each match can only lower the energy.

#include <vector>

#include "primo/rigid_system.h"

namespace primo {

// The optimal state of `body` given the others. Free bodies get rotation and translation;
// PinnedPosition bodies rotate about their prescribed rest_center; FixedRotation bodies only
// translate; Fixed bodies (and bodies with nothing acting on them) keep their state.
BodyState local_match(const RigidSystem& system, const std::vector<BodyState>& state, int body);

// One Gauss-Seidel sweep over all bodies in index order.
void local_sweep(const RigidSystem& system, std::vector<BodyState>& state);

// Bodies grouped so that no two coupled bodies share a group (greedy graph colouring). Bodies
// of one colour can be matched at the same time: none reads another's state.
using BodyColoring = std::vector<std::vector<int>>;
BodyColoring color_bodies(const RigidSystem& system);

// One Gauss-Seidel sweep colour by colour, the bodies of a colour in parallel (OpenMP). Its
// fixed points are those of the sequential sweep.
void colored_sweep(const RigidSystem& system, const BodyColoring& coloring,
                   std::vector<BodyState>& state);

}  // namespace primo
