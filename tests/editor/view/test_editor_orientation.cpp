// The model's orientation in the editor: views relative to its up and front, where it comes
// from (scenario, orientation file, format), Spot facing the viewer, and Set front from view
// as an undo step that is saved with the scenario.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <functional>
#include <glm/gtc/constants.hpp>

#include "document/document.h"
#include "editor.h"
#include "support/editor_harness.h"
#include "document/model_orientation.h"
#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/scenario/scenario.h"
#include "document/scenario_bridge.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using namespace primo;
using namespace primo::editor;

namespace {

ModelOrientation orientation(const char* up, const char* front) {
  return parse_model_orientation(std::string(R"({"up": ")") + up + R"(", "front": ")" + front +
                                     "\"}",
                                 "");
}

glm::dvec3 towards_eye(const Camera& c) { return glm::normalize(c.eye() - c.pose().target); }

void show(Camera& c, ViewPreset preset) {
  c.view_preset(preset);
  c.update(10.0);  // finish the animation
}

std::string spot_path() { return test::source_path("assets/meshes/spot_quadrangulated.obj"); }

}  // namespace

TEST(EditorOrientation, ViewsAreTheModels) {
  for (const ModelOrientation& o :
       {ModelOrientation{}, orientation("+y", "-z"), orientation("+z", "-y"), orientation("-x", "+y")}) {
    SCOPED_TRACE(orientation_label(o));
    const glm::dvec3 up = axis_vector(o.up), front = axis_vector(o.front);
    const glm::dvec3 side = glm::cross(up, front);  // on the viewer's right in front view
    Camera c;
    c.set_viewport(800, 600);
    c.set_model_axes(up, front, false);
    show(c, ViewPreset::Front);
    EXPECT_GT(glm::dot(towards_eye(c), front), 1.0 - 1e-12) << "the eye is on the front side";
    EXPECT_GT(glm::dot(c.up(), up), 1.0 - 1e-12) << "the model's up is up on screen";
    EXPECT_GT(glm::dot(c.right(), side), 1.0 - 1e-12);
    show(c, ViewPreset::Back);
    EXPECT_GT(glm::dot(towards_eye(c), -front), 1.0 - 1e-12);
    show(c, ViewPreset::Right);
    EXPECT_GT(glm::dot(towards_eye(c), side), 1.0 - 1e-12);
    show(c, ViewPreset::Left);
    EXPECT_GT(glm::dot(towards_eye(c), -side), 1.0 - 1e-12);
    show(c, ViewPreset::Top);
    EXPECT_LT(glm::dot(c.forward(), up), -0.9999) << "looking down the up axis";
    EXPECT_GT(glm::dot(c.up(), -front), 0.9999) << "the front at the bottom, as in Blender";
    show(c, ViewPreset::Bottom);
    EXPECT_GT(glm::dot(c.forward(), up), 0.9999);
    // The turntable keeps the model's up up.
    c.orbit(120, -300);
    EXPECT_GT(glm::dot(c.up(), up), 0.0);
    EXPECT_NEAR(glm::dot(c.right(), up), 0.0, 1e-12) << "no roll";
  }
}

TEST(EditorOrientation, KeepingTheViewKeepsTheEye) {
  Camera c;
  c.set_viewport(800, 600);
  c.set_pose({glm::dvec3(0.1, 0.2, 0.3), 3.0, 0.4, 0.3});
  const glm::dvec3 eye = c.eye();
  c.set_model_axes(glm::dvec3(0, 0, 1), glm::dvec3(0, -1, 0), true);
  EXPECT_LT(glm::length(c.eye() - eye), 1e-12);
  EXPECT_GT(glm::dot(c.up(), glm::dvec3(0, 0, 1)), 0.0) << "rolled so that the new up is up";
  // Without keeping it, the yaw and pitch keep their meaning: the same side of the model.
  Camera d;
  d.set_viewport(800, 600);
  d.set_model_axes(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1), false);
  EXPECT_EQ(d.pose().yaw, CameraPose{}.yaw);
  EXPECT_EQ(d.pose().pitch, CameraPose{}.pitch);
  EXPECT_GT(glm::dot(towards_eye(d), glm::dvec3(0, 0, -1)), 0.7) << "the initial view sees the front";
}

