// Sessions inside the editor (no window): recording what commands and panels do to the
// document, saving, playback with seek and play, and exporting as an animated glTF.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "editor.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/sessions/session.h"
#include "support/session_support.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;

namespace {

std::vector<int> faces_with(const Document& d, double y_min, double y_max) {
  std::vector<int> out;
  for (int f = 0; f < d.n_faces(); ++f) {
    const double y = d.topology->rest_geometry.centroid[f].y();
    if (y >= y_min && y <= y_max) out.push_back(f);
  }
  return out;
}

bool same_handles(const std::vector<HandleGroup>& a, const std::vector<HandleGroup>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].name != b[i].name || *a[i].faces != *b[i].faces || !(a[i].pose == b[i].pose)) return false;
  return true;
}

// Saves a bar as DIR/bar.obj and opens it in `e`.
void open_bar(Editor& e, const std::string& dir) {
  save_mesh(make_bar(0.2, 1.0, 2, 10), dir + "/bar.obj");
  e.adopt(make_document(load_mesh(dir + "/bar.obj"), dir + "/bar.obj"));
  e.update(0.016);
}

}  // namespace

TEST(EditorSessions, RecordSaveAndPlayBack) {
  const std::string dir = primo::test::temp_dir();
  Editor e;
  open_bar(e, dir);
  e.sessions.start_recording(e);
  ASSERT_TRUE(e.sessions.recording());
  Document* d = e.document();
  add_handle(d->state, *d->topology, d->topology->rest_points, faces_with(*d, -1, 0.05), HandleMode::Fixed);
  e.commit("fixed");
  e.update(0.016);
  const int top = add_handle(d->state, *d->topology, d->topology->rest_points, faces_with(*d, 0.95, 2),
                             HandleMode::Position);
  e.commit("top");
  e.update(0.016);
  std::vector<std::vector<HandleGroup>> seen;
  for (int k = 1; k <= 10; ++k) {
    d->state.handles[size_t(top)].pose.translate = Vec3(0.03 * k, 0.0, 0.0);
    e.live_edit();
    e.update(0.016);
    seen.push_back(d->state.handles);
  }
  e.commit("drag");
  e.update(0.016);
  e.undo();
  e.update(0.016);
  e.redo();
  e.update(0.016);
  const std::vector<HandleGroup> final_handles = d->state.handles;
  e.sessions.save(e, dir + "/s.session.json");
  EXPECT_FALSE(e.sessions.recording());
  std::ifstream in(dir + "/s.session.json");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("\"type\":\"undo\""), std::string::npos);
  EXPECT_NE(text.str().find("\"type\":\"redo\""), std::string::npos);
  EXPECT_NE(text.str().find("\"mesh\": \"bar.obj\""), std::string::npos);

  // Play it back on a fresh document of the same mesh.
  e.adopt(make_document(load_mesh(dir + "/bar.obj"), dir + "/bar.obj"));
  e.update(0.016);
  e.sessions.open_playback(e, dir + "/s.session.json");
  ASSERT_TRUE(e.sessions.has_playback());
  d = e.document();
  EXPECT_TRUE(d->state.handles.empty());
  e.sessions.seek(e, e.sessions.duration());
  EXPECT_TRUE(same_handles(d->state.handles, final_handles));
  EXPECT_EQ(d->history.undo_label(), "Session playback");
  // Scrubbing back to a frame of the drag shows that frame's pose exactly.
  const Session& s = e.sessions.playback_session();
  double t5 = -1;
  for (const SessionEvent& ev : s.events)
    if (ev.type == SessionEvent::Type::Targets && ev.poses[0].pose.translate.x() == 0.03 * 5) t5 = ev.t;
  ASSERT_GE(t5, 0.0);
  e.sessions.seek(e, t5);
  EXPECT_TRUE(same_handles(d->state.handles, seen[4]));
  e.sessions.seek(e, 0.0);
  EXPECT_TRUE(d->state.handles.empty());
  e.sessions.play(e);
  for (int i = 0; i < 1000 && e.sessions.playing(); ++i) e.update(0.016);
  EXPECT_FALSE(e.sessions.playing());
  EXPECT_TRUE(same_handles(d->state.handles, final_handles));
}

