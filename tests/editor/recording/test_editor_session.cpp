// The editor driven like a user, without a window: input events for selecting, making
// handles, dragging, painting, shortcuts, cancel, undo and redo, with the solver thread
// running. A stand-in picker finds the face under the cursor from projected centroids.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "support/editor_harness.h"
#include "primo/solve/deformer.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;
using primo::editor::harness::Harness;

TEST(EditorSession, DragIsOneStepAndUndoRestoresTheMesh) {
  Harness s;
  s.two_handles();
  ASSERT_EQ(s.editor.document()->state.handles.size(), 2u);
  EXPECT_EQ(s.editor.tools.tool, Tool::Drag) << "making a handle switches to dragging";
  const size_t steps = s.editor.document()->history.size();

  s.drag("Handle 2", 80, -30);
  const Document& d = *s.editor.document();
  EXPECT_EQ(d.history.size(), steps + 1) << "one drag, one undo step";
  EXPECT_EQ(d.history.undo_label(), "Drag 'Handle 2'");
  const Vec3 moved = d.state.handles[1].pose.translate;
  EXPECT_GT(moved.norm(), 0.05);
  // The drag moves in the view plane.
  const glm::dvec3 f = s.editor.camera().forward();
  EXPECT_LT(std::abs(moved.dot(Vec3(f.x, f.y, f.z))), 1e-9);

  ASSERT_TRUE(s.settle());
  // What a direct solve of the same setup gives.
  const DeformationInputs in = deformation_inputs(d.state);
  Deformer direct(*d.mesh, in.params, in.handles, in.forces);
  direct.solve(SolveOptions{});
  EXPECT_LT(largest_point_distance(s.editor.positions(), direct.vertex_positions()),
            1e-6 * s.diagonal());

  s.key(GLFW_KEY_Z, GLFW_MOD_CONTROL);
  EXPECT_TRUE(d.state.handles[1].pose.is_identity());
  ASSERT_TRUE(s.settle());
  EXPECT_LT(largest_point_distance(s.editor.positions(), d.topology->rest_points),
            1e-6 * s.diagonal());
  s.key(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT);
  EXPECT_EQ(d.state.handles[1].pose.translate, moved);

  // Alt+G puts the active handle back at rest, as one step.
  s.key(GLFW_KEY_G, GLFW_MOD_ALT);
  EXPECT_TRUE(d.state.handles[1].pose.is_identity());
  EXPECT_EQ(d.history.undo_label(), "Reset 'Handle 2'");
}

TEST(EditorSession, RightButtonCancelsADrag) {
  Harness s;
  s.two_handles();
  const size_t steps = s.editor.document()->history.size();
  double x, y;
  ASSERT_TRUE(s.editor.handle_window_position("Handle 2", x, y));
  s.event(InputEvent::cursor(x, y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::cursor(x + 50, y));
  EXPECT_FALSE(s.editor.document()->state.handles[1].pose.is_identity()) << "live while dragging";
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_RIGHT, GLFW_PRESS, 0));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  EXPECT_TRUE(s.editor.document()->state.handles[1].pose.is_identity());
  EXPECT_EQ(s.editor.document()->history.size(), steps);
}

TEST(EditorSession, FixedRegionsDoNotMoveAndPositionHandlesLetOrientationFollow) {
  Harness s;
  s.two_handles();
  s.drag("Fixed 1", 60, 0);  // the fixed base
  EXPECT_TRUE(s.editor.document()->state.handles[0].pose.is_identity());
  s.editor.set_handle_mode(1, HandleMode::Position);
  s.drag("Handle 2", 100, 0);
  ASSERT_TRUE(s.settle());
  const Document& d = *s.editor.document();
  EXPECT_TRUE(d.state.handles[1].pose.rotation.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs()));
  // The top cap tilts: its vertices no longer share one height.
  double lo = 1e9, hi = -1e9;
  for (int v = 0; v < d.topology->n_vertices; ++v)
    if (d.topology->rest_points[v].y() > 0.999) {
      lo = std::min(lo, s.editor.positions()[v].y());
      hi = std::max(hi, s.editor.positions()[v].y());
    }
  EXPECT_GT(hi - lo, 1e-3);
}

