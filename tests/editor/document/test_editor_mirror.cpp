// Symmetry: twin faces by position and by topology, and the editor selecting, painting and
// posing on both sides of the mirror plane, on exactly symmetric meshes and on a scan.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "support/editor_harness.h"
#include "view/face_colors.h"
#include "document/mirror.h"
#include "primo/solve/deformer.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "document/scenario_bridge.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;
using primo::editor::harness::Harness;

namespace {

void expect_involution(const MirrorMap& map) {
  for (size_t f = 0; f < map.face_twin.size(); ++f) {
    const int g = map.face_twin[f];
    if (g >= 0) {
      ASSERT_EQ(map.face_twin[size_t(g)], int(f)) << "twins point at each other";
    }
  }
}

// The rest centroid of each face, reflected, lands on its twin's.
double worst_reflection_error(const MeshTopology& t, const MirrorMap& map) {
  double worst = 0.0;
  for (int f = 0; f < t.n_faces; ++f)
    if (map.twin(f) >= 0)
      worst = std::max(worst, (reflect(map, t.rest_geometry.centroid[size_t(f)]) -
                               t.rest_geometry.centroid[size_t(map.twin(f))])
                                  .norm());
  return worst;
}

// A 2 x 0.2 x 0.2 bar of quads along x, symmetric across x = 0.
Mesh bar_along_x() {
  Mesh m = make_bar(0.2, 2.0, 2, 20);
  for (auto v : m.vertices()) {
    const Vec3 p = m.point(v);
    m.set_point(v, Vec3(p.y() - 1.0, -p.x(), p.z()));
  }
  return m;
}

}  // namespace

TEST(MirrorMatch, ASymmetricMeshOnThePlaneMatchesEveryFaceByPosition) {
  const MeshTopology t = build_topology(make_icosphere(3));
  for (int axis = 0; axis < 3; ++axis) {
    const MirrorMap map = match_mirror_by_position(t, axis);
    EXPECT_EQ(map.matched, t.n_faces) << axis_name(axis);
    expect_involution(map);
    EXPECT_LT(worst_reflection_error(t, map), 1e-9);
  }
  // A quad bar, and topology agrees with position on it.
  const MeshTopology bar = build_topology(bar_along_x());
  const MirrorMap by_position = match_mirror_by_position(bar, 0);
  const MirrorMap by_topology = match_mirror_by_topology(bar, 0);
  EXPECT_EQ(by_position.matched, bar.n_faces);
  EXPECT_EQ(by_topology.matched, bar.n_faces);
  EXPECT_EQ(by_topology.face_twin, by_position.face_twin);
}

TEST(MirrorMatch, TopologyFindsTheTwinsOfAMeshThatIsOffThePlaneAndPosed) {
  const Mesh clean = make_icosphere(3);
  const MirrorMap reference = match_mirror_by_position(build_topology(clean), 0);
  ASSERT_EQ(reference.matched, int(clean.n_faces()));
  // Turned 3 degrees, one side bulged, every vertex jittered by 15% of an edge; ten jitters
  // (with four candidate twins per seed, 3 of 60 such jitters matched).
  for (unsigned seed = 1; seed <= 10; ++seed) {
    Mesh moved = clean;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.015, 0.015);  // edges are about 0.1
    const Mat3 turn = Eigen::AngleAxisd(3.0 * M_PI / 180.0, Vec3::UnitY()).toRotationMatrix();
    for (auto v : moved.vertices()) {
      Vec3 p = moved.point(v);
      if (p.x() > 0) p.x() *= 1.15;
      const double dx = jitter(rng), dy = jitter(rng), dz = jitter(rng);  // in this order
      p += Vec3(dx, dy, dz);
      moved.set_point(v, turn * p);
    }
    const MeshTopology t = build_topology(moved);
    const MirrorMap by_position = match_mirror_by_position(t, 0);
    EXPECT_NE(by_position.face_twin, reference.face_twin) << "positions no longer line up";
    const MirrorMap by_topology = match_mirror_by_topology(t, 0);
    EXPECT_EQ(by_topology.matched, t.n_faces) << "jitter " << seed;
    EXPECT_EQ(by_topology.face_twin, reference.face_twin) << "jitter " << seed;
    const MirrorMap chosen = match_mirror(t, 0);
    EXPECT_TRUE(chosen.by_topology) << "jitter " << seed;
    EXPECT_EQ(chosen.face_twin, reference.face_twin) << "jitter " << seed;
  }
}