TEST(EditorOrientation, SnapsAViewToTheNearestAxes) {
  // Looking from a bit right of +x, a little above, the camera's up near +y.
  ModelOrientation o = orientation_from_view(glm::normalize(glm::dvec3(1.0, 0.3, 0.2)),
                                             glm::normalize(glm::dvec3(-0.3, 1.0, 0.0)));
  EXPECT_EQ(o, orientation("+y", "+x"));
  // From below, the up comes out negative.
  o = orientation_from_view(glm::dvec3(0, 0, -1), glm::normalize(glm::dvec3(0.1, -1, 0)));
  EXPECT_EQ(o, orientation("-y", "-z"));
  // Looking straight down: the camera's up is the nearest axis that is not the front.
  o = orientation_from_view(glm::normalize(glm::dvec3(0.01, 1, 0.02)),
                            glm::normalize(glm::dvec3(0, 0.02, -1)));
  EXPECT_EQ(o, orientation("-z", "+y"));
  // Even when the camera's up is closest to the front's own axis, the up is perpendicular.
  o = orientation_from_view(glm::normalize(glm::dvec3(0.8, 0.6, 0.0)),
                            glm::normalize(glm::dvec3(-0.7, 0.7, 0.1)));
  EXPECT_EQ(o.front, (SignedAxis{0, 1}));
  EXPECT_EQ(o.up, (SignedAxis{1, 1}));
}

