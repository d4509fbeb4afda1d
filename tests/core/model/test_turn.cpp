// Turns beyond half a turn (turn.h): a handle's rotation keeps its whole turns, and a solve
// follows them through their whole angle.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <complex>
#include <iostream>

#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/model/turn.h"
#include <nlohmann/json.hpp>

#include "support/test_support.h"

using namespace primo;

namespace {

constexpr double kDeg = M_PI / 180.0;

// A tube along y (radius 0.15, length 2, 16 x 24 quads) with its bottom band fixed and its top
// band turned `turn_deg` about the axis, on the product's default material (a thin layer of the
// format's default height lets a tube this slender untwist through itself past about 300
// degrees: docs/scenario-format.md). With `keep_turns` false the top gets its rotation only.
struct Tube {
  Mesh mesh = make_cylinder(0.15, 2.0, 16, 24, FaceShape::Quads);
  std::vector<Handle> handles;
  Tube() {
    const double band = 2.0 / 24;
    handles = {{"bottom", test::faces_where(mesh, [&](const Vec3& p) { return p.y() < band; }), Fix::All, {}},
               {"top", test::faces_where(mesh, [&](const Vec3& p) { return p.y() > 2 - band; }), Fix::All, {}}};
  }
  Deformer turned(double turn_deg, bool keep_turns) const {
    std::vector<Handle> h = handles;
    h[1].transform = make_rigid_transform(Vec3::Zero(), Vec3::UnitY(), turn_deg, Vec3(0, 2, 0));
    if (keep_turns) h[1].turn = turn_about(Vec3::UnitY(), turn_deg);
    return Deformer(mesh, PrismParameters::product_default(), h);
  }
};

// How far the ring of vertices at height y turned about the tube's axis, in degrees in
// (-180, 180]: the circular mean of each vertex's turn.
double turn_at_deg(const Mesh& mesh, const std::vector<Vec3>& points, double y) {
  std::complex<double> sum = 0.0;
  for (const auto v : mesh.vertices()) {
    const Vec3 rest = mesh.point(v);
    if (std::abs(rest.y() - y) > 1e-9) continue;
    const Vec3& now = points[size_t(v.idx())];
    sum += std::polar(1.0, std::atan2(rest.z(), rest.x()) - std::atan2(now.z(), now.x()));
  }
  return std::arg(sum) / kDeg;
}

SolveOptions converging() {
  SolveOptions o;
  o.max_iterations = 300;
  return o;
}

}  // namespace

TEST(Turn, AboutAnAxisKeepsItsAngleAsWritten) {
  EXPECT_TRUE(turn_about(Vec3(0, 0, 2), 720.0).isApprox(Vec3(0, 0, 4 * M_PI)));
  EXPECT_TRUE(turn_about(Vec3(1, 0, 0), -40.0).isApprox(Vec3(-40 * kDeg, 0, 0)));
  EXPECT_EQ(turn_about(Vec3::Zero(), 0.0), Vec3::Zero());
  EXPECT_THROW(turn_about(Vec3::Zero(), 90.0), Error);
  EXPECT_THROW(turn_about(Vec3(NAN, 0, 0), 90.0), Error);
  // A whole turn is the identity, and 270 degrees the same rotation as -90.
  EXPECT_TRUE(rotation_of_turn(turn_about(Vec3::UnitY(), 360.0)).isApprox(Mat3::Identity(), 1e-12));
  EXPECT_TRUE(rotation_of_turn(turn_about(Vec3::UnitY(), 270.0))
                  .isApprox(rotation_of_turn(turn_about(Vec3::UnitY(), -90.0)), 1e-12));
}

TEST(Turn, ARotationContinuesTheTurnsItFollows) {
  const Vec3 z = Vec3::UnitZ();
  // 190 degrees after 170 is 190, not -170; the identity after 350 is 360; from rest, the
  // principal turn.
  const Vec3 after_170 = nearest_turn(rotation_of_turn(190 * kDeg * z), 170 * kDeg * z);
  EXPECT_TRUE(after_170.isApprox(190 * kDeg * z)) << after_170.transpose();
  EXPECT_TRUE(nearest_turn(Mat3::Identity(), 350 * kDeg * z).isApprox(2 * M_PI * z));
  EXPECT_TRUE(nearest_turn(rotation_of_turn(190 * kDeg * z)).isApprox(-170 * kDeg * z));
  EXPECT_EQ(nearest_turn(Mat3::Identity()), Vec3::Zero());
  // Half a turn from no turn is half a turn (either way), not one and a half.
  EXPECT_NEAR(nearest_turn(rotation_of_turn(M_PI * z)).norm(), M_PI, 1e-12);
  EXPECT_NEAR(nearest_turn(rotation_of_turn(-M_PI * Vec3::UnitX())).norm(), M_PI, 1e-12);
  // Turned in steps of 30 degrees, two and a quarter turns are kept.
  Vec3 turn = Vec3::Zero();
  for (int k = 1; k <= 27; ++k) turn = nearest_turn(rotation_of_turn(k * 30 * kDeg * -z), turn);
  EXPECT_TRUE(turn.isApprox(-810 * kDeg * z)) << turn.transpose() / kDeg;
  EXPECT_TRUE(turn_makes(turn, rotation_of_turn(-90 * kDeg * z)));
  EXPECT_FALSE(turn_makes(turn, rotation_of_turn(90 * kDeg * z)));
}

