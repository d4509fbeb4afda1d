// Input at any frame rate: events are queued, not sampled once a frame. Which events one panel
// frame takes (one_ui_frame_of_input), and the panels driven headless through the window's own
// pieces (UiInput, route_input) with a whole burst of input queued in one slow frame: a quick
// Enter ends a value field's edit, the keys after it reach the editor, and the solver settles
// while a field is being typed in.

#include <gtest/gtest.h>

#include <imgui.h>
#include <imgui_internal.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <thread>

#include "editor.h"
#include "support/headless_imgui.h"
#include "panels.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"
#include "ui_input.h"

using namespace primo;
using namespace primo::editor;

namespace {

InputEvent press(int key, int mods = 0) { return InputEvent::key_event(key, GLFW_PRESS, mods); }
InputEvent release(int key, int mods = 0) { return InputEvent::key_event(key, GLFW_RELEASE, mods); }

// The sizes of the panel frames a queue is split into.
std::vector<size_t> frames_of(InputQueue queue) {
  std::vector<size_t> sizes;
  while (!queue.empty()) {
    const size_t n = one_ui_frame_of_input(queue);
    EXPECT_GT(n, 0u);
    if (n == 0) break;
    sizes.push_back(n);
    queue.erase(queue.begin(), queue.begin() + std::ptrdiff_t(n));
  }
  return sizes;
}

// The window's panels without a window: Dear ImGui with GLFW's key codes (as its GLFW backend
// maps them), an editor on Spot's control mesh with one handle, and displayed frames that take
// their queued input as the window's frames do (App::frame): one panel frame per batch, the
// editor updated once.
struct Window : primo::test::HeadlessImGui {
  Editor e;
  UiState ui;
  UiInput input;

  Window() {
    ImGuiIO& io = ImGui::GetIO();
    const std::pair<ImGuiKey_, int> keys[] = {
        {ImGuiKey_Tab, GLFW_KEY_TAB}, {ImGuiKey_LeftArrow, GLFW_KEY_LEFT},
        {ImGuiKey_RightArrow, GLFW_KEY_RIGHT}, {ImGuiKey_UpArrow, GLFW_KEY_UP},
        {ImGuiKey_DownArrow, GLFW_KEY_DOWN}, {ImGuiKey_PageUp, GLFW_KEY_PAGE_UP},
        {ImGuiKey_PageDown, GLFW_KEY_PAGE_DOWN}, {ImGuiKey_Home, GLFW_KEY_HOME},
        {ImGuiKey_End, GLFW_KEY_END}, {ImGuiKey_Insert, GLFW_KEY_INSERT},
        {ImGuiKey_Delete, GLFW_KEY_DELETE}, {ImGuiKey_Backspace, GLFW_KEY_BACKSPACE},
        {ImGuiKey_Space, GLFW_KEY_SPACE}, {ImGuiKey_Enter, GLFW_KEY_ENTER},
        {ImGuiKey_Escape, GLFW_KEY_ESCAPE}, {ImGuiKey_KeyPadEnter, GLFW_KEY_KP_ENTER},
        {ImGuiKey_A, GLFW_KEY_A}, {ImGuiKey_C, GLFW_KEY_C}, {ImGuiKey_V, GLFW_KEY_V},
        {ImGuiKey_X, GLFW_KEY_X}, {ImGuiKey_Y, GLFW_KEY_Y}, {ImGuiKey_Z, GLFW_KEY_Z}};
    for (const auto& [imgui_key, glfw_key] : keys) io.KeyMap[imgui_key] = glfw_key;
    ui.recovery_checked = true;
    e.adopt(load_document(primo::test::source_path("assets/meshes/spot_control_mesh.obj")));
    const MeshTopology& t = *e.document()->topology;
    FaceMask head(size_t(t.n_faces), 0);
    for (int f = 0; f < t.n_faces; ++f)
      head[size_t(f)] = (t.rest_geometry.centroid[size_t(f)] - Vec3(0.0, 0.55, -0.45)).norm() < 0.3;
    e.document()->state.selection = std::make_shared<const FaceMask>(head);
    e.make_handle(HandleMode::Pose);
    e.tools.tool = Tool::Drag;
    for (int k = 0; k < 3; ++k) frame();  // settle the layout
  }

