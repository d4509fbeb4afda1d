// Faults around the commands' output (docs/reliability.md): a missing, read-only or
// special output, an output that is also an input, a full disk, SIGKILL in the middle of a
// large write and of a `replay --frames` export, two processes writing the same file. In every
// case the user's existing files stay as they were, and no partial file is left under a final
// name. The tests run as root here, where chmod does not stop writes: read-only is /proc.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "primo/util/error.h"
#include "primo/io/mesh_io.h"
#include "primo/io/output_files.h"
#include "primo/sessions/session.h"
#include "support/session_support.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using primo::test::CommandResult;
using primo::test::read_text;
using primo::test::run_primo;
using primo::test::write_text;

namespace {

const char* kCube =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

const char* kScenario = R"({"format": "primo-scenario/1", "mesh": "cube.obj",
  "handles": [{"select": {"faces": [0]}, "fix": "all"},
              {"select": {"faces": [1]}, "fix": "all", "transform": {"translate": [0.2, 0, 0]}}]})";

std::vector<std::string> entries(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

int lines(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

// Runs `primo ARGS` in the background; returns its pid.
pid_t start_primo(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv = {const_cast<char*>(PRIMO_EXECUTABLE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int null = ::open("/dev/null", O_WRONLY);
    dup2(null, 1), dup2(null, 2);
    execv(PRIMO_EXECUTABLE, argv.data());
    _exit(127);
  }
  return pid;
}

// Waits until `found()` or `seconds` pass; true when found.
template <typename F>
bool wait_for(F found, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (found()) return true;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return false;
}

bool has_entry_containing(const std::string& folder, const std::string& part) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().find(part) != std::string::npos) return true;
  return false;
}

class Faults : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = primo::test::temp_dir();
    write_text(dir + "/cube.obj", kCube);
    write_text(dir + "/s.json", kScenario);
    write_text(dir + "/existing.obj", "keep me");
  }
  CommandResult deform(const std::string& rest) {
    return run_primo("deform " + dir + "/s.json " + rest);
  }
  void expect_refused(const CommandResult& r, const std::string& part) {
    EXPECT_NE(0, r.exit_code);
    EXPECT_EQ(1, lines(r.err)) << r.err;
    EXPECT_NE(std::string::npos, r.err.find(part)) << r.err;
    EXPECT_EQ("keep me", read_text(dir + "/existing.obj"));
    EXPECT_EQ(kCube, read_text(dir + "/cube.obj"));
    EXPECT_EQ(kScenario, read_text(dir + "/s.json"));
    EXPECT_EQ((std::vector<std::string>{"cube.obj", "existing.obj", "s.json"}), entries(dir))
        << r.err;
  }
  std::string dir;
};

}  // namespace

// The stats could not be written after the mesh was: deform used to save over existing.obj and
// then delete it.
TEST_F(Faults, UnwritableStatsKeepTheExistingOutput) {
  expect_refused(deform("-o " + dir + "/existing.obj --stats " + dir + "/missing/st.json"),
                 "does not exist");
  // /proc exists but nothing can be created in it, not even by root: found only when writing.
  expect_refused(deform("-o " + dir + "/existing.obj --stats /proc/st.json"),
                 "/proc/st.json: cannot save");
}

TEST_F(Faults, OutputThatIsAnInputOrAnotherOutput) {
  const std::string o = "-o " + dir + "/existing.obj";
  expect_refused(deform(o + " --stats " + dir + "/existing.obj"), "--stats is the same file as -o");
  expect_refused(deform(o + " --stats " + dir + "/s.json"),
                 "--stats is the same file as the scenario");
  expect_refused(deform("-o " + dir + "/cube.obj"), "-o is the same file as the scenario's mesh");
  expect_refused(deform("-o " + dir + "/../" + fs::path(dir).filename().string() + "/./cube.obj"),
                 "same file");
  fs::create_symlink(dir + "/cube.obj", dir + "/alias.obj");
  const CommandResult r = deform("-o " + dir + "/alias.obj");
  EXPECT_NE(std::string::npos, r.err.find("same file as the scenario's mesh")) << r.err;
  EXPECT_EQ(kCube, read_text(dir + "/cube.obj"));
  fs::remove(dir + "/alias.obj");
}

TEST_F(Faults, FullDiskDeviceAndReadOnlyFolders) {
  // /dev/full as a target: refused before any work, and the device is left a device (root could
  // otherwise rename a regular file over it).
  expect_refused(deform("-o " + dir + "/existing.obj --stats /dev/full"), "special file");
  struct stat st;
  ASSERT_EQ(0, ::stat("/dev/full", &st));
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  expect_refused(deform("-o /proc/out.obj"), "/proc/out.obj: cannot save");
  expect_refused(deform("-o " + dir + "/cube.obj/out.obj"),
                 "does not exist");  // a file, not a folder
  expect_refused(deform("-o " + dir), "unknown output format");
}