TEST(MirrorMatch, AnAsymmetricMeshHasFewTwins) {
  // A sheet curling up on one side only (z = x^3): across x = 0.5 the sides do not meet.
  Mesh sheet = make_grid(1.0, 1.0, 20, 20, FaceShape::Triangles);
  for (auto v : sheet.vertices()) {
    const Vec3 p = sheet.point(v);
    sheet.set_point(v, Vec3(p.x(), p.y(), 0.6 * p.x() * p.x() * p.x()));
  }
  const MeshTopology t = build_topology(sheet);
  const MirrorMap map = match_mirror(t, 0);
  EXPECT_FALSE(map.by_topology) << "a consistent spread far from the geometric mirror is refused";
  EXPECT_LT(map.matched, t.n_faces / 2);
}

TEST(MirrorMatch, MirroredPoseIsTheReflection) {
  const MeshTopology t = build_topology(bar_along_x());
  const MirrorMap map = match_mirror(t, 0);
  std::vector<int> right, left;
  for (int f = 0; f < t.n_faces; ++f)
    if (t.rest_geometry.centroid[size_t(f)].x() > 0.9) right.push_back(f);
  for (const int f : right) left.push_back(map.twin(f));
  std::sort(left.begin(), left.end());
  HandleGroup a = make_handle_group("a", right, HandleMode::Pose, t, t.rest_points);
  const HandleGroup b = make_handle_group("b", left, HandleMode::Pose, t, t.rest_points);
  a.pose.translate = Vec3(0.1, 0.3, -0.2);
  a.pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  HandleGroup twin = b;
  twin.pose = mirrored_pose(a, b, map);
  // Every vertex of b's faces moves to the mirror image of where its twin vertex of a goes.
  for (const Vec3& p : {Vec3(0.95, 0.1, 0.1), Vec3(1.0, -0.1, 0.05), Vec3(0.3, 0.2, -0.4)}) {
    const Vec3 image = reflect(map, a.transform().apply(reflect(map, p)));
    EXPECT_LT((twin.transform().apply(p) - image).norm(), 1e-12);
  }
}