  void frame(InputQueue queue = {}) {
    ImGuiIO& io = ImGui::GetIO();
    do {
      const auto taken = queue.begin() + std::ptrdiff_t(one_ui_frame_of_input(queue));
      const InputQueue batch(queue.begin(), taken);
      queue.erase(queue.begin(), taken);
      input.feed(batch);
      input.apply_pointer();
      io.DeltaTime = 1.0f / 60.0f;
      ImGui::NewFrame();
      e.set_viewport(viewport_rect(ui, io.DisplaySize.x, io.DisplaySize.y, 1.0f));
      route_input(batch, e, ui);
      if (queue.empty()) e.update(0.25);  // a slow frame
      draw_ui(e, ui);
      ImGui::Render();
    } while (!queue.empty());
  }

  // The ID of the active handle's Angle field (panels.cpp: Properties > handles > active).
  ImGuiID angle_field() {
    ImGui::NewFrame();
    draw_ui(e, ui);
    ImGui::Begin("Properties");
    ImGui::PushID("handles");
    ImGui::PushID("active");
    const ImGuiID id = ImGui::GetID("Angle");
    ImGui::PopID();
    ImGui::PopID();
    ImGui::End();
    ImGui::Render();
    return id;
  }
  // A point on a widget of the properties panel, found by hovering down its left part.
  bool find(ImGuiID id, float& x, float& y) {
    x = ImGui::GetIO().DisplaySize.x - ui.panel_width + 60.0f;
    for (y = 0.0f; y < ImGui::GetIO().DisplaySize.y; y += 3.0f) {
      frame({InputEvent::cursor(x, y)});
      if (ImGui::GetCurrentContext()->HoveredId == id) return true;
    }
    return false;
  }
  bool editing() const { return ImGui::GetActiveID() != 0; }
  double angle_deg() const {
    const HandleGroup& h = e.document()->state.handles.at(0);
    return Eigen::AngleAxisd(h.pose.rotation).angle() * 180.0 / M_PI;
  }
  // Ctrl + click on the field, an event a frame: it becomes a text field, its text selected.
  void start_typing_into(float x, float y) {
    for (const InputEvent& event :
         {press(GLFW_KEY_LEFT_CONTROL), InputEvent::cursor(x, y),
          InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, GLFW_MOD_CONTROL),
          InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, GLFW_MOD_CONTROL),
          release(GLFW_KEY_LEFT_CONTROL, GLFW_MOD_CONTROL)})
      frame({event});
    frame();
  }
  // Typed as a keyboard sends it: each key down, its character, the key up.
  static void type(InputQueue& q, const std::string& text) {
    for (const char c : text) {
      const int key = c == '.' ? GLFW_KEY_PERIOD : GLFW_KEY_0 + (c - '0');
      q.push_back(press(key));
      q.push_back(InputEvent::character(static_cast<unsigned char>(c)));
      q.push_back(release(key));
    }
  }
};

}  // namespace

TEST(UiInputFrames, APressAndReleaseOfOneKeyAreTwoFrames) {
  EXPECT_EQ(frames_of({press(GLFW_KEY_ENTER), release(GLFW_KEY_ENTER)}),
            (std::vector<size_t>{1, 1}));
  // Characters typed in a row go together; a key change between them parts them, in order.
  EXPECT_EQ(frames_of({InputEvent::character('1'), InputEvent::character('2'),
                       press(GLFW_KEY_BACKSPACE), release(GLFW_KEY_BACKSPACE),
                       InputEvent::character('3')}),
            (std::vector<size_t>{2, 1, 1, 1}));
  // A chord: each key's change its own frame.
  EXPECT_EQ(frames_of({press(GLFW_KEY_LEFT_CONTROL), press(GLFW_KEY_Z, GLFW_MOD_CONTROL),
                       release(GLFW_KEY_Z, GLFW_MOD_CONTROL), release(GLFW_KEY_LEFT_CONTROL)}),
            (std::vector<size_t>{1, 1, 1, 1}));
}

TEST(UiInputFrames, PointerMovesGoWithAFrameUntilAButtonChanges) {
  const InputEvent down = InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0);
  const InputEvent up = InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0);
  // Moves, then the press where they ended; the moves after it with the release.
  EXPECT_EQ(frames_of({InputEvent::cursor(1, 1), InputEvent::cursor(2, 2), down,
                       InputEvent::cursor(3, 3), InputEvent::cursor(4, 4), up}),
            (std::vector<size_t>{3, 3}));
  // Key repeats and moves do not part a frame; a wheel step after a key does.
  InputEvent repeat = press(GLFW_KEY_RIGHT_BRACKET);
  repeat.action = GLFW_REPEAT;
  EXPECT_EQ(frames_of({press(GLFW_KEY_RIGHT_BRACKET), repeat, repeat, InputEvent::cursor(5, 5),
                       InputEvent::scroll(0, 1), InputEvent::cursor(6, 6)}),
            (std::vector<size_t>{4, 1, 1}));
  EXPECT_EQ(one_ui_frame_of_input({}), 0u);
}

