// End-to-end test of session recording under Xvfb (docs/sessions.md): `primo edit --script`
// records a posing session on a small bar (a drag, undo, redo, a second drag), saves the
// session and the editor's deformed mesh; then
//  - `primo replay` gives the editor's final mesh (1e-6 of the bbox diagonal),
//  - two replays give identical files (and identical OBJ frame sequences),
//  - opening the session in the editor and playing it back ends at the same mesh.
// Artifacts stay in <build>/tests/e2e-artifacts/session-*/.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "e2e_support.h"
#include "primo/mesh/geometry.h"
#include "primo/io/mesh_io.h"

namespace fs = std::filesystem;
using namespace primo;
using namespace primo::e2e;

TEST(SessionE2E, RecordedSessionReplaysToTheEditorsMesh) {
  const std::string dir = artifacts("session-record-replay");
  make_bar_scenario(dir);
  write_text(dir + "/record.txt", "wait-settled 60\nrecord-start\nmove @top\nwait 0.2\npress left\n"
                                  "move @top 150 30 over 1.0\nrelease left\nwait-settled 120\n"
                                  "key ctrl+z\nwait 0.2\nkey ctrl+shift+z\nwait-settled 120\n"
                                  "move @top\nwait 0.2\npress left\nmove @top -40 10 over 0.5\n"
                                  "release left\nwait-settled 120\nrecord-stop\n"
                                  "save-session " + dir + "/pose.session.json\n"
                                  "save-mesh " + dir + "/editor.obj\nquit\n");
  ASSERT_EQ(run(kPrimo + " edit " + dir + "/bar-setup.json --script " + dir + "/record.txt > " + dir +
                "/record.log 2>&1"),
            0)
      << read_text(dir + "/record.log");
  const std::string session = read_text(dir + "/pose.session.json");
  for (const char* type : {"\"targets\"", "\"undo\"", "\"redo\""})
    EXPECT_NE(session.find(type), std::string::npos) << type << " missing from the recording";

  ASSERT_EQ(run(kPrimo + " replay " + dir + "/pose.session.json -o " + dir + "/replay-a.obj --frames " +
                dir + "/frames-a --every 10 > /dev/null"),
            0);
  ASSERT_EQ(run(kPrimo + " replay " + dir + "/pose.session.json -o " + dir + "/replay-b.obj --frames " +
                dir + "/frames-b --every 10 > /dev/null"),
            0);
  EXPECT_EQ(read_text(dir + "/replay-a.obj"), read_text(dir + "/replay-b.obj"));
  size_t frames = 0;
  for (const auto& f : fs::directory_iterator(dir + "/frames-a")) {
    ++frames;
    EXPECT_EQ(read_text(f.path().string()),
              read_text(dir + "/frames-b/" + f.path().filename().string()));
  }
  EXPECT_GT(frames, 2u);

  const Mesh rest = load_mesh(dir + "/bar.obj");
  const Mesh editor = load_mesh(dir + "/editor.obj");
  const Mesh replay = load_mesh(dir + "/replay-a.obj");
  const double diagonal = bounding_box_diagonal(rest);
  EXPECT_GT(max_vertex_distance(editor, rest), 0.05 * diagonal) << "the drags moved the mesh";
  const double difference = max_vertex_distance(editor, replay);
  std::printf("editor vs primo replay: %.3g of the bbox diagonal\n", difference / diagonal);
  EXPECT_LT(difference, 1e-6 * diagonal);

  // Played back in the editor (from the setup again), the session ends at the same mesh.
  write_text(dir + "/play.txt", "wait-settled 60\nplay-session " + dir + "/pose.session.json\n"
                                "wait 8\nwait-settled 120\nsave-mesh " + dir + "/played.obj\nquit\n");
  ASSERT_EQ(run(kPrimo + " edit " + dir + "/bar-setup.json --script " + dir + "/play.txt > " + dir +
                "/play.log 2>&1"),
            0)
      << read_text(dir + "/play.log");
  const Mesh played = load_mesh(dir + "/played.obj");
  EXPECT_LT(max_vertex_distance(editor, played), 1e-6 * diagonal);
}
