// A handle's falloff (soft selection) in a recorded session: the recording keeps the faces and
// weights the editor froze, and a replay without the editor solves the springs the editor
// solved, so it ends at the editor's mesh.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "editor.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/geometry.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_replay.h"
#include "support/editor_harness.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;

namespace {

double largest_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0.0;
  for (size_t v = 0; v < a.size(); ++v) worst = std::max(worst, (a[v] - b[v]).norm());
  return worst;
}

}  // namespace

TEST(EditorSessionFalloff, ARecordedFalloffReplaysToTheEditorsMesh) {
  const std::string dir = test::temp_dir();
  Editor editor;
  const int top = harness::open_tube_with_fixed_base(editor, dir);
  Document& doc = *editor.document();
  // Tight enough that the editor's settle and the replay's agree to far below 1e-9 of the
  // diagonal wherever their paths went.
  doc.solver.tolerance = 1e-13;
  ASSERT_TRUE(harness::settle(editor));
  editor.sessions.start_recording(editor);
  editor.set_falloff_radius(top, 0.6);
  ASSERT_TRUE(doc.state.handles[size_t(top)].falloff);
  for (int k = 1; k <= 10; ++k) {
    doc.state.handles[size_t(top)].pose.translate = Vec3(0.06 * k, 0.0, 0.02 * k);
    editor.live_edit();
    editor.update(0.016);
  }
  editor.commit("pull");
  ASSERT_TRUE(harness::settle(editor));
  const std::vector<Vec3> shown = editor.positions();
  const std::string path = dir + "/soft.session.json";
  editor.sessions.save(editor, path);

  // The falloff was recorded as a handles event when it was set.
  const Session session = load_session(path);
  const auto has_falloff = [&](const SessionEvent& e) {
    return e.type == SessionEvent::Type::Handles && e.handles.size() > size_t(top) &&
           e.handles[size_t(top)].falloff;
  };
  ASSERT_TRUE(std::any_of(session.events.begin(), session.events.end(), has_falloff));
  const SessionFalloff& recorded = *std::find_if(session.events.begin(), session.events.end(),
                                                 has_falloff)->handles[size_t(top)].falloff;
  EXPECT_EQ(recorded.radius, 0.6);
  ASSERT_EQ(recorded.faces.size(), doc.state.handles[size_t(top)].falloff->size());
  for (size_t i = 0; i < recorded.faces.size(); ++i) {
    EXPECT_EQ(recorded.faces[i], (*doc.state.handles[size_t(top)].falloff)[i].face);
    EXPECT_EQ(recorded.weights[i], (*doc.state.handles[size_t(top)].falloff)[i].weight);
  }

  const Mesh mesh = load_mesh(session.mesh_path);
  const ReplayResult replayed = replay_session(session, mesh);
  ASSERT_TRUE(replayed.converged);
  const double diagonal = doc.topology->bbox_diagonal;
  const double difference = largest_distance(shown, replayed.positions);
  std::printf("editor vs replay with a falloff: %.3g of the bbox diagonal\n", difference / diagonal);
  EXPECT_LT(difference, 1e-9 * diagonal);

  // The falloff matters: the same session without it ends elsewhere.
  Session without = session;
  for (SessionEvent& e : without.events)
    for (SessionHandle& h : e.handles) h.falloff = nullptr;
  EXPECT_GT(largest_distance(shown, replay_session(without, mesh).positions), 1e-3 * diagonal);

  // Played back in the editor, the handle has its falloff again, springs and all.
  Editor player;
  harness::open_tube_with_fixed_base(player, dir);
  player.sessions.open_playback(player, path);
  ASSERT_TRUE(player.sessions.has_playback());
  player.sessions.seek(player, player.sessions.duration());
  const HandleGroup& played = player.document()->state.handles[size_t(top)];
  EXPECT_EQ(played.falloff_radius, 0.6);
  ASSERT_TRUE(played.falloff);
  EXPECT_TRUE(*played.falloff == *doc.state.handles[size_t(top)].falloff);
}