TEST(EditorUiInput, AQuickEnterInAValueFieldEndsTheEditInOneSlowFrame) {
  Window w;
  float x, y;
  ASSERT_TRUE(w.find(w.angle_field(), x, y));
  w.start_typing_into(x, y);
  ASSERT_TRUE(w.editing()) << "Ctrl + click makes the field a text field";
  // "30", Enter down and up: all within one frame of a quarter second.
  InputQueue typed;
  Window::type(typed, "30");
  typed.push_back(press(GLFW_KEY_ENTER));
  typed.push_back(release(GLFW_KEY_ENTER));
  w.frame(typed);
  EXPECT_FALSE(w.editing()) << "the field left edit mode";
  EXPECT_NEAR(w.angle_deg(), 30.0, 1e-9);
  // The keyboard is the editor's again: W is the Move tool, Ctrl+Z undoes the typed angle.
  w.frame({press(GLFW_KEY_W), release(GLFW_KEY_W)});
  EXPECT_EQ(w.e.tools.tool, Tool::Move);
  w.frame({press(GLFW_KEY_LEFT_CONTROL), press(GLFW_KEY_Z, GLFW_MOD_CONTROL),
           release(GLFW_KEY_Z, GLFW_MOD_CONTROL), release(GLFW_KEY_LEFT_CONTROL)});
  EXPECT_NEAR(w.angle_deg(), 0.0, 1e-9);
}

TEST(EditorUiInput, TheSolverSettlesWhileAValueFieldIsInEditMode) {
  Window w;
  float x, y;
  ASSERT_TRUE(w.find(w.angle_field(), x, y));
  w.start_typing_into(x, y);
  // Past half a turn: shown again from the rotation, the field would read 90 degrees about
  // the opposite axis, while the text typed says 270.
  InputQueue typed;
  Window::type(typed, "270");
  w.frame(typed);
  ASSERT_TRUE(w.editing());
  // The typed angle poses the handle live; the field stays open, and the solver must come to
  // rest rather than start over at every frame.
  bool settled = false;
  for (int k = 0; k < 600 && !settled; ++k) {
    w.frame();
    settled = w.e.settled();
    if (!settled) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(w.editing()) << "still in edit mode";
  EXPECT_TRUE(settled) << "solver: iteration " << w.e.solver_status().iterations;
  EXPECT_NEAR(w.angle_deg(), 90.0, 1e-9) << "a quarter turn the other way";
}

TEST(EditorUiInput, ControlsWindowWithTheMoveToolLeavesTheViewAsItWas) {
  // F1 opens and closes Help > Controls over the 3D view: the view's rectangle, the camera and
  // its projection stay as they were, whichever tool is on (the Move tool's gizmo included).
  Window w;
  w.e.set_tool(Tool::Move);
  double x = 0.0, y = 0.0;
  ASSERT_TRUE(w.e.handle_window_position("Handle 1", x, y));
  w.frame({InputEvent::cursor(x + 30.0, y)});
  w.frame();
  const ViewportRect vp = w.e.viewport();
  const CameraPose pose = w.e.camera().pose();
  const glm::dmat4 matrix = w.e.camera().projection() * w.e.camera().view();
  auto same_view = [&](const char* when) {
    const ViewportRect now = w.e.viewport();
    EXPECT_EQ(now.x, vp.x) << when;
    EXPECT_EQ(now.y, vp.y) << when;
    EXPECT_EQ(now.width, vp.width) << when;
    EXPECT_EQ(now.height, vp.height) << when;
    EXPECT_EQ(w.e.camera().pose().target, pose.target) << when;
    EXPECT_EQ(w.e.camera().pose().distance, pose.distance) << when;
    EXPECT_TRUE(w.e.camera().projection() * w.e.camera().view() == matrix) << when;
  };
  w.frame({press(GLFW_KEY_F1), release(GLFW_KEY_F1)});
  for (int k = 0; k < 4; ++k) w.frame();
  EXPECT_TRUE(w.ui.show_help);
  EXPECT_EQ(w.e.tools.tool, Tool::Move);
  same_view("with the Controls window open");
  w.frame({InputEvent::cursor(x, y)});
  same_view("with the pointer over the view");
  w.frame({press(GLFW_KEY_F1), release(GLFW_KEY_F1)});
  for (int k = 0; k < 4; ++k) w.frame();
  EXPECT_FALSE(w.ui.show_help);
  same_view("after the Controls window closed");
}
