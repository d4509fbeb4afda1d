// Session files (docs/sessions.md), without the editor: recording states into events, the
// file round trip, validation errors naming the event, and the shipped session.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "primo/util/error.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_mapping.h"
#include "support/session_support.h"
#include "support/test_support.h"

using namespace primo;
using primo::test::record_bar_session;
using primo::test::RecordedSession;

namespace {

using primo::test::error_of;

}  // namespace

TEST(SessionFile, RecorderTurnsStatesIntoEvents) {
  const RecordedSession r = record_bar_session("bar.obj");
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
  // Replaying the events on the initial state gives the last recorded state exactly.
  EXPECT_TRUE(validate_session(r.session, int(r.mesh.n_faces())) == r.final_state);
}

TEST(SessionFile, RoundTripIsExact) {
  const RecordedSession r = record_bar_session("bar.obj");
  const std::string dir = primo::test::temp_dir();
  const std::string text = session_to_json(r.session, dir + "/a.session.json");
  const Session back = parse_session(text, dir + "/a.session.json");
  EXPECT_EQ(session_to_json(back, dir + "/a.session.json"), text);
  ASSERT_EQ(back.events.size(), r.session.events.size());
  EXPECT_TRUE(validate_session(back, int(r.mesh.n_faces())) == r.final_state);
  EXPECT_NE(text.find("\"format\": \"primo-session/1\""), std::string::npos);
}

TEST(SessionFile, PrismsKeepTheirHeightUnit) {
  const RecordedSession r = record_bar_session("bar.obj");
  const std::string text = session_to_json(r.session, "");
  // The editor's default material is written as half_thickness (a fraction of the diagonal).
  ASSERT_NE(text.find("\"half_thickness\""), std::string::npos);
  // A session of the format's height in mean edge lengths reads back in that unit.
  std::string legacy = text;
  for (size_t at; (at = legacy.find("\"half_thickness\"")) != std::string::npos;)
    legacy.replace(at, 16, "\"height\"");
  const Session back = parse_session(legacy, "s.json");
  EXPECT_EQ(back.initial.prisms.height_unit, HeightUnit::MeanEdgeLength);
  EXPECT_EQ(back.initial.prisms.height, r.session.initial.prisms.height);
  // Both keys at once are an error naming where.
  std::string both = text;
  both.insert(both.find("\"half_thickness\""), "\"height\": 1, ");
  EXPECT_NE(error_of([&] { parse_session(both, "s.json"); }).find("exactly one of"), std::string::npos);
}

TEST(SessionFile, AcceptsEveryMaterialTheEditorCanMake) {
  // The Shell/plate slider goes below 0 (detail enhancement) and the thickness slider to 0
  // (a membrane): a session recorded with those loads and validates, as a scenario would.
  RecordedSession r = record_bar_session("bar.obj");
  r.session.initial.prisms.normal_blend = -0.47;
  r.session.initial.prisms.height = 0.0;
  for (SessionEvent& event : r.session.events)
    if (event.type == SessionEvent::Type::Prisms) event.prisms.normal_blend = 1.4;
  const std::string text = session_to_json(r.session, "");
  const Session back = parse_session(text, "s.json");
  EXPECT_EQ(back.initial.prisms.normal_blend, -0.47);
  EXPECT_NO_THROW(validate_session(back, int(r.mesh.n_faces())));
  // Out of every range still is an error naming the key.
  Session negative = r.session;
  negative.initial.prisms.width = -1.0;
  const std::string bad = session_to_json(negative, "");
  EXPECT_NE(error_of([&] { parse_session(bad, "s.json"); }).find("width: must be positive"),
            std::string::npos);
}