TEST(EditorMirror, SelectingAndPaintingActOnBothSides) {
  Harness s(bar_along_x());
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;
  e.set_mirror(0, true);
  ASSERT_NE(e.mirror_summary(0).find(std::to_string(t.n_faces) + " of"), std::string::npos)
      << e.mirror_summary(0);
  // A box around the right tip (the camera looks at the bar from the front).
  e.tools.tool = Tool::Select;
  e.tools.shape = SelectShape::Box;
  const glm::dvec3 tip = e.camera().project(glm::dvec3(0.95, 0.0, 0.1));
  s.event(InputEvent::cursor(tip.x - 30, tip.y - 60));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::cursor(tip.x + 60, tip.y + 60));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const FaceMask& selected = *e.document()->state.selection;
  const MirrorMap& map = *e.mirror_map(0);
  int right = 0, left = 0;
  for (int f = 0; f < t.n_faces; ++f) {
    if (!selected[size_t(f)]) continue;
    EXPECT_TRUE(selected[size_t(map.twin(f))]) << "face " << f << "'s twin";
    (t.rest_geometry.centroid[size_t(f)].x() > 0 ? right : left)++;
  }
  EXPECT_GT(right, 0);
  EXPECT_EQ(left, right);

  // A paint dab on the right tip paints the left one alike.
  e.clear_selection();
  e.tools.tool = Tool::Paint;
  e.tools.paint_layer = PaintLayer::Height;
  e.tools.paint_height = 0.4;
  s.event(InputEvent::cursor(tip.x, tip.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const FactorArray& height = e.document()->state.height_factor;
  ASSERT_TRUE(height);
  int painted = 0;
  for (int f = 0; f < t.n_faces; ++f) {
    EXPECT_EQ((*height)[size_t(f)], (*height)[size_t(map.twin(f))]);
    painted += (*height)[size_t(f)] != 1.0;
  }
  EXPECT_GT(painted, 1);

  // Mirror off: a dab paints one side only.
  e.set_mirror(0, false);
  e.tools.paint_height = 0.7;
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  int asymmetric = 0;
  for (int f = 0; f < t.n_faces; ++f)
    asymmetric += (*e.document()->state.height_factor)[size_t(f)] !=
                  (*e.document()->state.height_factor)[size_t(map.twin(f))];
  EXPECT_GT(asymmetric, 0);
}

TEST(EditorMirror, AHandleMadeOnOneSideGetsATwinThatFollowsIt) {
  Harness s(bar_along_x());
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;
  auto select = [&](auto take) {
    FaceMask m(size_t(t.n_faces), 0);
    for (int f = 0; f < t.n_faces; ++f) m[size_t(f)] = take(t.rest_geometry.centroid[size_t(f)]);
    e.document()->state.selection = std::make_shared<const FaceMask>(m);
  };
  select([](const Vec3& c) { return std::abs(c.x()) < 0.1; });
  e.make_handle(HandleMode::Fixed);  // the middle: one region across the plane
  e.set_mirror(0, true);
  select([](const Vec3& c) { return std::abs(c.x()) < 0.1; });
  e.make_handle(HandleMode::Fixed);
  ASSERT_EQ(e.document()->state.handles.size(), 1u) << "a region across the plane stays one";
  select([](const Vec3& c) { return c.x() > 0.9; });  // the right tip only
  e.make_handle(HandleMode::Pose);
  const auto& handles = e.document()->state.handles;
  ASSERT_EQ(handles.size(), 3u);
  EXPECT_EQ(handles[1].name, "Handle 3 +X");
  EXPECT_EQ(handles[2].name, "Handle 3 -X");
  EXPECT_EQ(handles[1].mirror_twin, 2);
  EXPECT_EQ(handles[2].mirror_twin, 1);
  EXPECT_EQ(handles[1].faces->size(), handles[2].faces->size());

  // Drag the right tip up and forward: the left tip follows as its mirror image.
  ASSERT_TRUE(s.settle());
  s.drag("Handle 3 +X", 40, -120);
  ASSERT_TRUE(s.settle());
  const std::vector<Vec3>& p = e.positions();
  const MirrorMap& map = *e.mirror_map(0);
  EXPECT_GT((handles[2].pose.translate).norm(), 0.1) << "the twin moved";
  // The mesh stays symmetric: each vertex sits at its mirror vertex's reflection.
  std::vector<int> vertex_twin(size_t(t.n_vertices), -1);
  for (int v = 0; v < t.n_vertices; ++v)
    for (int w = 0; w < t.n_vertices; ++w)
      if ((reflect(map, t.rest_points[size_t(v)]) - t.rest_points[size_t(w)]).norm() < 1e-9)
        vertex_twin[size_t(v)] = w;
  double worst = 0.0;
  for (int v = 0; v < t.n_vertices; ++v) {
    ASSERT_GE(vertex_twin[size_t(v)], 0);
    worst = std::max(worst, (reflect(map, p[size_t(v)]) - p[size_t(vertex_twin[size_t(v)])]).norm());
  }
  EXPECT_LT(worst, 1e-5 * s.diagonal());
  EXPECT_GT(largest_point_distance(p, t.rest_points), 0.1 * s.diagonal());

  // Saved and opened again, the pair is still a pair.
  const Scenario saved = export_scenario(e.document()->state, "bar.obj", "", SolverSpec{}, nullptr);
  ASSERT_TRUE(saved.editor);
  ASSERT_EQ(saved.editor->mirror_pairs.size(), 1u);
  const ResolvedScenario resolved = resolve_scenario(saved, *e.document()->mesh);
  const EditState reopened = import_scenario(saved, resolved, t);
  ASSERT_EQ(reopened.handles.size(), 3u);
  EXPECT_EQ(reopened.handles[1].mirror_twin, 2);
  EXPECT_EQ(reopened.handles[2].mirror_twin, 1);
  EXPECT_EQ(reopened.handles[1].mirror_axis, 0);

  // Deleting one leaves the other on its own; undo brings the pair back.
  e.delete_handle(2);
  EXPECT_EQ(e.document()->state.handles[1].mirror_twin, -1);
  e.undo();
  EXPECT_EQ(e.document()->state.handles[1].mirror_twin, 2);
}

TEST(MirrorMatch, TheShippedSpotIsMatchedByTopologyAcrossX) {
  const MeshTopology t =
      build_topology(load_mesh(primo::test::source_path("assets/meshes/spot_quadrangulated.obj")));
  const MirrorMap map = match_mirror(t, 0);
  EXPECT_TRUE(map.by_topology);
  EXPECT_EQ(map.matched, t.n_faces);
  expect_involution(map);
  EXPECT_LT(worst_reflection_error(t, map), 0.01 * t.bbox_diagonal);
}

namespace {

// Every twin points back, and no two faces share one.
void expect_one_to_one(const MirrorMap& map) {
  std::vector<int> taken(map.face_twin.size(), 0);
  for (size_t f = 0; f < map.face_twin.size(); ++f) {
    const int g = map.face_twin[f];
    if (g < 0) continue;
    ASSERT_EQ(map.face_twin[size_t(g)], int(f)) << "twins point at each other";
    ++taken[size_t(g)];
  }
  for (size_t g = 0; g < taken.size(); ++g) ASSERT_LE(taken[g], 1) << "face " << g << " is twice a twin";
}

// The `count` faces whose centroids are nearest face `seed`'s.
std::vector<int> faces_around(const MeshTopology& t, int seed, size_t count) {
  std::vector<std::pair<double, int>> by_distance;
  for (int f = 0; f < t.n_faces; ++f)
    by_distance.emplace_back(
        (t.rest_geometry.centroid[size_t(f)] - t.rest_geometry.centroid[size_t(seed)]).norm(), f);
  std::sort(by_distance.begin(), by_distance.end());
  std::vector<int> faces;
  for (size_t i = 0; i < count; ++i) faces.push_back(by_distance[i].second);
  std::sort(faces.begin(), faces.end());
  return faces;
}

// `faces` and their twins, as a brush stroke with the mirror on selects them.
FaceMask mirrored_selection(const std::vector<int>& faces, const MirrorMap& map, int n_faces) {
  FaceMask mask(size_t(n_faces), 0);
  for (const int f : faces) {
    mask[size_t(f)] = 1;
    if (map.twin(f) >= 0) mask[size_t(map.twin(f))] = 1;
  }
  return mask;
}

// The face counts a message gives in parentheses, "(590 faces)", in order.
std::vector<size_t> counts_in(const std::string& text) {
  std::vector<size_t> counts;
  for (size_t at = text.find('('); at != std::string::npos; at = text.find('(', at + 1)) {
    size_t n = 0;
    if (std::sscanf(text.c_str() + at, "(%zu faces)", &n) == 1) counts.push_back(n);
  }
  return counts;
}

}  // namespace

TEST(MirrorMatch, ASymmetricShapeTessellatedAsymmetricallyIsMatchedOneToOne) {
  // A sheet of triangles whose diagonals all lean the same way: across x = 0.5 the shape is
  // symmetric but a triangle's reflection lands between two triangles of the other side.
  const MeshTopology t = build_topology(make_grid(1.0, 1.0, 20, 20, FaceShape::Triangles));
  const MirrorMap map = match_mirror_by_position(t, 0);
  expect_one_to_one(map);
  EXPECT_GT(map.matched, 9 * t.n_faces / 10) << "of " << t.n_faces;
}

TEST(MirrorMatch, AScanIsMatchedOneToOneByPosition) {
  const MeshTopology t =
      build_topology(load_mesh(primo::test::shared_path("meshes/armadillo_29k.obj")));
  const MirrorMap map = match_mirror(t, 0);
  EXPECT_FALSE(map.by_topology) << "the scan's two sides are tessellated differently";
  expect_one_to_one(map);
  // Half of the faces at least (the arms and legs are posed a little differently on each
  // side), and the faces without a twin are the ones the view shades.
  EXPECT_GT(map.matched, t.n_faces / 2);
  const std::vector<char> without = faces_without_twin(map);
  EXPECT_EQ(std::count(without.begin(), without.end(), 1), t.n_faces - map.matched);
}

TEST(EditorMirror, HandlesOnAScanKeepEveryFaceOfTheSelectionAndSayHowMany) {
  Harness s(load_mesh(primo::test::shared_path("meshes/armadillo_29k.obj")));
  Editor& e = s.editor;
  const MeshTopology& t = *e.document()->topology;
  e.set_mirror(0, true);
  const MirrorMap& map = *e.mirror_map(0);
  // The summary counts the faces left without a twin, and the view shades exactly those.
  const int without = t.n_faces - map.matched;
  EXPECT_NE(e.mirror_summary(0).find("the " + std::to_string(without) + " without one"),
            std::string::npos)
      << e.mirror_summary(0);
  const std::vector<char> shaded = e.faces_without_twin();
  ASSERT_EQ(shaded.size(), size_t(t.n_faces));
  EXPECT_EQ(std::count(shaded.begin(), shaded.end(), 1), without);
  int unshaded_face = -1, shaded_face = -1;
  for (int f = 0; f < t.n_faces; ++f) (shaded[size_t(f)] ? shaded_face : unshaded_face) = f;
  OverlayInputs overlay;
  overlay.state = &e.document()->state;
  overlay.n_faces = t.n_faces;
  overlay.without_twin = &shaded;
  const std::vector<std::uint32_t> colors = face_overlay_colors(overlay);
  EXPECT_EQ(colors[size_t(unshaded_face)] >> 24, 0u) << "a face with a twin is not covered";
  EXPECT_GT(colors[size_t(shaded_face)] >> 24, 100u) << "a face without one is shaded";

  // A hand brushed with the mirror on: the 590 faces around the tip of the left arm, and the
  // twins they have.
  int tip = 0;
  for (int f = 0; f < t.n_faces; ++f)
    if (t.rest_geometry.centroid[size_t(f)].x() < t.rest_geometry.centroid[size_t(tip)].x()) tip = f;
  const std::vector<int> hand = faces_around(t, tip, 590);
  auto make_from = [&](const FaceMask& selection, HandleMode mode) {
    e.document()->state.selection = std::make_shared<const FaceMask>(selection);
    e.commit("Select");
    const size_t handles_before = e.document()->state.handles.size();
    e.make_handle(mode);
    const auto& handles = e.document()->state.handles;
    ASSERT_EQ(handles.size(), handles_before + 2) << "a mirrored pair";
    const HandleGroup& a = handles[handles.size() - 2];
    const HandleGroup& b = handles[handles.size() - 1];
    EXPECT_EQ(a.mirror_twin, int(handles.size() - 1));
    // Every selected face is in one of the two, and each is on its own side of the plane.
    std::vector<int> both = *a.faces;
    both.insert(both.end(), b.faces->begin(), b.faces->end());
    std::sort(both.begin(), both.end());
    EXPECT_EQ(both, selected_faces(selection)) << "no face of the selection is lost";
    for (const int f : *a.faces) EXPECT_GT(t.rest_geometry.centroid[size_t(f)].x(), map.plane);
    for (const int f : *b.faces) EXPECT_LT(t.rest_geometry.centroid[size_t(f)].x(), map.plane);
    // The message gives each group's true size.
    const std::string said = e.messages().back().text;
    EXPECT_EQ(counts_in(said), (std::vector<size_t>{a.faces->size(), b.faces->size()})) << said;
  };
  const FaceMask hand_selected = mirrored_selection(hand, map, t.n_faces);
  make_from(hand_selected, HandleMode::Pose);
  int hand_without_twin = 0;
  for (const int f : hand) hand_without_twin += map.twin(f) < 0;
  ASSERT_GT(hand_without_twin, 0) << "the test needs a hand the other side does not mirror fully";
  EXPECT_NE(e.messages().back().text.find(std::to_string(hand_without_twin) + " of the " +
                                          std::to_string(count_selected(hand_selected)) +
                                          " faces have no twin"),
            std::string::npos)
      << e.messages().back().text;

  // Both legs box-selected with the mirror on and fixed: every face of them is fixed.
  std::vector<int> legs;
  for (int f = 0; f < t.n_faces; ++f)
    if (t.rest_geometry.centroid[size_t(f)].y() < -0.4) legs.push_back(f);
  make_from(mirrored_selection(legs, map, t.n_faces), HandleMode::Fixed);
}