TEST(EditorOrientation, ComesFromTheFormatOrAnOrientationFile) {
  EXPECT_EQ(format_orientation("a/b.obj"), ModelOrientation{});
  EXPECT_EQ(format_orientation("model.PLY"), ModelOrientation{});
  EXPECT_EQ(format_orientation("part.STL"), orientation("+z", "-y")) << "CAD and 3D printing: z up";
  EXPECT_EQ(orientation_file_path("/m/spot.obj"), "/m/spot.orientation.json");
  EXPECT_EQ(orientation_file_path(""), "");

  const std::string dir = test::temp_dir();
  save_mesh(make_bar(0.2, 1.0, 2, 4), dir + "/bar.obj");
  EXPECT_EQ(load_document(dir + "/bar.obj")->state.orientation, ModelOrientation{});
  test::write_text(dir + "/bar.orientation.json", R"({"up": "+x", "front": "+y"})");
  const auto doc = load_document(dir + "/bar.obj");
  EXPECT_EQ(doc->state.orientation, orientation("+x", "+y"));
  EXPECT_EQ(doc->saved_state, doc->state) << "as opened: nothing to save";
  // The message of the Error `open` throws ("no error" when it throws none).
  auto error_of = [](const std::function<void()>& open) -> std::string {
    try {
      open();
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  // A broken file is an error naming it and the key.
  test::write_text(dir + "/bar.orientation.json", R"({"up": "+x", "front": "x"})");
  std::string m = error_of([&] { load_document(dir + "/bar.obj"); });
  EXPECT_NE(m.find("bar.orientation.json: front: expected"), std::string::npos) << m;
  // A named pipe under the sidecar's name is refused at once, not waited on.
  fs::remove(dir + "/bar.orientation.json");
  ASSERT_EQ(0, ::mkfifo((dir + "/bar.orientation.json").c_str(), 0600));
  m = error_of([&] { mesh_orientation(dir + "/bar.obj"); });
  EXPECT_NE(m.find("bar.orientation.json: not a regular file (a named pipe)"), std::string::npos) << m;
}

// Spot faces -z: its head (the top fifth) lies on the front side of its body, and the editor
// shows it from the front, in the initial view as in front view.
TEST(EditorOrientation, SpotLooksAtTheViewer) {
  const std::unique_ptr<Document> doc = load_document(spot_path());
  const ModelOrientation o = doc->state.orientation;
  EXPECT_EQ(o, orientation("+y", "-z"));
  const glm::dvec3 up = axis_vector(o.up), front = axis_vector(o.front);
  const std::vector<Vec3>& p = doc->topology->rest_points;
  double lo = 1e9, hi = -1e9;
  glm::dvec3 mean(0.0);
  for (const Vec3& v : p) {
    const glm::dvec3 g(v.x(), v.y(), v.z());
    lo = std::min(lo, glm::dot(g, up)), hi = std::max(hi, glm::dot(g, up));
    mean += g / double(p.size());
  }
  glm::dvec3 head(0.0);
  int n = 0;
  for (const Vec3& v : p) {
    const glm::dvec3 g(v.x(), v.y(), v.z());
    if (glm::dot(g, up) > hi - 0.2 * (hi - lo)) head += g, ++n;
  }
  head /= double(n);
  EXPECT_GT(glm::dot(head - mean, front), 0.3) << "the head is at the front";

  harness::Harness h(load_mesh(spot_path()));
  h.editor.adopt(load_document(spot_path()));
  const Camera& c = h.editor.camera();
  EXPECT_GT(glm::dot(towards_eye(c), front), 0.6) << "the initial view sees the face";
  h.key(GLFW_KEY_KP_1);
  h.editor.update(10.0);
  EXPECT_GT(glm::dot(towards_eye(c), front), 1.0 - 1e-12) << "Numpad 1 is Spot's front";
  // A scenario on Spot without an orientation of its own takes the mesh's.
  EXPECT_EQ(load_document(test::source_path("assets/scenarios/spot-pose.json"))->state.orientation, o);
}

TEST(EditorOrientation, AScenarioSaysWhichWayIsUp) {
  const std::string dir = test::temp_dir();
  save_mesh(make_bar(0.2, 1.0, 2, 4), dir + "/bar.obj");
  test::write_text(dir + "/z-up.json", R"({"format": "primo-scenario/1", "mesh": "bar.obj",
      "editor": {"orientation": {"up": "+z", "front": "+x"}}})");
  // The scenario's orientation wins over an orientation file beside the mesh.
  test::write_text(dir + "/bar.orientation.json", R"({"up": "-y", "front": "+z"})");
  harness::Harness h;
  h.editor.adopt(load_document(dir + "/z-up.json"));
  EXPECT_EQ(h.editor.document()->state.orientation, orientation("+z", "+x"));
  h.key(GLFW_KEY_KP_7);
  h.editor.update(10.0);
  EXPECT_LT(h.editor.camera().forward().z, -0.9999) << "top view looks down +z";
}

TEST(EditorOrientation, SetFrontFromViewIsSavedAndUndone) {
  const std::string dir = test::temp_dir();
  save_mesh(make_bar(0.2, 1.0, 2, 4), dir + "/bar.obj");
  harness::Harness h;
  h.editor.adopt(load_document(dir + "/bar.obj"));
  Editor& e = h.editor;
  EXPECT_FALSE(e.has_unsaved_changes());
  // Look from +x, a little from above and turned a bit: the front snaps to +x.
  CameraPose pose = e.camera().pose();
  pose.yaw = glm::half_pi<double>() - 0.2;
  pose.pitch = 0.3;
  e.camera().set_pose(pose);
  e.set_front_from_view();
  EXPECT_EQ(e.document()->state.orientation, orientation("+y", "+x"));
  EXPECT_TRUE(e.has_unsaved_changes());
  e.update(10.0);
  EXPECT_GT(glm::dot(towards_eye(e.camera()), glm::dvec3(1, 0, 0)), 1.0 - 1e-12)
      << "shows the new front";
  h.key(GLFW_KEY_KP_3);
  e.update(10.0);
  EXPECT_GT(glm::dot(towards_eye(e.camera()), glm::dvec3(0, 0, -1)), 1.0 - 1e-12)
      << "right view: the side on the viewer's right of the new front";

  e.undo();
  e.update(0.0);
  EXPECT_EQ(e.document()->state.orientation, ModelOrientation{});
  EXPECT_EQ(e.camera().model_front(), glm::dvec3(0, 0, 1)) << "the turntable follows undo";
  e.redo();
  ASSERT_TRUE(e.save_scenario(dir + "/saved.json"));
  const Scenario saved = load_scenario(dir + "/saved.json");
  ASSERT_TRUE(saved.editor && saved.editor->orientation);
  EXPECT_EQ(*saved.editor->orientation, orientation("+y", "+x"));
  EXPECT_EQ(load_document(dir + "/saved.json")->state.orientation, orientation("+y", "+x"));

  // The convention need not be written, unless an orientation file could say otherwise.
  EditState plain = initial_edit_state(e.document()->n_faces());
  EXPECT_FALSE(export_scenario(plain, dir + "/bar.obj", dir + "/p.json", SolverSpec{}).editor);
  const Scenario on_spot = export_scenario(plain, spot_path(), dir + "/p.json", SolverSpec{});
  ASSERT_TRUE(on_spot.editor && on_spot.editor->orientation);
  EXPECT_EQ(*on_spot.editor->orientation, ModelOrientation{});
}