TEST_F(Faults, FullDiskMidWrite) {
  // A write that runs out of room (RLIMIT_FSIZE, as a full disk does): the target keeps its old
  // bytes, nothing else is left, and the message names the target.
  const primo::Mesh big = primo::load_mesh(dir + "/cube.obj");
  std::string message;
  {
    const primo::test::FileSizeLimit limit(100);
    try {
      primo::StagedOutputs out;
      out.stage_mesh(dir + "/existing.obj", big);
      out.stage(dir + "/s.json", std::string(1000, 'x'));
      out.commit();
    } catch (const primo::Error& e) {
      message = e.what();
    }
  }
  EXPECT_NE(std::string::npos, message.find("cannot save")) << message;
  EXPECT_EQ("keep me", read_text(dir + "/existing.obj"));
  EXPECT_EQ((std::vector<std::string>{"cube.obj", "existing.obj", "s.json"}), entries(dir));
}

TEST_F(Faults, ARenameFailingHalfWayPutsTheEarlierTargetsBack) {
  // Three staged files; the third's target became a folder after staging, so its rename fails
  // once the first two are in place: the replaced one gets its old bytes back, the new one goes.
  std::string message;
  try {
    primo::StagedOutputs out;
    out.stage(dir + "/existing.obj", "new mesh");
    out.stage(dir + "/new.json", "{}");
    out.stage(dir + "/later.json", "{}");
    fs::create_directory(dir + "/later.json");
    out.commit();
  } catch (const primo::Error& e) {
    message = e.what();
  }
  EXPECT_NE(std::string::npos, message.find(dir + "/later.json: cannot save")) << message;
  EXPECT_NE(std::string::npos, message.find("nothing was written: " + dir + "/new.json, " + dir +
                                            "/existing.obj put back as it was"))
      << message;
  EXPECT_EQ("keep me", read_text(dir + "/existing.obj"));
  EXPECT_TRUE(fs::is_directory(dir + "/later.json"));
  EXPECT_EQ((std::vector<std::string>{"cube.obj", "existing.obj", "later.json", "s.json"}),
            entries(dir));
  // A commit that succeeds leaves no backup behind.
  fs::remove(dir + "/later.json");
  primo::StagedOutputs out;
  out.stage(dir + "/existing.obj", "new mesh");
  out.stage(dir + "/new.json", "{}");
  out.commit();
  EXPECT_EQ("new mesh", read_text(dir + "/existing.obj"));
  EXPECT_EQ((std::vector<std::string>{"cube.obj", "existing.obj", "new.json", "s.json"}),
            entries(dir));
}

TEST_F(Faults, SigkillDuringALargeWrite) {
  // A 1M-quad cylinder (88 MB of OBJ) killed while its partial file grows: the old file stays,
  // the partial is clearly named, and the next write to the target removes it.
  const pid_t pid = start_primo({"generate", "cylinder", "--segments", "1000", "--bands", "1000",
                                 "-o", dir + "/existing.obj"});
  const bool caught =
      wait_for([&] { return has_entry_containing(dir, ".existing.obj.primo-partial-"); }, 20);
  ::kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!caught || !WIFSIGNALED(status)) GTEST_SKIP() << "the write ended before it could be killed";
  EXPECT_EQ("keep me", read_text(dir + "/existing.obj"));
  EXPECT_TRUE(
      has_entry_containing(dir, ".existing.obj.primo-partial-" + std::to_string(pid) + "-"));
  ASSERT_EQ(0, deform("-o " + dir + "/existing.obj").exit_code);
  EXPECT_EQ((std::vector<std::string>{"cube.obj", "existing.obj", "s.json"}), entries(dir));
  EXPECT_EQ(8u, primo::load_mesh(dir + "/existing.obj").n_vertices());
}