TEST(EditorSession, BrushSelectPaintAndShortcuts) {
  Harness s;
  Document& d = *s.editor.document();
  s.key(GLFW_KEY_Q);
  s.key(GLFW_KEY_C);
  EXPECT_EQ(s.editor.tools.tool, Tool::Select);
  EXPECT_EQ(s.editor.tools.shape, SelectShape::Brush);
  const size_t steps = d.history.size();
  s.event(InputEvent::cursor(400, 300));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::cursor(420, 310));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const int brushed = count_selected(*d.state.selection);
  EXPECT_GT(brushed, 0);
  EXPECT_EQ(d.history.size(), steps + 1);

  s.key(GLFW_KEY_EQUAL, GLFW_MOD_CONTROL);
  EXPECT_GT(count_selected(*d.state.selection), brushed);
  const int grown = count_selected(*d.state.selection);
  s.key(GLFW_KEY_I, GLFW_MOD_CONTROL);
  EXPECT_EQ(count_selected(*d.state.selection), d.n_faces() - grown);
  s.key(GLFW_KEY_A, GLFW_MOD_ALT);
  EXPECT_EQ(count_selected(*d.state.selection), 0);
  s.key(GLFW_KEY_A);
  EXPECT_EQ(count_selected(*d.state.selection), d.n_faces());
  s.key(GLFW_KEY_A, GLFW_MOD_ALT);

  // Paint stiffness: one stroke, one step, factors where the brush went.
  s.key(GLFW_KEY_P);
  const size_t before_paint = d.history.size();
  s.event(InputEvent::cursor(400, 300));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::cursor(410, 280));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  ASSERT_TRUE(d.state.height_factor);
  EXPECT_EQ(group_factors(d.state.height_factor).size(), 1u);
  EXPECT_EQ(group_factors(d.state.height_factor)[0].value, s.editor.tools.paint_height);
  EXPECT_EQ(d.history.size(), before_paint + 1);
  EXPECT_EQ(d.history.undo_label(), "Paint stiffness");
  // Ctrl erases.
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, GLFW_MOD_CONTROL));
  s.event(InputEvent::cursor(400, 300));
  s.event(InputEvent::cursor(410, 280));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, GLFW_MOD_CONTROL));
  EXPECT_FALSE(d.state.height_factor);
  ASSERT_TRUE(s.settle());
  EXPECT_EQ(s.editor.solver_status().phase, SolverPhase::Settled);
}

TEST(EditorSession, CommandsWithoutAMeshOrSelectionExplainThemselves) {
  Editor e;
  e.make_handle(HandleMode::Pose);  // no document: nothing happens
  e.undo();
  Harness s;
  s.editor.make_handle(HandleMode::Pose);
  ASSERT_FALSE(s.editor.messages().empty());
  EXPECT_TRUE(s.editor.messages().back().error);
  // Said in the status bar, where the next click fixes it: no popup to dismiss first.
  ASSERT_NE(s.editor.current_message(), nullptr);
  EXPECT_NE(s.editor.current_message()->text.find("Select faces"), std::string::npos);
  EXPECT_TRUE(s.editor.take_error_popup().empty());
  EXPECT_EQ(s.editor.error_count(), 1u);
  // Likewise saving with nothing open.
  EXPECT_FALSE(e.save_scenario("/tmp/x.json"));
  EXPECT_TRUE(e.take_error_popup().empty());
  ASSERT_NE(e.current_message(), nullptr);
  EXPECT_NE(e.current_message()->text.find("Nothing to save"), std::string::npos);
}

TEST(EditorSession, DroppedFilesOpenInTheBackground) {
  Harness s;
  const std::string path = std::string(PRIMO_SOURCE_DIR) + "/assets/meshes/cylinder.obj";
  s.editor.handle_event(InputEvent::drop({path}), false, false);
  EXPECT_TRUE(s.editor.file_task_running());
  ASSERT_TRUE(s.settle());
  EXPECT_EQ(s.editor.document()->mesh_path, path);
  EXPECT_EQ(s.editor.document()->n_faces(), 864);
  // A file that cannot be read is an error message, and the open document stays.
  s.editor.handle_event(InputEvent::drop({path + ".missing.obj"}), false, false);
  for (int i = 0; i < 500 && s.editor.file_task_running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    s.editor.update(0.01);
  }
  EXPECT_EQ(s.editor.document()->mesh_path, path);
  EXPECT_FALSE(s.editor.take_error_popup().empty());
}

