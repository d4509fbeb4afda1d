// The drag predictor: when it predicts, what it predicts, and what it does to a drag.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>

#include "primo/solve/deformer.h"
#include "primo/solve/drag_predictor.h"
#include "primo/mesh/geometry.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::faces_where;

namespace {

std::vector<BodyState> one_body(const Mat3& rotation, const Vec3& position) {
  return {BodyState{rotation, position}};
}

// Body b of four turns about `axis` by 3 degrees and moves by `step` per frame.
std::vector<BodyState> frame(int k) {
  const Vec3 axis = Vec3(1, 2, 3).normalized();
  const Mat3 r = Eigen::AngleAxisd(k * 3.0 * M_PI / 180.0, axis).toRotationMatrix();
  const Vec3 p = Vec3(0.5, -1, 2) + k * Vec3(0.01, 0.02, -0.03);
  return std::vector<BodyState>(4, BodyState{r, p});
}

// A solve's start as the Deformer makes it: the fraction to predict, then the state remembered.
double advance(DragPredictor& p, const std::vector<double>& move, const std::vector<BodyState>& s,
               double multiplier) {
  const double f = p.fraction(move, multiplier);
  p.remember(move, s);
  return f;
}

}  // namespace

TEST(DragPredictor, PredictsOnlyWhenTheTargetsMoveAsInTheLastFrame) {
  DragPredictor p;
  const std::vector<BodyState> s = one_body(Mat3::Identity(), Vec3::Zero());
  EXPECT_EQ(advance(p, {1.0, 0.0}, s, 1.0), 0.0);   // no last frame yet
  EXPECT_EQ(advance(p, {1.0, 0.0}, s, 1.0), 1.0);   // the same move again
  EXPECT_EQ(advance(p, {0.5, 0.0}, s, 0.8), 0.4);   // half of it, scaled by the multiplier
  EXPECT_EQ(advance(p, {1.0, 0.0}, s, 1.0), 1.0);   // more than the last: at most all of it
  EXPECT_EQ(advance(p, {0.0, 1.0}, s, 1.0), 0.0);   // at right angles
  EXPECT_EQ(advance(p, {0.0, -1.0}, s, 1.0), 0.0);  // back
  EXPECT_EQ(advance(p, {0.0, 0.0}, s, 1.0), 0.0);   // a settling solve ...
  EXPECT_EQ(advance(p, {0.0, -1.0}, s, 1.0), 0.0);  // ... ends the drag
  EXPECT_EQ(advance(p, {0.0, -1.0}, s, 1.0), 1.0);
  p.forget();
  EXPECT_EQ(advance(p, {0.0, -1.0}, s, 1.0), 0.0);
  EXPECT_EQ(advance(p, {0.0, -1.0, 0.0}, s, 1.0), 0.0);  // another handle set
}

TEST(DragPredictor, CarriesATurnAndAShiftOnAndKeepsWhatHandlesPrescribe) {
  RigidSystem system;
  system.bodies.resize(4);
  system.bodies[1].kind = BodyKind::Fixed;
  system.bodies[2].kind = BodyKind::PinnedPosition;
  system.bodies[3].kind = BodyKind::FixedRotation;
  DragPredictor p;
  p.remember({1.0}, frame(4));  // the start of the last frame's solve
  ASSERT_EQ(p.fraction({1.0}, 1.0), 1.0);
  std::vector<BodyState> predicted;
  const std::vector<BodyState> now = frame(5);
  for (double fraction : {1.0, 0.5}) {
    p.predict(system, now, fraction, predicted);
    // Where a fraction f of the last frame's change leads: frame 5 + f.
    const Vec3 axis = Vec3(1, 2, 3).normalized();
    const Mat3 r = Eigen::AngleAxisd((5 + fraction) * 3.0 * M_PI / 180.0, axis).toRotationMatrix();
    const Vec3 x = Vec3(0.5, -1, 2) + (5 + fraction) * Vec3(0.01, 0.02, -0.03);
    EXPECT_LT((predicted[0].rotation - r).norm(), 1e-6) << fraction;
    EXPECT_LT((predicted[0].position - x).norm(), 1e-12) << fraction;
    EXPECT_EQ(predicted[1].rotation, now[1].rotation);
    EXPECT_EQ(predicted[1].position, now[1].position);
    EXPECT_LT((predicted[2].rotation - r).norm(), 1e-6);
    EXPECT_EQ(predicted[2].position, now[2].position);
    EXPECT_EQ(predicted[3].rotation, now[3].rotation);
    EXPECT_LT((predicted[3].position - x).norm(), 1e-12);
    // Still a rotation.
    EXPECT_LT((predicted[0].rotation.transpose() * predicted[0].rotation - Mat3::Identity()).norm(),
              1e-12);
  }
}

TEST(DragPredictor, AfterForgettingReadsTheKindsOfTheSystemNowInPlace) {
  // The predictor copies the bodies' kinds from the system it predicts for; a deformer moved
  // into another's place has a new system at the old address, and forgets its drag then.
  RigidSystem system;
  system.bodies.resize(4);
  DragPredictor p;
  std::vector<BodyState> predicted;
  p.remember({1.0}, frame(4));
  p.predict(system, frame(5), 1.0, predicted);
  EXPECT_NE(predicted[1].position, frame(5)[1].position);  // a free body moves on
  // Another system, in the same place.
  system.bodies[1].kind = BodyKind::Fixed;
  p.forget();
  p.remember({1.0}, frame(4));
  p.predict(system, frame(5), 1.0, predicted);
  EXPECT_EQ(predicted[1].position, frame(5)[1].position);
  EXPECT_EQ(predicted[1].rotation, frame(5)[1].rotation);
}