TEST_F(Faults, SigkillDuringAReplayFramesExport) {
  // A session long enough to be caught exporting: the recorded bar session with 3,000 more frames.
  const primo::test::RecordedSession r = primo::test::record_bar_session(dir + "/bar.obj");
  primo::save_mesh(r.mesh, dir + "/bar.obj");
  primo::Session s = r.session;
  primo::SessionEvent e = s.events.back();
  for (int k = 1; k <= 3000; ++k) {
    primo::SessionEvent t;
    t.type = primo::SessionEvent::Type::Targets;
    t.frame = e.frame + k;
    t.t = e.t + k / 60.0;
    t.poses.push_back(
        {1, {primo::Vec3(0.0, 0.0, 0.001 * (k % 100)), Eigen::Quaterniond::Identity()}});
    s.events.push_back(t);
  }
  primo::save_session(s, dir + "/long.session.json");
  fs::create_directory(dir + "/frames");
  const pid_t pid = start_primo({"replay", dir + "/long.session.json", "-o", dir + "/existing.obj",
                                 "--frames", dir + "/frames"});
  const bool caught =
      wait_for([&] { return has_entry_containing(dir + "/frames", ".primo-replay-"); }, 30);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ::kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!caught || !WIFSIGNALED(status)) GTEST_SKIP() << "the replay ended before it could be killed";
  EXPECT_EQ("keep me", read_text(dir + "/existing.obj"));
  EXPECT_EQ((std::vector<std::string>{".primo-replay-" + std::to_string(pid)}),
            entries(dir + "/frames"));
  // The next replay into the folder removes what the killed one left.
  primo::save_session(r.session, dir + "/short.session.json");
  ASSERT_EQ(0, run_primo("replay " + dir + "/short.session.json -o " + dir +
                         "/short.obj --frames " + dir + "/frames --every 100")
                   .exit_code);
  EXPECT_EQ((std::vector<std::string>{"frame_000000.obj"}), entries(dir + "/frames"));
}

TEST_F(Faults, TwoProcessesWritingTheSameOutput) {
  ASSERT_EQ(0, deform("-o " + dir + "/alone.obj").exit_code);
  const std::string cmd =
      std::string(PRIMO_EXECUTABLE) + " deform " + dir + "/s.json -o " + dir + "/existing.obj";
  for (int round = 0; round < 3; ++round) {
    ASSERT_EQ(0, std::system(("(" + cmd + " & " + cmd + " & wait) 2>/dev/null").c_str()));
    EXPECT_EQ(read_text(dir + "/alone.obj"), read_text(dir + "/existing.obj"));
  }
  EXPECT_EQ((std::vector<std::string>{"alone.obj", "cube.obj", "existing.obj", "s.json"}),
            entries(dir));
}

TEST_F(Faults, ReplayWithUnwritableStatsKeepsTheExistingOutput) {
  const primo::test::RecordedSession r = primo::test::record_bar_session(dir + "/bar.obj");
  primo::save_mesh(r.mesh, dir + "/bar.obj");
  primo::save_session(r.session, dir + "/pose.session.json");
  for (const std::string stats : {dir + "/missing/st.json", std::string("/proc/st.json")}) {
    const CommandResult c = run_primo("replay " + dir + "/pose.session.json -o " + dir +
                                      "/existing.obj --stats " + stats);
    EXPECT_NE(0, c.exit_code);
    EXPECT_EQ(1, lines(c.err)) << c.err;
    EXPECT_EQ("keep me", read_text(dir + "/existing.obj")) << stats;
  }
  const CommandResult same =
      run_primo("replay " + dir + "/pose.session.json -o " + dir + "/bar.obj");
  EXPECT_NE(std::string::npos, same.err.find("-o is the same file as the session's mesh"))
      << same.err;
}

TEST_F(Faults, ASessionOfAHundredThousandEvents) {
  // 100,000 target events over 1,000 frames after the recorded bar session: read, checked and
  // replayed in seconds, bitwise the same twice.
  const primo::test::RecordedSession r = primo::test::record_bar_session(dir + "/bar.obj");
  primo::save_mesh(r.mesh, dir + "/bar.obj");
  primo::Session s = r.session;
  const primo::SessionEvent last = s.events.back();
  for (int k = 0; k < 100000; ++k) {
    primo::SessionEvent t;
    t.type = primo::SessionEvent::Type::Targets;
    t.frame = last.frame + 1 + k / 100;
    t.t = last.t + t.frame / 60.0;
    t.poses.push_back(
        {1, {primo::Vec3(0.0, 0.0, 1e-4 * (k % 1000)), Eigen::Quaterniond::Identity()}});
    s.events.push_back(t);
  }
  primo::save_session(s, dir + "/many.session.json");
  const auto start = std::chrono::steady_clock::now();
  const CommandResult a = run_primo("replay " + dir + "/many.session.json -o " + dir +
                                    "/a.obj --stats " + dir + "/a.json");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(0, a.exit_code) << a.err;
  EXPECT_LT(seconds, 60.0);
  EXPECT_NE(std::string::npos,
            read_text(dir + "/a.json").find("\"events\": " + std::to_string(s.events.size())));
  ASSERT_EQ(0, run_primo("replay " + dir + "/many.session.json -o " + dir + "/b.obj").exit_code);
  EXPECT_EQ(read_text(dir + "/a.obj"), read_text(dir + "/b.obj"));
  std::printf("[ metric   ] 100,000-event session (%zu bytes) replayed in %.1f s\n",
              read_text(dir + "/many.session.json").size(), seconds);
}
