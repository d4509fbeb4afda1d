#pragma once
// Horn's closed-form absolute orientation with unit quaternions [Hor87], the kernel of local
// shape matching (paper Sect. 4.1 and Appendix A) and of the projection onto rigid motions.

#include "primo/util/types.h"

namespace primo {

// Given the weighted cross-covariance S = sum_k w_k s_k t_k^T of centred source points s_k
// and target points t_k (difference vectors enter the same way), returns the rotation R that
// maximizes sum_k w_k t_k . (R s_k) = trace(R S), i.e. minimizes sum_k w_k |R s_k - t_k|^2.
// For a degenerate S (rank below 2) the maximizer is not unique; the rotation closest to
// `prior` among the maximizers is not searched for, `prior` is returned when S is zero.
// Beyond that `prior` is only a hint that makes the call faster the closer it is to the
// answer (local shape matching passes the body's current rotation): where the maximizer is
// unique, any matrix gives it up to rounding.
Mat3 horn_rotation(const Mat3& S, const Mat3& prior = Mat3::Identity());

}  // namespace primo