TEST(EditorSession, GizmoMovesAndRotatesTheActiveHandleExactly) {
  Harness s;
  s.two_handles();
  Document& d = *s.editor.document();
  s.key(GLFW_KEY_W);
  GizmoKind kind;
  glm::dvec3 center;
  ASSERT_TRUE(s.editor.gizmo_visible(kind, center));
  EXPECT_EQ(kind, GizmoKind::Translate);
  const Camera& cam = s.editor.camera();
  // Grab the X arrow near its tip and pull along it, holding Ctrl to snap.
  const glm::dvec3 tip = cam.project(center + 0.8 * gizmo_world_size(cam, center) * glm::dvec3(1, 0, 0));
  const glm::dvec3 further = cam.project(center + 1.6 * gizmo_world_size(cam, center) * glm::dvec3(1, 0, 0));
  s.event(InputEvent::cursor(tip.x, tip.y));
  s.event(InputEvent::key_event(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS, 0));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, GLFW_MOD_CONTROL));
  s.event(InputEvent::cursor(further.x, further.y));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, GLFW_MOD_CONTROL));
  s.event(InputEvent::key_event(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE, GLFW_MOD_CONTROL));
  const Vec3 t = d.state.handles[1].pose.translate;
  const double step = snap_step_for(d.topology->bbox_diagonal);
  EXPECT_GT(t.x(), 0.0);
  EXPECT_NEAR(t.x() / step, std::round(t.x() / step), 1e-9) << "snapped";
  EXPECT_EQ(t.y(), 0.0);
  EXPECT_EQ(t.z(), 0.0);
  EXPECT_EQ(d.history.undo_label(), "Move 'Handle 2'");

  // Rotate: sweep a quarter turn around the view ring, snapped to 15 degrees.
  s.key(GLFW_KEY_E);
  ASSERT_TRUE(s.editor.gizmo_visible(kind, center));
  EXPECT_EQ(kind, GizmoKind::Rotate);
  s.quarter_turn_of_the_view_ring();
  const Eigen::AngleAxisd aa(d.state.handles[1].pose.rotation);
  EXPECT_NEAR(aa.angle() * 180.0 / M_PI, 90.0, 1e-9);
  const glm::dvec3 f = cam.forward();
  EXPECT_NEAR(std::abs(aa.axis().dot(Vec3(f.x, f.y, f.z))), 1.0, 1e-9) << "about the view direction";
  EXPECT_EQ(d.state.handles[1].pose.translate, t) << "rotation about the pivot keeps it in place";
  EXPECT_EQ(d.history.undo_label(), "Rotate 'Handle 2'");
  ASSERT_TRUE(s.settle());
}

TEST(EditorSession, OrientationHandlesTurnWhenDragged) {
  Harness s;
  s.two_handles();
  s.editor.set_handle_mode(1, HandleMode::Orientation);
  s.drag("Handle 2", 60, 0);
  const Pose& p = s.editor.document()->state.handles[1].pose;
  EXPECT_EQ(p.translate, Vec3::Zero());
  EXPECT_NEAR(Eigen::AngleAxisd(p.rotation).angle() * 180.0 / M_PI, 30.0, 1e-6) << "half a degree per pixel";
}