TEST(SessionFile, ErrorsNameTheEvent) {
  const RecordedSession r = record_bar_session("bar.obj");
  const std::string text = session_to_json(r.session, "");
  const int n = int(r.mesh.n_faces());
  auto parse_error = [&](const std::string& t) { return error_of([&] { parse_session(t, "s.json"); }); };
  // An unknown key in event 3 (a targets event).
  std::string bad = text;
  const size_t p3 = bad.find("\"type\":\"targets\"", bad.find("\"type\":\"targets\"") + 1);
  bad.insert(p3, "\"speed\":1,");
  EXPECT_EQ(parse_error(bad), "s.json: events[3] (targets): speed: unknown key");
  // A truncated file names the event it stops in.
  const size_t cut = text.find("\"type\":\"factors\"") + 30;
  const std::string truncated = parse_error(text.substr(0, cut));
  EXPECT_NE(truncated.find("s.json: events[14] (factors): the file ends early"), std::string::npos) << truncated;
  // An unknown event type.
  std::string unknown = text;
  unknown.replace(unknown.find("\"type\":\"prisms\""), 15, "\"type\":\"prismz\"");
  EXPECT_NE(parse_error(unknown).find("events[15] (prismz): type: unknown event type"), std::string::npos);
  // A bad quaternion.
  Session s = r.session;
  std::string q = session_to_json(s, "");
  const size_t rot = q.find("\"rotation\":[", q.find("\"type\":\"targets\""));
  q.replace(rot + 12, q.find(',', rot) - rot - 12, "2");
  EXPECT_NE(parse_error(q).find("events[3] (targets): poses[0].rotation: not a unit quaternion"), std::string::npos)
      << parse_error(q);
  // Events that parse but do not fit the state or the mesh.
  s.events[5].poses[0].handle = 7;
  EXPECT_EQ(error_of([&] { validate_session(s, n); }),
            "session: events[5] (targets): poses[0].handle: no handle 7 (there are 2)");
  s = r.session;
  s.events[14].faces[0] = n + 3;
  EXPECT_NE(error_of([&] { validate_session(s, n); }).find("events[14] (factors): faces[0]: face "),
            std::string::npos);
  s = r.session;
  s.events[1].handles[1].faces = s.events[1].handles[0].faces;
  EXPECT_NE(error_of([&] { validate_session(s, n); }).find("events[1] (handles): handles[1].faces: face"),
            std::string::npos);
  EXPECT_NE(parse_error("{\"format\": \"primo-session/2\"}").find("format"), std::string::npos);
}

TEST(SessionFile, ShippedSessionIsValid) {
  const Session s = load_session(primo::test::source_path("assets/sessions/spot-pose.session.json"));
  const Mesh mesh = load_mesh(s.mesh_path);
  const SessionState end = validate_session(s, int(mesh.n_faces()));
  EXPECT_EQ(end.handles.size(), 3u);
  EXPECT_GT(s.events.size(), 20u);
  bool undo = false, redo = false;
  for (const SessionEvent& ev : s.events)
    undo = undo || ev.type == SessionEvent::Type::Undo, redo = redo || ev.type == SessionEvent::Type::Redo;
  EXPECT_TRUE(undo && redo);
}

namespace {

// The recorded bar session with a falloff on its top handle from the first handles event that
// has it: the free faces just below the top, weights falling away from it.
Session with_falloff(const RecordedSession& r) {
  Session s = r.session;
  SessionEvent& e = s.events[1];
  std::vector<bool> taken(r.mesh.n_faces(), false);
  for (const SessionHandle& h : e.handles)
    for (int f : *h.faces) taken[size_t(f)] = true;
  auto falloff = std::make_shared<SessionFalloff>();
  falloff->radius = 0.25;
  for (int f = int(r.mesh.n_faces()) - 1; f >= 0 && falloff->faces.size() < 6; --f)
    if (!taken[size_t(f)]) falloff->faces.insert(falloff->faces.begin(), f);
  for (size_t i = 0; i < falloff->faces.size(); ++i) falloff->weights.push_back(0.25 + 0.125 * double(i));
  for (size_t i = 1; i < s.events.size(); ++i)
    if (s.events[i].type == SessionEvent::Type::Handles) s.events[i].handles[1].falloff = falloff;
  return s;
}

}  // namespace

TEST(SessionFile, AFalloffRoundTripsAndItsReplayPullsTheFreeFaces) {
  const RecordedSession r = record_bar_session("bar.obj");
  const Session s = with_falloff(r);
  const std::string text = session_to_json(s, "");
  EXPECT_NE(text.find("\"falloff\":{\"faces\":["), std::string::npos);
  const Session back = parse_session(text, "s.json");
  EXPECT_EQ(session_to_json(back, ""), text);
  const SessionState end = validate_session(back, int(r.mesh.n_faces()));
  ASSERT_TRUE(end.handles[1].falloff);
  EXPECT_TRUE(*end.handles[1].falloff == *s.events[1].handles[1].falloff);
  EXPECT_FALSE(end == validate_session(r.session, int(r.mesh.n_faces())));
  // One spring a falloff face, after the handles' own forces.
  const SessionSolverInputs in = solver_inputs(end, compute_face_geometry(r.mesh));
  ASSERT_EQ(in.forces.size(), end.handles[1].falloff->faces.size());
  EXPECT_EQ(in.forces[0].name, end.handles[1].name + " falloff");
  EXPECT_EQ(in.forces[0].faces, std::vector<int>{end.handles[1].falloff->faces[0]});
}