TEST(Turn, ATubeTurnedBeyondHalfATurnIsTwistedThatFar) {
  const Tube tube;
  // Kept, a quarter of the way up the tube turns a quarter of the turn, halfway up half of it;
  // as a rotation only, 360 degrees is the rest and 450 is 90.
  for (const double turn : {360.0, -360.0, 450.0}) {
    Deformer kept = tube.turned(turn, true);
    const SolveReport report = kept.solve(converging());
    const std::vector<Vec3> points = kept.vertex_positions();
    const double quarter = turn_at_deg(tube.mesh, points, 0.5);
    const double middle = turn_at_deg(tube.mesh, points, 1.0);
    Deformer rotation_only = tube.turned(turn, false);
    const SolveReport only = rotation_only.solve(converging());
    const double quarter_of_rotation = turn_at_deg(tube.mesh, rotation_only.vertex_positions(), 0.5);
    std::cout << "[ metric   ] tube turned " << turn << " degrees: turned " << quarter
              << " a quarter up, " << middle << " halfway (" << report.path_steps
              << " sub-steps, E = " << report.energy << "); as a rotation only " << quarter_of_rotation
              << " a quarter up (E = " << only.energy << ")\n";
    EXPECT_TRUE(report.converged);
    // The fixed bands at the ends hold the twist back near them: the quarter turns less.
    EXPECT_NEAR(quarter, turn / 4, 0.15 * std::abs(turn / 4));
    EXPECT_NEAR(std::abs(std::remainder(middle - turn / 2, 360.0)), 0.0, 3.0);
    EXPECT_NEAR(quarter_of_rotation, std::remainder(turn, 360.0) / 4, 3.0);
  }
}

TEST(Turn, SettingARotationContinuesTheHandlesTurns) {
  // A handle turned in steps of 30 degrees by rotations alone (as a drag sets them) has turned
  // 390 degrees, and a solve from rest follows all of it; the same turn set at once is a turn
  // of 30.
  const Tube tube;
  Deformer stepped = tube.turned(0.0, true);
  for (int k = 1; k <= 13; ++k)
    stepped.set_handle_transform(1, make_rigid_transform(Vec3::Zero(), Vec3::UnitY(), 30.0 * k,
                                                         Vec3(0, 2, 0)));
  EXPECT_TRUE(stepped.handles()[1].turn->isApprox(turn_about(Vec3::UnitY(), 390.0)));
  stepped.reset();
  stepped.solve(converging());
  EXPECT_NEAR(turn_at_deg(tube.mesh, stepped.vertex_positions(), 0.5), 97.5, 15.0);
  Deformer direct = tube.turned(0.0, true);
  direct.set_handle_transform(1, make_rigid_transform(Vec3::Zero(), Vec3::UnitY(), 390.0, Vec3(0, 2, 0)));
  EXPECT_TRUE(direct.handles()[1].turn->isApprox(turn_about(Vec3::UnitY(), 30.0)));
  // A turn that does not make the rotation is refused.
  EXPECT_THROW(direct.set_handle_transform(1, RigidTransform::identity(), turn_about(Vec3::UnitY(), 90.0)),
               Error);
}

TEST(Turn, AWholeTurnInAScenarioIsTwistedOnce) {
  // `primo deform` keeps angle_deg as written: 360 and -360 twist the tube once each way, 0
  // leaves it at rest.
  const std::string dir = test::temp_dir();
  const Tube tube;
  save_mesh(tube.mesh, dir + "/tube.obj");
  for (const double turn : {360.0, -360.0, 0.0}) {
    const std::string path = dir + "/turned.json";
    test::write_text(path, R"({"format": "primo-scenario/1", "mesh": "tube.obj",
      "prisms": {"half_thickness": 0.08},
      "handles": [
        {"name": "bottom", "select": {"box": {"min": [-1, -1, -1], "max": [1, 0.084, 1]}}, "fix": "all"},
        {"name": "top", "select": {"box": {"min": [-1, 1.916, -1], "max": [1, 3, 1]}}, "fix": "all",
         "transform": {"axis": [0, 1, 0], "angle_deg": )" + std::to_string(turn) + R"(}}]})");
    const test::CommandResult r =
        test::run_primo("deform " + path + " -o " + dir + "/out.obj --stats " + dir + "/stats.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const double energy = test::read_json(dir + "/stats.json").at("energy").get<double>();
    const Mesh out = load_mesh(dir + "/out.obj");
    std::vector<Vec3> points;
    for (const auto v : out.vertices()) points.push_back(out.point(v));
    const double quarter = turn_at_deg(tube.mesh, points, 0.5);
    std::cout << "[ metric   ] scenario turning the tube's end " << turn << " degrees: turned "
              << quarter << " a quarter up, E = " << energy << "\n";
    EXPECT_NEAR(quarter, turn / 4, 0.15 * std::abs(turn / 4) + 1e-6);
    if (turn == 0.0) {
      EXPECT_LT(energy, 1e-20);
    }
  }
}