TEST(EditorSession, SettlesToTheMinimumWhateverTheIterationLimit) {
  // solver.max_iterations is for batch commands: the editor, even with a limit of 1, settles
  // where a direct solve ends, without a Continue click.
  Harness s;
  s.editor.document()->solver.max_iterations = 1;
  s.two_handles();
  s.drag("Handle 2", 80, -30);
  ASSERT_TRUE(s.settle());
  EXPECT_EQ(s.editor.solver_status().phase, SolverPhase::Settled);
  EXPECT_GT(s.editor.solver_status().iterations, 1);
  const Document& d = *s.editor.document();
  const DeformationInputs in = deformation_inputs(d.state);
  Deformer direct(*d.mesh, in.params, in.handles, in.forces);
  direct.solve(SolveOptions{});
  EXPECT_LT(largest_point_distance(s.editor.positions(), direct.vertex_positions()),
            1e-6 * s.diagonal());
  EXPECT_FALSE(s.editor.continue_solving()) << "nothing has stopped";
}

TEST(EditorSession, OpeningDocumentsBackToBackNeverShowsTheOldOnesGeometry) {
  // A busy solver (a 7,000-quad tube twisted far) publishes results of the first document
  // while the second one is opened; the editor must drop them (they crashed face_centroid).
  Editor e;
  e.set_viewport({0, 0, 800, 600, 1.0});
  const std::string dir = primo::test::temp_dir();
  for (int round = 0; round < 3; ++round) {
    auto big = make_document(make_cylinder(0.25, 2.0, 70, 100, FaceShape::Quads), "");
    const MeshTopology& t = *big->topology;
    std::vector<int> bottom, top;
    for (int f = 0; f < t.n_faces; ++f) {
      const double y = t.rest_geometry.centroid[f].y();
      if (y < 0.05) bottom.push_back(f);
      if (y > 1.95) top.push_back(f);
    }
    add_handle(big->state, t, t.rest_points, bottom, HandleMode::Fixed);
    const int h = add_handle(big->state, t, t.rest_points, top, HandleMode::Pose);
    big->state.handles[size_t(h)].pose.rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(2.5, Vec3::UnitY()));
    e.adopt(std::move(big));
    for (int k = 0; k < 20; ++k) {  // let the worker start publishing the big tube
      e.update(0.016);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    // The small bar, opened while the worker is still busy with the tube.
    e.adopt(make_document(make_bar(0.2, 1.0, 2, 10 + round), ""));
    const size_t n = size_t(e.document()->topology->n_vertices);
    for (int k = 0; k < 200; ++k) {
      e.update(0.016);
      ASSERT_EQ(e.positions().size(), n) << "round " << round << ", frame " << k;
      if (k % 20 == 0) e.frame_selection();  // reads face centroids of the shown positions
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
}

TEST(EditorSession, ALassoClosedNearItsStartSelectsWhatItEncloses) {
  Harness s;
  s.editor.tools.tool = Tool::Select;
  s.editor.tools.shape = SelectShape::Lasso;
  ASSERT_TRUE(s.settle());
  // A loop of radius 60 px around the middle of the view, released 1 px from where it began.
  const double cx = 400, cy = 300, r = 60;
  s.event(InputEvent::cursor(cx + r, cy));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  for (int k = 1; k <= 36; ++k) {
    const double a = 2 * M_PI * k / 36;
    s.event(InputEvent::cursor(cx + r * std::cos(a), cy + r * std::sin(a)));
  }
  s.event(InputEvent::cursor(cx + r, cy + 1));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const FaceMask& selected = *s.editor.document()->state.selection;
  int n = 0;
  for (auto m : selected) n += m ? 1 : 0;
  EXPECT_GT(n, 0);
  // A real click (no movement) on empty space still clears.
  s.event(InputEvent::cursor(5, 5));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  n = 0;
  for (auto m : *s.editor.document()->state.selection) n += m ? 1 : 0;
  EXPECT_EQ(n, 0);
}

TEST(EditorSession, TheHistoryListGoesBackToAnyStep) {
  Harness s;
  s.two_handles();
  ASSERT_TRUE(s.settle());
  const size_t before_drag = s.editor.document()->history.position();
  const std::vector<Vec3> rest = s.editor.positions();
  s.drag("Handle 2", 80, -30);
  ASSERT_TRUE(s.settle());
  ASSERT_GT(largest_point_distance(s.editor.positions(), rest), 0.01 * s.diagonal());
  s.editor.go_to_history(before_drag);  // as if clicked in Edit > History
  ASSERT_TRUE(s.settle());
  EXPECT_EQ(s.editor.document()->history.position(), before_drag);
  EXPECT_LT(largest_point_distance(s.editor.positions(), rest), 1e-6 * s.diagonal());
  s.editor.go_to_history(before_drag + 1);  // and forward again
  ASSERT_TRUE(s.settle());
  EXPECT_GT(largest_point_distance(s.editor.positions(), rest), 0.01 * s.diagonal());
}

TEST(EditorSession, AnIdleWaitIsNotAFrame) {
  Harness s;
  ASSERT_TRUE(s.settle());
  for (int k = 0; k < 50; ++k) s.editor.update(0.016);
  const double busy = s.editor.frame_ms();
  EXPECT_NEAR(busy, 16.0, 1.0);
  EXPECT_FALSE(s.editor.idle());
  // The window waited a quarter of a second for events: shown as idle, frame time unchanged.
  s.editor.mark_idle_wait();
  s.editor.update(0.25);
  EXPECT_TRUE(s.editor.idle());
  EXPECT_EQ(s.editor.frame_ms(), busy);
  s.editor.update(0.016);
  EXPECT_FALSE(s.editor.idle());
}

TEST(EditorSession, ASoftBrushPaintsLessTowardsItsRim) {
  Harness s;
  ASSERT_TRUE(s.settle());
  s.editor.set_tool(Tool::Paint);
  s.editor.tools.paint_layer = PaintLayer::Height;
  s.editor.tools.paint_height = 0.2;
  s.editor.tools.paint_strength = 0.5;
  s.editor.tools.paint_falloff = Falloff::Smooth;
  s.editor.tools.brush_radius = 80;
  s.event(InputEvent::cursor(400, 300));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0));
  s.event(InputEvent::mouse(GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0));
  const FactorArray& f = s.editor.document()->state.height_factor;
  ASSERT_TRUE(f);
  double lowest = 1.0, highest = 0.0;
  int painted = 0;
  for (double v : *f)
    if (v != 1.0) {
      ++painted;
      lowest = std::min(lowest, v);
      highest = std::max(highest, v);
    }
  EXPECT_GT(painted, 2);
  EXPECT_GE(lowest, 0.2 + 0.5 * 0.8 - 0.01) << "strength 0.5: at most half way to 0.2";
  EXPECT_GT(highest, lowest) << "the rim got less than the centre";
}

