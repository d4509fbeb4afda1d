#pragma once
// The couplings between two bodies summed into one coupling whose energy is theirs, up to a
// constant, under every pair of rigid motions of the two bodies. A coupling's energy
//   w sum_m c_m |R0 a_m + [p0] - R1 b_m - [p1]|^2
// (mode weights c_m, the translations on the mean mode only) expands to
//   T - 2 trace(R0 C R1^T) + 2 (p0 - p1).(R0 S0 - R1 S1) + W |p0 - p1|^2
// with W = w, S0 = w a_mean, S1 = w b_mean, C = w sum_m c_m a_m b_m^T and a constant T. Sums
// of such energies have the same form, so any number of couplings between two bodies are one
// set of moments (W, S0, S1, C), and one coupling reproduces them exactly: means S0 / W and
// S1 / W, and vector modes that factor the rest of C. Its gradient and exact Hessian are
// therefore those of the couplings it replaces; its Gauss-Newton Hessian nearly so where the
// joints are nearly closed (the factors are then nearly equal on both sides).
//
// The hierarchy's coarsest level holds one such coupling per pair of neighbouring clusters
// instead of every finer coupling between them (hierarchical_solver.cpp): its Newton steps
// assemble and evaluate them several times a cycle.

#include "primo/model/rigid_system.h"

namespace primo {

// What CouplingMoments::add reads of a coupling, seen from one of its sides ("own"): the
// bodies, the weight, both sides' means and the cross moments of the own side. The rest of
// the coupling, its vector modes, enters the moments only through their lengths, which no
// rigid motion changes (vector_mode_trace).
struct OrientedCoupling {
  int own = 0, other = 0;
  double weight = 0.0;
  Vec3 own_mean = Vec3::Zero(), other_mean = Vec3::Zero();
  Mat3 cross = Mat3::Zero();  // Coupling::cross_of(own side)

  // `turned`: c's side 1 is the own side.
  static OrientedCoupling of(const RigidSystem::Coupling& c, bool turned);
};

// w sum_k c_k (|a_k|^2 + |b_k|^2) over a coupling's vector modes: the part of the moments'
// constant that is the same under every motion of its sides.
double vector_mode_trace(const RigidSystem::Coupling& c);

struct CouplingMoments {
  double weight = 0.0;                            // W
  double trace = 0.0;                             // T: the constant part of the energy
  Vec3 sum0 = Vec3::Zero(), sum1 = Vec3::Zero();  // S0, S1
  Mat3 cross = Mat3::Zero();                      // C

  // Adds a coupling of weight `w` between modes `side0` and `side1`, expressed as the two
  // bodies see them.
  void add(const PatchModes& side0, const PatchModes& side1, double w);
  // Adds coupling `c` with its sides moved into the bodies' view: the own side turned by
  // rotation0 and its mean then shifted by offset0, the other side by rotation1 and offset1.
  // The same as add() of the moved modes, but from c's cross moments instead of every mode;
  // the vector modes' part of the constant is left out (add vector_mode_trace(c) to `trace`
  // for it: it does not change from one motion to the next).
  void add_moved(const OrientedCoupling& c, const Mat3& rotation0, const Vec3& offset0,
                 const Mat3& rotation1, const Vec3& offset1);
  // Writes one coupling with these moments into `out` (its weight, modes and cross moments;
  // its bodies are left alone) and returns the constant by which its energy falls short of
  // the sum of the couplings added, for every motion of the bodies.
  double write(RigidSystem::Coupling& out) const;
};

}  // namespace primo
