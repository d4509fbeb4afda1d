// Unsaved work in the editor: what counts as a change, asking before it is discarded (open,
// quit), autosave and recovery, and the recent-files list (docs/editor.md, "Files").

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "user_files/autosave.h"
#include "editor.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/scenario/scenario.h"
#include "primo/util/utf8.h"
#include "user_files/recent_files.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;
namespace fs = std::filesystem;

namespace {

bool settle(Editor& e) {
  for (int i = 0; i < 3000; ++i) {
    e.update(0.016);
    if (e.settled() && !e.file_task_running()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// A bar on disk, opened, with a fixed region and a moved handle: unsaved work.
struct Posed {
  explicit Posed(const std::string& name = "bar.obj") : mesh(dir + "/" + name) { pose(); }
  std::string dir = test::temp_dir();
  std::string mesh;
  std::string other = dir + "/other.obj";
  Editor e;
  void pose() {
    save_mesh(make_bar(0.2, 1.0, 2, 10), mesh);
    save_mesh(make_bar(0.2, 1.0, 2, 12), other);
    e.set_autosave_interval(0.0);
    e.open(mesh);
    EXPECT_TRUE(settle(e));
    Document& d = *e.document();
    const MeshTopology& t = *d.topology;
    std::vector<int> bottom, top;
    for (int f = 0; f < t.n_faces; ++f) {
      const double y = t.rest_geometry.centroid[f].y();
      if (y < 0.1) bottom.push_back(f);
      if (y > 0.9) top.push_back(f);
    }
    add_handle(d.state, t, t.rest_points, bottom, HandleMode::Fixed);
    const int h = add_handle(d.state, t, t.rest_points, top, HandleMode::Pose);
    d.state.handles[size_t(h)].pose.translate = Vec3(0.2, 0.0, 0.0);
    e.commit("pose");
    EXPECT_TRUE(settle(e));
  }
};

}  // namespace

TEST(EditorUnsavedWork, EditsCountAndSelectionDoesNot) {
  Posed p;
  EXPECT_TRUE(p.e.has_unsaved_changes());
  ASSERT_TRUE(p.e.save_scenario(p.dir + "/pose.json"));
  EXPECT_FALSE(p.e.has_unsaved_changes());
  p.e.select_all();
  EXPECT_FALSE(p.e.has_unsaved_changes()) << "selecting is not work to lose";
  p.e.document()->state.prisms.width = 0.9;
  p.e.commit("width");
  EXPECT_TRUE(p.e.has_unsaved_changes());
}

TEST(EditorUnsavedWork, OpeningAnotherFileAsksFirst) {
  Posed p;
  p.e.request_open(p.other);
  ASSERT_TRUE(p.e.discard_question().has_value());
  EXPECT_EQ(p.e.discard_question()->then, Editor::DiscardQuestion::Then::Open);
  // Cancel: nothing happens, the work stays.
  p.e.answer_discard(Editor::DiscardAnswer::Cancel);
  ASSERT_TRUE(settle(p.e));
  EXPECT_FALSE(p.e.discard_question().has_value());
  EXPECT_EQ(p.e.document()->mesh_path, p.mesh);
  EXPECT_EQ(p.e.document()->state.handles.size(), 2u);
  // Save: the scenario is written (with the pose), then the other file opens.
  p.e.request_open(p.other);
  p.e.answer_discard(Editor::DiscardAnswer::Save, p.dir + "/kept.json");
  ASSERT_TRUE(settle(p.e));
  EXPECT_EQ(p.e.document()->mesh_path, p.other);
  const Scenario kept = load_scenario(p.dir + "/kept.json");
  EXPECT_EQ(kept.handles.size(), 2u);
  EXPECT_TRUE(kept.solved_state.has_value());
  // Nothing unsaved: opens at once.
  p.e.request_open(p.mesh);
  EXPECT_FALSE(p.e.discard_question().has_value());
  ASSERT_TRUE(settle(p.e));
  EXPECT_EQ(p.e.document()->mesh_path, p.mesh);
}

TEST(EditorUnsavedWork, QuittingAsksFirstAndDiscardQuits) {
  Posed p;
  EXPECT_FALSE(p.e.ask_to_quit());
  ASSERT_TRUE(p.e.discard_question().has_value());
  EXPECT_EQ(p.e.discard_question()->then, Editor::DiscardQuestion::Then::Quit);
  EXPECT_FALSE(p.e.quit_requested());
  // A save that fails (no such folder) keeps the question: the work is not safe yet.
  p.e.answer_discard(Editor::DiscardAnswer::Save, p.dir + "/missing/x.json");
  EXPECT_TRUE(p.e.discard_question().has_value());
  EXPECT_FALSE(p.e.quit_requested());
  p.e.answer_discard(Editor::DiscardAnswer::Discard);
  EXPECT_TRUE(p.e.quit_requested());
}

TEST(EditorUnsavedWork, AutosaveKeepsTheWorkAndRecoveryBringsItBack) {
  std::vector<Vec3> shown;
  std::string autosaved;
  {
    Posed p;
    shown = p.e.positions();
    p.e.set_autosave_interval(60.0);
    for (int i = 0; i < 80; ++i) p.e.update(1.0);  // 80 s of editor time: one autosave at least
    autosaved = autosave_path(p.mesh);
    ASSERT_TRUE(fs::exists(autosaved));
    const Scenario s = load_scenario(autosaved);
    EXPECT_EQ(s.handles.size(), 2u);
    EXPECT_TRUE(s.solved_state.has_value());
    ASSERT_EQ(list_autosaved_work().size(), 1u);
    // The editor goes away without saving, as after a crash: the file stays.
  }
  ASSERT_TRUE(fs::exists(autosaved));
  Editor next;
  next.set_autosave_interval(0.0);
  next.recover(list_autosaved_work().front().path);
  ASSERT_TRUE(settle(next));
  ASSERT_NE(next.document(), nullptr);
  EXPECT_EQ(next.document()->state.handles.size(), 2u);
  EXPECT_TRUE(next.document()->scenario_path.empty()) << "Save must ask where";
  EXPECT_TRUE(next.has_unsaved_changes());
  double apart = 0.0;
  for (size_t v = 0; v < shown.size(); ++v) apart = std::max(apart, (next.positions()[v] - shown[v]).norm());
  EXPECT_LT(apart, 1e-9);
  // Saving it for real removes the autosave.
  ASSERT_TRUE(next.save_scenario(fs::path(autosaved).parent_path().parent_path().string() + "/saved.json"));
  EXPECT_FALSE(fs::exists(autosaved));
  EXPECT_TRUE(list_autosaved_work().empty());
}

TEST(EditorUnsavedWork, AMeshWhoseNameIsNotUtf8IsAutosavedThroughALinkAndRecovered) {
  // A Linux file name is bytes, a JSON string text: the autosave named such a mesh and failed
  // with a raw JSON error, so the work it was there to keep was not kept.
  const std::string name = "caf\xE9-\xFF.obj";
  std::vector<Vec3> shown;
  std::string autosaved, mesh;
  {
    Posed p(name);
    mesh = p.mesh;
    shown = p.e.positions();
    ASSERT_TRUE(p.e.autosave_now());
    autosaved = autosave_path(p.mesh);
    EXPECT_EQ(fs::path(autosaved).filename().string().rfind("caf%E9-%FF-", 0), 0u) << autosaved;
    const Scenario s = load_scenario(autosaved);  // valid JSON, naming a link to the mesh
    EXPECT_TRUE(is_valid_utf8(s.mesh));
    EXPECT_TRUE(fs::is_symlink(s.mesh_path));
    EXPECT_TRUE(fs::equivalent(s.mesh_path, p.mesh));
    // Saving it as a scenario says why it cannot, in words, and keeps the work unsaved.
    EXPECT_FALSE(p.e.save_scenario(p.dir + "/pose.json"));
    ASSERT_FALSE(p.e.messages().empty());
    EXPECT_NE(p.e.messages().back().text.find("caf%E9-%FF.obj\" is not UTF-8"), std::string::npos)
        << p.e.messages().back().text;
    EXPECT_TRUE(p.e.has_unsaved_changes());
    // The recent files keep what JSON can hold.
    EXPECT_TRUE(p.e.recent_files().entries().size() >= 1);
  }
  Editor next;
  next.set_autosave_interval(0.0);
  next.recover(autosaved);
  ASSERT_TRUE(settle(next));
  ASSERT_NE(next.document(), nullptr);
  EXPECT_EQ(next.document()->mesh_path, fs::absolute(mesh).string()) << "the mesh, not the link";
  double apart = 0.0;
  for (size_t v = 0; v < shown.size(); ++v) apart = std::max(apart, (next.positions()[v] - shown[v]).norm());
  EXPECT_LT(apart, 1e-9);
  // Leaving the work removes the autosave and its link.
  remove_autosave(autosaved);
  EXPECT_FALSE(fs::exists(autosaved));
  for (const auto& entry : fs::directory_iterator(fs::path(autosaved).parent_path()))
    EXPECT_FALSE(entry.is_symlink()) << entry.path();
}

static bool a_name_not_utf8_stays_out_of_the_file(const std::string& list, const std::string& dir) {
  {
    RecentFiles r(list);
    if (!r.add(dir + "/caf\xE9.obj") || r.entries().front() != dir + "/caf\xE9.obj") return false;
  }
  const RecentFiles again(list);
  return again.entries().size() == RecentFiles::kMaxEntries - 1 &&
         again.entries().front() == dir + "/m5.obj";
}

TEST(EditorUnsavedWork, RecentFilesAreNewestFirstUniqueAndBounded) {
  const std::string dir = test::temp_dir();
  const std::string list = dir + "/recent.json";
  {
    RecentFiles r(list);
    EXPECT_TRUE(r.entries().empty());  // no file yet
    for (int i = 0; i < 12; ++i) ASSERT_TRUE(r.add(dir + "/m" + std::to_string(i) + ".obj"));
    ASSERT_TRUE(r.add(dir + "/m5.obj"));
  }
  RecentFiles again(list);
  ASSERT_EQ(again.entries().size(), RecentFiles::kMaxEntries);
  EXPECT_EQ(again.entries()[0], dir + "/m5.obj");
  EXPECT_EQ(again.entries()[1], dir + "/m11.obj");
  EXPECT_EQ(std::count(again.entries().begin(), again.entries().end(), dir + "/m5.obj"), 1);
  // A name that is not UTF-8 stays out of the file (JSON holds text) and the rest is kept.
  ASSERT_TRUE(a_name_not_utf8_stays_out_of_the_file(list, dir));
  // A broken list is an empty one, not an error.
  test::write_text(list, "{not json");
  EXPECT_TRUE(RecentFiles(list).entries().empty());
  // So is a named pipe in its place, which must not hold the editor's start.
  fs::remove(list);
  ASSERT_EQ(0, ::mkfifo(list.c_str(), 0600));
  EXPECT_TRUE(RecentFiles(list).entries().empty());
  fs::remove(list);
  // The editor adds what it opens and saves.
  Posed p;
  ASSERT_TRUE(p.e.save_scenario(p.dir + "/pose.json"));
  const auto& entries = p.e.recent_files().entries();
  ASSERT_GE(entries.size(), 2u);
  EXPECT_EQ(fs::path(entries[0]).filename(), "pose.json");
  EXPECT_EQ(fs::path(entries[1]).filename(), "bar.obj");
}

TEST(EditorPreferences, AreKeptBetweenRunsAndAppliedAtStart) {
  const std::string file = preferences_path();  // in this test process's own config folder
  Preferences p;
  EXPECT_TRUE(p.grid) << "the ground grid is on by default";
  p.wireframe = true;
  p.grid = false;
  p.brush_radius = 55.0;
  p.paint_falloff = Falloff::Smooth;
  p.autosave_minutes = 5.0;
  p.tolerance = 1e-6;
  ASSERT_TRUE(save_preferences(p));
  const Preferences back = load_preferences();
  EXPECT_TRUE(back.wireframe);
  EXPECT_FALSE(back.grid);
  EXPECT_EQ(back.brush_radius, 55.0);
  EXPECT_EQ(back.paint_falloff, Falloff::Smooth);
  EXPECT_EQ(back.tolerance, 1e-6);
  // A new editor starts with them; a mesh opened without a scenario settles to that tolerance.
  Editor e;
  EXPECT_TRUE(e.display.wireframe);
  EXPECT_FALSE(e.display.grid);
  EXPECT_EQ(e.tools.brush_radius, 55.0);
  EXPECT_EQ(e.tools.paint_falloff, Falloff::Smooth);
  const std::string dir = test::temp_dir();
  save_mesh(make_bar(0.2, 1.0, 2, 6), dir + "/bar.obj");
  e.open(dir + "/bar.obj");
  ASSERT_TRUE(settle(e));
  EXPECT_EQ(e.document()->solver.tolerance, 1e-6);
  // Broken or out-of-range files give defaults or clamped values, never a failure.
  test::write_text(file, R"({"brush_radius": 1e9, "smooth": "yes", "tolerance": -1})");
  const Preferences odd = load_preferences();
  EXPECT_EQ(odd.brush_radius, 200.0);
  EXPECT_TRUE(odd.smooth);
  EXPECT_EQ(odd.tolerance, 1e-14);
  test::write_text(file, "{broken");
  EXPECT_EQ(load_preferences().brush_radius, Preferences{}.brush_radius);
  fs::remove(file);
}

TEST(EditorUnsavedWork, TheAutosaveAtExitKeepsThePoseTheSolveReached) {
  // SIGTERM right after an edit: the autosave has the solved state of that edit, not none and
  // not the one of the edit before.
  Posed p;
  ASSERT_TRUE(settle(p.e));
  Document& d = *p.e.document();
  d.state.handles[1].pose.translate = Vec3(0.5, 0.0, 0.0);
  p.e.commit("pose again");
  ASSERT_TRUE(p.e.autosave_before_exit());
  const Scenario s = load_scenario(autosave_path(p.mesh));
  ASSERT_TRUE(s.solved_state.has_value());
  // The top's faces are held by the handle: their motion is its translation.
  const int top_face = (*d.state.handles[1].faces)[0];
  EXPECT_LT((s.solved_state->face_motions[size_t(top_face)].translation - Vec3(0.5, 0, 0)).norm(), 1e-9);
  remove_autosave(autosave_path(p.mesh));
}