TEST(EditorSession, ExportingWhileSolvingSaysSoInTheMessageThatStays) {
  Editor e;
  e.set_viewport({0, 0, 800, 600, 1.0});
  auto doc = make_document(make_cylinder(0.25, 2.0, 60, 80, FaceShape::Quads), "");
  const MeshTopology& t = *doc->topology;
  std::vector<int> bottom, top;
  for (int f = 0; f < t.n_faces; ++f) {
    const double y = t.rest_geometry.centroid[f].y();
    if (y < 0.05) bottom.push_back(f);
    if (y > 1.95) top.push_back(f);
  }
  add_handle(doc->state, t, t.rest_points, bottom, HandleMode::Fixed);
  const int h = add_handle(doc->state, t, t.rest_points, top, HandleMode::Pose);
  doc->state.handles[size_t(h)].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(2.5, Vec3::UnitY()));
  doc->state.prisms.height = 1.0;  // the thin layer: slow to converge
  doc->state.prisms.height_unit = HeightUnit::MeanEdgeLength;
  e.adopt(std::move(doc));
  for (int k = 0; k < 200 && e.solver_status().phase != SolverPhase::Solving; ++k) {
    e.update(0.016);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(e.solver_status().busy());
  const std::string out = primo::test::temp_dir() + "/shown.obj";
  e.save_mesh(out);
  for (int k = 0; k < 500 && e.file_task_running(); ++k) {
    e.update(0.016);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_FALSE(e.messages().empty());
  const std::string last = e.messages().back().text;
  EXPECT_NE(last.find("Saved the deformed mesh"), std::string::npos) << last;
  EXPECT_NE(last.find("not converged yet"), std::string::npos) << last;
}

TEST(EditorSession, StatusMessagesGoStaleAfterAToolChangeOrTenSeconds) {
  Harness s;
  ASSERT_TRUE(s.settle());
  s.editor.info("Saved the scenario to x.json");
  ASSERT_NE(s.editor.current_message(), nullptr);
  EXPECT_EQ(s.editor.current_message()->text, "Saved the scenario to x.json");
  s.editor.set_tool(Tool::Paint);  // the message was about something else
  EXPECT_EQ(s.editor.current_message(), nullptr);
  s.editor.info("Painted");
  ASSERT_NE(s.editor.current_message(), nullptr);
  for (int k = 0; k < 11; ++k) s.editor.update(1.0);
  EXPECT_EQ(s.editor.current_message(), nullptr) << "older than 10 s";
  s.editor.error("Could not write");
  for (int k = 0; k < 11; ++k) s.editor.update(1.0);
  ASSERT_NE(s.editor.current_message(), nullptr) << "errors stay longer";
  EXPECT_TRUE(s.editor.current_message()->error);
}

TEST(EditorSession, MakingAHandleSaysThatTheDragToolIsOn) {
  Harness s;
  s.key(GLFW_KEY_Q);
  s.select_where(0.9, 2);
  s.editor.make_handle(HandleMode::Pose);
  EXPECT_EQ(s.editor.tools.tool, Tool::Drag);
  ASSERT_NE(s.editor.current_message(), nullptr) << "the tool change does not hide the message";
  EXPECT_NE(s.editor.current_message()->text.find("the Drag tool is on"), std::string::npos)
      << s.editor.current_message()->text;
  EXPECT_NE(s.editor.current_message()->text.find("Q selects again"), std::string::npos);
  // With another tool the tool stays, and the message says nothing of it.
  s.key(GLFW_KEY_W);
  s.select_where(-1, 0.1);
  s.editor.make_handle(HandleMode::Fixed);
  EXPECT_EQ(s.editor.tools.tool, Tool::Move);
  ASSERT_NE(s.editor.current_message(), nullptr);
  EXPECT_EQ(s.editor.current_message()->text.find("Drag tool"), std::string::npos);
}

TEST(EditorSession, OpeningFilesInQuickSuccessionOpensTheNewestWithoutAnError) {
  const std::string dir = test::temp_dir();
  std::vector<std::string> paths;
  for (int k = 0; k < 4; ++k) {
    paths.push_back(dir + "/bar" + std::to_string(k) + ".obj");
    save_mesh(make_bar(0.2, 1.0, 2, 10 + 20 * k), paths.back());
  }
  Editor e;
  for (const std::string& p : paths) e.open(p);  // faster than any of them loads
  for (int i = 0; i < 3000 && (e.file_task_running() || !e.document()); ++i) {
    e.update(0.016);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(e.error_count(), 0u) << "no request is refused";
  EXPECT_TRUE(e.take_error_popup().empty());
  ASSERT_NE(e.document(), nullptr);
  EXPECT_EQ(e.document()->mesh_path, paths.back()) << "the newest request wins";
  ASSERT_FALSE(e.recent_files().entries().empty());
  EXPECT_EQ(e.recent_files().entries().front(), paths.back());
}

TEST(EditorSession, ExportingASkinnedCharacterToObjSaysTheSkinIsLeftOut) {
  Editor e;
  e.adopt(load_document(test::source_path("assets/meshes/huesitos.fbx")));
  ASSERT_FALSE(e.document()->attributes->skin.empty());
  const std::string dir = test::temp_dir();
  for (const char* name : {"posed.obj", "posed.glb"}) {
    e.save_mesh(dir + "/" + name);
    for (int k = 0; k < 1000 && e.file_task_running(); ++k) {
      e.update(0.016);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_FALSE(e.messages().empty());
    const std::string last = e.messages().back().text;
    EXPECT_NE(last.find("Saved the deformed mesh"), std::string::npos) << last;
    const bool said = last.find("the skin (9 joints) is not saved") != std::string::npos;
    EXPECT_EQ(said, std::string(name) == "posed.obj") << last;
  }
}