namespace {

struct DragResult {
  double last_frame_energy = 0.0;
  std::vector<Vec3> last_frame;
  std::vector<double> initial_energies;      // where each frame's solve started
  std::vector<double> unpredicted_energies;  // the last frame's state at the frame's targets
  Deformer deformer;
};

// Spot's head dragged 0.35 along a curve and turned 30 degrees in 30 frames of one
// hierarchical cycle each, its feet fixed.
DragResult drag_spot(double prediction) {
  const Mesh mesh = load_mesh(test::source_path("assets/meshes/spot_quadrangulated.obj"));
  Handle feet{"feet", faces_where(mesh, [](const Vec3& p) { return p.y() < -0.6; }), Fix::All, {}};
  Handle head{
      "head",
      faces_where(mesh, [](const Vec3& p) { return (p - Vec3(0, 0.2, 0.95)).norm() < 0.2; }),
      Fix::All,
      {}};
  DragResult r{0.0, {}, {}, {}, Deformer(mesh, PrismParameters{}, {feet, head})};
  SolveOptions frame;
  frame.method = SolveMethod::Hierarchical;
  frame.max_iterations = 1;
  frame.tolerance = 0.0;
  frame.hierarchical.hierarchy.coarsest_max_bodies = 150;
  frame.drag_prediction = prediction;
  constexpr int kFrames = 30;
  for (int k = 1; k <= kFrames; ++k) {
    const double t = double(k) / kFrames;
    r.deformer.set_handle_transform(
        1, make_rigid_transform(Vec3(0.25 * t, 0.2 * t * t, -0.1 * t), Vec3::UnitX(), 30.0 * t,
                                Vec3(0, 0.2, 0.95)));
    r.unpredicted_energies.push_back(r.deformer.energy());
    const SolveReport report = r.deformer.solve(frame);
    r.initial_energies.push_back(report.initial_energy);
  }
  r.last_frame_energy = r.deformer.energy();
  r.last_frame = r.deformer.vertex_positions();
  return r;
}

}  // namespace

TEST(DragPredictor, ADragFollowsTheHandCloserAndReachesTheSameMinimum) {
  DragResult plain = drag_spot(0.0), predicted = drag_spot(1.0);
  SolveOptions converge;
  converge.method = SolveMethod::Hierarchical;
  converge.max_iterations = 1000;
  converge.tolerance = 1e-10;
  converge.hierarchical.hierarchy.coarsest_max_bodies = 150;
  const SolveReport a = plain.deformer.solve(converge);
  const SolveReport b = predicted.deformer.solve(converge);
  ASSERT_TRUE(a.converged && b.converged);
  const double diagonal =
      bounding_box_diagonal(load_mesh(test::source_path("assets/meshes/spot_quadrangulated.obj")));
  EXPECT_LT(std::abs(a.energy / b.energy - 1.0), 1e-6);
  EXPECT_LT(largest_point_distance(plain.deformer.vertex_positions(),
                                   predicted.deformer.vertex_positions()),
            1e-4 * diagonal);

  const double plain_gap = plain.last_frame_energy / a.energy - 1.0;
  const double predicted_gap = predicted.last_frame_energy / a.energy - 1.0;
  const std::vector<Vec3> minimum = predicted.deformer.vertex_positions();
  const double plain_lag = largest_point_distance(plain.last_frame, minimum) / diagonal;
  const double predicted_lag = largest_point_distance(predicted.last_frame, minimum) / diagonal;
  std::cout << "[ metric   ] Spot drag, 30 frames: last frame above the minimum " << 100 * plain_gap
            << "% without prediction, " << 100 * predicted_gap << "% with; largest vertex lag "
            << 100 * plain_lag << "% and " << 100 * predicted_lag << "% of the diagonal\n";
  EXPECT_LT(predicted_gap, 0.5 * plain_gap);
  EXPECT_LT(predicted_lag, 0.5 * plain_lag);

  // Predictions are kept only where they lower the energy a frame starts from: never above
  // the frame's start without one (the last state at the new targets). Here every frame
  // but the first (no last frame to repeat yet) starts from one.
  int predicted_frames = 0;
  for (size_t k = 0; k < predicted.initial_energies.size(); ++k) {
    EXPECT_LE(predicted.initial_energies[k], predicted.unpredicted_energies[k]) << k;
    predicted_frames += predicted.initial_energies[k] < predicted.unpredicted_energies[k];
  }
  EXPECT_EQ(predicted_frames, 29);
  for (size_t k = 0; k < plain.initial_energies.size(); ++k)
    EXPECT_EQ(plain.initial_energies[k], plain.unpredicted_energies[k]) << k;

  // The same drag again gives the same bits.
  const DragResult again = drag_spot(1.0);
  EXPECT_EQ(largest_point_distance(again.last_frame, predicted.last_frame), 0.0);
}
