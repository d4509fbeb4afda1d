// Editor scripts: parsing with line numbers, and the events a player emits frame by frame.

#include <gtest/gtest.h>

#include <cstdio>

#include "primo/util/error.h"
#include "input/script.h"

using namespace primo;
using namespace primo::editor;

namespace {

struct Host : ScriptHost {
  std::vector<InputEvent> events;
  std::vector<std::string> ran;
  bool is_settled = false;
  double cx = 0, cy = 0;
  void push_input(const InputEvent& e) override {
    events.push_back(e);
    if (e.type == InputEvent::Type::CursorMove) cx = e.x, cy = e.y;
  }
  void locate(const ScriptCommand& c, double& x, double& y) override {
    if (c.anchor == ScriptCommand::Anchor::Handle) {
      if (c.handle != "top") throw Error("no handle '" + c.handle + "'");
      x = 100 + c.x, y = 50 + c.y;
    } else {
      x = c.x, y = c.y;
    }
  }
  void cursor(double& x, double& y) override { x = cx, y = cy; }
  bool settled() override { return is_settled; }
  bool nothing_open() override { return is_empty; }
  bool is_empty = false;
  void run(const ScriptCommand& c) override { ran.push_back(c.text); }
};

}  // namespace

TEST(EditorScript, ParsesCommands) {
  const auto cmds = parse_script(
      "# a drag\nwait-settled 5\nmove @top 10 -20 over 0.5\npress left\nmove 3 4\nrelease left\n"
      "key ctrl+shift+z\nhold shift\nscreenshot out.png ui\nsave-mesh my mesh.obj\nquit\n",
      "s.txt");
  ASSERT_EQ(cmds.size(), 10u);
  EXPECT_EQ(cmds[0].kind, ScriptCommand::Kind::WaitSettled);
  EXPECT_EQ(cmds[0].seconds, 5.0);
  EXPECT_EQ(cmds[1].anchor, ScriptCommand::Anchor::Handle);
  EXPECT_EQ(cmds[1].handle, "top");
  EXPECT_EQ(cmds[1].y, -20.0);
  EXPECT_EQ(cmds[1].seconds, 0.5);
  EXPECT_EQ(cmds[5].key, GLFW_KEY_Z);
  EXPECT_EQ(cmds[5].mods, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT);
  EXPECT_TRUE(cmds[7].with_ui);
  EXPECT_EQ(cmds[8].text, "my mesh.obj");
  EXPECT_EQ(cmds[9].line, 11);
}

TEST(EditorScript, ErrorsNameTheLine) {
  try {
    parse_script("wait 1\n\nmove 1\n", "s.txt");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("s.txt:3: ", 0), 0u) << e.what();
  }
  EXPECT_THROW(parse_script("key ctrl+nosuchkey\n", "s"), Error);
  EXPECT_THROW(parse_script("press thumb\n", "s"), Error);
  EXPECT_THROW(parse_script("dance\n", "s"), Error);
  EXPECT_THROW(parse_script("hold ctrl+a\n", "s"), Error);
}

TEST(EditorScript, OneInputEventPerFrame) {
  Host host;
  ScriptPlayer p(parse_script("move 10 10\nkey ctrl+z\nclick left\nsave-scenario a.json\nquit\n", "s"));
  double t = 0;
  std::vector<size_t> per_frame;
  while (!p.finished()) {
    const size_t before = host.events.size();
    p.update(t += 0.016, host);
    per_frame.push_back(host.events.size() - before);
  }
  EXPECT_FALSE(p.failed());
  for (size_t n : per_frame) EXPECT_LE(n, 1u);
  ASSERT_EQ(host.events.size(), 1u + 4u + 2u);
  EXPECT_EQ(host.events[1].key, GLFW_KEY_LEFT_CONTROL);
  EXPECT_EQ(host.events[2].key, GLFW_KEY_Z);
  EXPECT_EQ(host.events[2].mods, GLFW_MOD_CONTROL);
  EXPECT_EQ(host.events[3].action, GLFW_RELEASE);
  EXPECT_EQ(host.events[4].key, GLFW_KEY_LEFT_CONTROL);
  EXPECT_EQ(host.events[5].action, GLFW_PRESS);
  EXPECT_EQ(host.events[6].action, GLFW_RELEASE);
  EXPECT_EQ(host.ran, (std::vector<std::string>{"a.json", ""}));
}

TEST(EditorScript, TimedMovesAndWaits) {
  Host host;
  host.cx = 0, host.cy = 50;
  ScriptPlayer p(parse_script("move @top 100 0 over 1\nwait-settled 2\necho done\n", "s"));
  p.update(0.0, host);
  p.update(0.5, host);
  EXPECT_NEAR(host.cx, 100.0, 1e-9) << "halfway from x 0 to x 200";
  p.update(1.0, host);
  EXPECT_NEAR(host.cx, 200.0, 1e-9);
  p.update(1.1, host);
  EXPECT_TRUE(host.ran.empty()) << "waiting for the solver";
  host.is_settled = true;
  p.update(1.2, host);
  EXPECT_TRUE(p.finished());
  EXPECT_EQ(host.ran, (std::vector<std::string>{"done"}));

  ScriptPlayer q(parse_script("wait-settled 1\n", "s"));
  host.is_settled = false;
  q.update(0.0, host);
  q.update(2.0, host);
  EXPECT_TRUE(q.failed());
  ScriptPlayer r(parse_script("move @nobody\n", "s"));
  r.update(0.0, host);
  EXPECT_TRUE(r.failed());
  EXPECT_NE(r.error().find("line 1"), std::string::npos);

  // After a failed open there is nothing to settle: fail at once, not after the timeout.
  ScriptPlayer s(parse_script("wait-settled 300\n", "s"));
  host.is_empty = true;
  s.update(0.0, host);
  EXPECT_TRUE(s.failed());
  EXPECT_NE(s.error().find("nothing is open"), std::string::npos) << s.error();
}

TEST(EditorScript, ReportAndWaitFile) {
  const auto cmds = parse_script("report @top 5 5\nwait-file /tmp/x 3\n", "s");
  ASSERT_EQ(cmds.size(), 2u);
  EXPECT_EQ(cmds[0].kind, ScriptCommand::Kind::Report);
  EXPECT_EQ(cmds[0].handle, "top");
  EXPECT_EQ(cmds[1].kind, ScriptCommand::Kind::WaitFile);
  EXPECT_EQ(cmds[1].seconds, 3.0);
  EXPECT_THROW(parse_script("report @top over 2\n", "s"), Error);
  EXPECT_EQ(parse_script("move \"@Handle 1\" 3 4\n", "s")[0].handle, "Handle 1");

  const std::string flag = testing::TempDir() + "/primo-script-flag";
  std::remove(flag.c_str());
  Host host;
  ScriptPlayer p(parse_script("wait-file " + flag + " 5\necho go\n", "s"));
  p.update(0.0, host);
  p.update(1.0, host);
  EXPECT_TRUE(host.ran.empty());
  FILE* f = std::fopen(flag.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fclose(f);
  p.update(2.0, host);
  EXPECT_EQ(host.ran, (std::vector<std::string>{"go"}));
  std::remove(flag.c_str());
}