TEST(EditorSessions, PlaybackRejectsASessionOfAnotherMesh) {
  const std::string dir = primo::test::temp_dir();
  save_mesh(make_bar(0.2, 1.0, 2, 10), dir + "/bar.obj");
  Session s;
  s.mesh_path = dir + "/bar.obj";
  SessionEvent ev;
  ev.type = SessionEvent::Type::Factors;
  ev.faces = {100000};
  ev.values = {0.5};
  s.events.push_back(ev);
  save_session(s, dir + "/s.session.json");
  Editor e;
  e.adopt(make_document(load_mesh(dir + "/bar.obj"), dir + "/bar.obj"));
  e.update(0.016);
  e.sessions.open_playback(e, dir + "/s.session.json");
  EXPECT_FALSE(e.sessions.has_playback());
  ASSERT_FALSE(e.messages().empty());
  EXPECT_NE(e.messages().back().text.find("events[0] (factors): faces[0]: face 100000 out of range"),
            std::string::npos)
      << e.messages().back().text;
}

TEST(SessionControl, ProposesAFilePerMeshAndReadableDurations) {
  EXPECT_EQ(default_session_path("/models/spot.obj"), "/models/spot.session.json");
  EXPECT_NE(default_session_path("/models/spot.obj"), default_session_path("/models/bunny.off"));
  EXPECT_EQ(format_duration(8.078583), "8.1 s");
  EXPECT_EQ(format_duration(0.0), "0.0 s");
  EXPECT_EQ(format_duration(125.4), "2 min 05 s");
}

// The animation `primo replay --animation` writes of `dir`/s.session.json, into a file named as
// the editor's export `dir`/editor.glb (the node is named after the file); "" when it fails.
std::string replayed_animation(const std::string& dir) {
  std::filesystem::create_directories(dir + "/command");
  const primo::test::CommandResult run = primo::test::run_primo(
      "replay " + dir + "/s.session.json -o " + dir + "/final.obj --animation " + dir +
      "/command/editor.glb");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return run.exit_code == 0 ? primo::test::read_text(dir + "/command/editor.glb") : "";
}

