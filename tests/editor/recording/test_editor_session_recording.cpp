// Recording a posing session from the editor's document (docs/sessions.md): edits, and undo
// and redo read from the document's history, become the session's events. The session module
// itself is tested without the editor in test_session_*.cpp.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "recording/document_recorder.h"
#include "document/paint.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/sessions/session.h"
#include "recording/session_bridge.h"

using namespace primo;
using namespace primo::editor;

namespace {

std::vector<int> faces_with(const Document& doc, double y_min, double y_max) {
  std::vector<int> out;
  for (auto f : doc.mesh->faces()) {
    Vec3 c = Vec3::Zero();
    int n = 0;
    for (auto v : doc.mesh->fv_range(f)) c += doc.mesh->point(v), ++n;
    c /= n;
    if (c.y() >= y_min && c.y() <= y_max) out.push_back(f.idx());
  }
  return out;
}

// A bar posed the way a user would: a fixed base, a handle on top dragged over 12 frames and
// rotated, a stroke of softer joints, a prism setting change, then an undo and a redo.
struct Recorded {
  std::unique_ptr<Document> doc;
  Session session;
};

Recorded record_bar_session(const std::string& mesh_path) {
  Recorded r;
  r.doc = make_document(make_bar(0.2, 1.0, 2, 10), mesh_path);
  Document& doc = *r.doc;
  DocumentRecorder rec;
  double t = 0.0;
  rec.start(doc, t);
  auto frame = [&] { t += 1.0 / 60.0; rec.observe(doc, t); };
  frame();  // nothing changed: no event
  add_handle(doc.state, *doc.topology, doc.topology->rest_points, faces_with(doc, -1.0, 0.05), HandleMode::Fixed);
  doc.commit("fixed");
  frame();
  const int top = add_handle(doc.state, *doc.topology, doc.topology->rest_points,
                             faces_with(doc, 0.95, 2.0), HandleMode::Pose);
  doc.commit("handle");
  frame();
  for (int k = 1; k <= 12; ++k) {
    doc.state.handles[size_t(top)].pose.translate = Vec3(0.02 * k, 0.0, 0.01 * k);
    doc.state.handles[size_t(top)].pose.rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.03 * k, Vec3::UnitZ()));
    frame();
  }
  doc.commit("drag");
  doc.state.height_factor = paint_factors(doc.state.height_factor, doc.n_faces(), faces_with(doc, 0.4, 0.6), 0.5);
  doc.commit("paint");
  frame();
  doc.state.prisms.width = 0.9;
  doc.commit("width");
  frame();
  doc.state = doc.history.undo();
  frame();
  doc.state = doc.history.redo();
  frame();
  r.session = rec.stop(doc, t);
  return r;
}

}  // namespace

TEST(SessionFile, RecorderTurnsEditsIntoEvents) {
  const Recorded r = record_bar_session("bar.obj");
  std::vector<std::string> types;
  for (const SessionEvent& e : r.session.events) types.push_back(event_type_name(e.type));
  const std::vector<std::string> expected = {
      "handles", "handles", "targets", "targets", "targets", "targets", "targets", "targets",
      "targets", "targets", "targets", "targets", "targets", "targets", "factors", "prisms",
      "undo",    "prisms",  "redo",    "prisms"};
  EXPECT_EQ(types, expected);
  // Targets carry only the handle that moved, one event per frame, with times and frames.
  EXPECT_EQ(r.session.events[2].poses.size(), 1u);
  EXPECT_EQ(r.session.events[2].poses[0].handle, 1);
  EXPECT_EQ(r.session.events[0].frame, 1);
  EXPECT_EQ(r.session.events[3].frame, r.session.events[2].frame + 1);
  EXPECT_GT(r.session.events.back().t, r.session.events.front().t);
  // Replaying the events on the initial state gives the editor's final state exactly (but for
  // the selection, which sessions do not record).
  EXPECT_TRUE(validate_session(r.session, r.doc->n_faces()) == session_state(r.doc->state));
}


TEST(SessionBridge, EditStatesComeBackFromSessionStatesAsTheyWere) {
  // Every handle mode, a pose, a spring's stiffness, painted factors and prisms in the
  // format's unit: through the session's types and back, nothing the solver sees changes.
  const std::unique_ptr<Document> doc = make_document(make_bar(0.2, 1.0, 2, 10), "bar.obj");
  EditState& s = doc->state;
  const std::vector<HandleMode> modes = {HandleMode::Pose, HandleMode::Position,
                                         HandleMode::Orientation, HandleMode::Spring,
                                         HandleMode::Fixed};
  for (size_t i = 0; i < modes.size(); ++i)
    add_handle(s, *doc->topology, doc->topology->rest_points, {int(2 * i), int(2 * i + 1)}, modes[i]);
  s.handles[0].pose.translate = Vec3(0.1, 0.2, 0.3);
  s.handles[0].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vec3::UnitX()));
  s.handles[3].stiffness = 2.5;
  s.prisms.height = 1.5;
  s.prisms.height_unit = HeightUnit::MeanEdgeLength;
  s.prisms.width = 0.8;
  s.prisms.normal_blend = 0.3;
  s.width_factor = paint_factors(s.width_factor, doc->n_faces(), {12, 13}, 1.5);

  const SessionState session = session_state(s);
  ASSERT_EQ(session.handles.size(), modes.size());
  for (size_t i = 0; i < modes.size(); ++i) EXPECT_EQ(handle_mode(session.handles[i].mode), modes[i]);
  EditState back = initial_edit_state(doc->n_faces());
  set_session_state(back, session, doc->topology->rest_geometry);
  EXPECT_TRUE(back == s);
  for (size_t i = 0; i < modes.size(); ++i) EXPECT_EQ(back.handles[i].color, s.handles[i].color);
  EXPECT_TRUE(session_state(back) == session);
}