TEST(SessionFile, BadFalloffsAreRefusedNamingWhere) {
  const RecordedSession r = record_bar_session("bar.obj");
  const int n = int(r.mesh.n_faces());
  const Session good = with_falloff(r);
  const std::string where = "s.json: events[1] (handles): handles[1].falloff.";
  auto written = [&](const std::function<void(SessionFalloff&)>& change) {
    Session s = good;
    auto f = std::make_shared<SessionFalloff>(*s.events[1].handles[1].falloff);
    change(*f);
    s.events[1].handles[1].falloff = f;
    return session_to_json(s, "");
  };
  auto parse_error = [&](const std::string& t) { return error_of([&] { parse_session(t, "s.json"); }); };
  auto validate_error = [&](const std::string& t) {
    return error_of([&] { validate_session(parse_session(t, "s.json"), n); });
  };
  EXPECT_EQ(parse_error(written([](SessionFalloff& f) { f.weights[2] = 0.0; })),
            where + "weights[2]: must be in (0, 1]");
  EXPECT_EQ(parse_error(written([](SessionFalloff& f) { f.weights[0] = 1.5; })),
            where + "weights[0]: must be in (0, 1]");
  EXPECT_EQ(parse_error(written([](SessionFalloff& f) { f.weights[1] = std::nan(""); })),
            where + "weights[1]: expected a number");
  EXPECT_EQ(parse_error(written([](SessionFalloff& f) { f.weights.pop_back(); })),
            where + "weights: must have as many entries as faces");
  EXPECT_EQ(parse_error(written([](SessionFalloff& f) { f.radius = -0.5; })),
            where + "radius: must not be negative");
  EXPECT_EQ(parse_error(written([](SessionFalloff& f) { f.radius = std::numeric_limits<double>::infinity(); })),
            where + "radius: expected a number");
  std::string unknown = written([](SessionFalloff&) {});
  unknown.insert(unknown.find("\"falloff\":{") + 11, "\"shape\":\"smooth\",");
  EXPECT_EQ(parse_error(unknown), where + "shape: unknown key");
  EXPECT_NE(validate_error(written([n](SessionFalloff& f) { f.faces[3] = n + 2; }))
                .find(where + "faces[3]: face " + std::to_string(n + 2) + " out of range"),
            std::string::npos);
  EXPECT_EQ(validate_error(written([](SessionFalloff& f) { f.faces[1] = f.faces[0]; })),
            where + "faces[1]: faces must be sorted and distinct");
  const int own = good.events[1].handles[1].faces->front();
  EXPECT_EQ(validate_error(written([&](SessionFalloff& f) { f.faces = {own}, f.weights = {1.0}; })),
            where + "faces[0]: face " + std::to_string(own) + " is one of the handle's own faces");
}

TEST(SessionFile, AFalloffIsCarriedToAFinerMeshWithItsWeights) {
  // `primo replay --mesh`: each coarse falloff face's weight goes to its fine faces.
  const RecordedSession r = record_bar_session("bar.obj");
  const Session coarse = with_falloff(r);
  const Mesh fine = make_bar(0.2, 1.0, 4, 20);
  const Session mapped = map_session_to_mesh(coarse, r.mesh, fine);
  const SessionState end = validate_session(mapped, int(fine.n_faces()));
  ASSERT_TRUE(end.handles[1].falloff);
  const SessionFalloff& was = *coarse.events[1].handles[1].falloff;
  const SessionFalloff& now = *end.handles[1].falloff;
  EXPECT_EQ(now.radius, was.radius);
  EXPECT_EQ(now.faces.size(), 4 * was.faces.size()) << "each quad of the bar splits in four";
  for (double w : now.weights)
    EXPECT_NE(std::find(was.weights.begin(), was.weights.end(), w), was.weights.end()) << w;
}

TEST(SessionFile, ASessionWithoutFalloffsIsWrittenAsBefore) {
  // The shipped session, read and written again, is the same bytes: a file without a falloff
  // names no new key, so every PriMo that reads primo-session/1 reads it.
  const std::string path = primo::test::source_path("assets/sessions/spot-pose.session.json");
  const std::string text = session_to_json(load_session(path), path);
  EXPECT_EQ(text, primo::test::read_text(path));
  EXPECT_EQ(text.find("falloff"), std::string::npos);
}