// Lets the editor run (a minute at most) until its animation export is done.
void wait_for_export(Editor& e) {
  for (int i = 0; i < 6000 && e.sessions.exporting(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    e.update(0.016);
  }
}

TEST(EditorSessions, ExportsTheAnimationTheReplayCommandWrites) {
  const std::string dir = primo::test::temp_dir();
  const primo::test::RecordedSession r = primo::test::record_bar_session(dir + "/bar.obj");
  save_mesh(r.mesh, dir + "/bar.obj");
  save_session(r.session, dir + "/s.session.json");
  Editor e;
  e.adopt(make_document(load_mesh(dir + "/bar.obj"), dir + "/bar.obj"));
  e.update(0.016);
  EXPECT_FALSE(e.sessions.has_session());
  e.sessions.export_animation(e, dir + "/none.glb");
  EXPECT_NE(e.messages().back().text.find("No session to export"), std::string::npos);

  e.sessions.open_playback(e, dir + "/s.session.json");
  ASSERT_TRUE(e.sessions.has_session());
  e.sessions.export_animation(e, dir + "/editor.glb");
  EXPECT_TRUE(e.sessions.exporting());
  wait_for_export(e);
  ASSERT_FALSE(e.sessions.exporting());
  EXPECT_EQ(e.messages().back().text, "Exported the session animation to " + dir + "/editor.glb");
  const std::string exported = primo::test::read_text(dir + "/editor.glb");
  EXPECT_GT(exported.size(), 1000u);
  EXPECT_TRUE(exported == replayed_animation(dir));

  // A name that is no glTF: refused at once, nothing written.
  e.sessions.export_animation(e, dir + "/anim.obj");
  EXPECT_FALSE(e.sessions.exporting());
  EXPECT_NE(e.messages().back().text.find("anim.obj: an animation is written as glTF"), std::string::npos);
}

TEST(EditorSessions, ExportedAnimationKeepsTheMeshsUvsAsTheReplayCommandDoes) {
  const std::string dir = primo::test::temp_dir();
  const primo::test::RecordedSession r = primo::test::record_bar_session(dir + "/bar.obj");
  // The bar with a UV per face corner.
  MeshAttributes uvs;
  uvs.texcoords.emplace_back();
  const int corners = first_corners(r.mesh).back();
  for (int c = 0; c < corners; ++c) {
    uvs.texcoords[0].values.push_back({double(c % 7) / 7, double(c % 5) / 5});
    uvs.texcoords[0].corner.push_back(c);
  }
  save_mesh(r.mesh, uvs, dir + "/bar.obj");
  save_session(r.session, dir + "/s.session.json");
  Editor e;
  e.adopt(load_document(dir + "/bar.obj"));
  e.update(0.016);
  e.sessions.open_playback(e, dir + "/s.session.json");
  ASSERT_TRUE(e.sessions.has_session());
  e.sessions.export_animation(e, dir + "/editor.glb");
  wait_for_export(e);
  ASSERT_FALSE(e.sessions.exporting());
  const std::string exported = primo::test::read_text(dir + "/editor.glb");
  EXPECT_NE(exported.find("TEXCOORD_0"), std::string::npos);
  EXPECT_TRUE(exported == replayed_animation(dir));
}

TEST(EditorSessions, PlaybackRedrawsHandleColoursWhenTheHandlesChange) {
  const std::string dir = primo::test::temp_dir();
  Editor e;
  open_bar(e, dir);
  e.sessions.start_recording(e);
  Document* d = e.document();
  for (int k = 0; k < 5; ++k) e.update(0.016);
  add_handle(d->state, *d->topology, d->topology->rest_points, faces_with(*d, -1, 0.05), HandleMode::Fixed);
  e.commit("fixed");
  for (int k = 0; k < 5; ++k) e.update(0.016);
  e.sessions.save(e, dir + "/s.session.json");

  e.adopt(make_document(load_mesh(dir + "/bar.obj"), dir + "/bar.obj"));
  e.update(0.016);
  e.sessions.open_playback(e, dir + "/s.session.json");
  ASSERT_TRUE(e.sessions.has_playback());
  d = e.document();
  e.sessions.play(e);
  e.take_overlay_changed();
  bool redrawn = false;
  for (int i = 0; i < 100 && d->state.handles.empty(); ++i) {
    e.update(0.016);
    if (!d->state.handles.empty()) redrawn = e.take_overlay_changed();
    else e.take_overlay_changed();
  }
  ASSERT_EQ(d->state.handles.size(), 1u);
  EXPECT_TRUE(redrawn) << "the new handle's colour is drawn in the frame it appears";
}

TEST(EditorSessions, TrivialSessionErrorsAreStatusMessagesWithoutAPopup) {
  // Each is said in red in the status bar and counted as an error (a script stops on it), and
  // none opens a popup to dismiss: the next click fixes it, and no work is lost.
  const std::string dir = primo::test::temp_dir();
  Editor empty;
  empty.sessions.start_recording(empty);  // no mesh
  empty.sessions.open_playback(empty, dir + "/any.session.json");
  empty.sessions.export_animation(empty, dir + "/any.glb");
  EXPECT_EQ(empty.error_count(), 3u);
  EXPECT_TRUE(empty.take_error_popup().empty());
  ASSERT_NE(empty.current_message(), nullptr);
  EXPECT_TRUE(empty.current_message()->error);

  Editor e;
  open_bar(e, dir);
  e.sessions.save(e, dir + "/none.session.json");  // nothing recorded
  e.sessions.export_animation(e, dir + "/none.glb");  // no session
  std::ofstream(dir + "/broken.session.json") << "{ not json";
  e.sessions.open_playback(e, dir + "/broken.session.json");
  EXPECT_EQ(e.error_count(), 3u);
  EXPECT_TRUE(e.take_error_popup().empty());
  EXPECT_NE(e.messages().back().text.find("broken.session.json"), std::string::npos)
      << "names the file: " << e.messages().back().text;

  // Saving a recording that cannot be written would lose it: that one asks to be read.
  e.sessions.start_recording(e);
  e.update(0.016);
  e.sessions.save(e, dir + "/no such folder/s.session.json");
  EXPECT_EQ(e.error_count(), 4u);
  EXPECT_FALSE(e.take_error_popup().empty());
}
