// Assimp runs in a child process (src/core/io/scene/scene_reader_process.h): what the child
// sends back arrives bit for bit, and a crash, a memory bomb or a hang in it is one line naming
// the file while this process goes on.

#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>

#include "../../../src/core/io/scene/scene_reader_process.h"
#include "primo/util/error.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

namespace primo {
namespace {

using detail::ReaderProcessLimits;
using detail::SceneSoup;

ReaderProcessLimits small_limits() {
  ReaderProcessLimits limits;
  limits.memory_bytes = 300u << 20;
  limits.seconds = 20;
  return limits;
}

// The message of the Error that reading in the child throws ("" when it does not throw).
std::string child_error(const std::function<SceneSoup()>& read,
                        const ReaderProcessLimits& limits = small_limits()) {
  try {
    detail::read_in_child_process("scene.dae", "COLLADA", limits, read);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ReaderProcess, TheSoupComesBackBitForBit) {
  SceneSoup sent;
  sent.soup.points = {Vec3(0.1, -0.0, 1e-300), Vec3(std::numeric_limits<double>::max(), 2, 3),
                      Vec3(-1.5, 1.0 / 3.0, 7), Vec3(4, 5, 6), Vec3(8, 9, 10)};
  sent.soup.faces = {{0, 1, 2}, {0, 2, 3, 4}, {4, 3, 2, 1, 0}};
  sent.note = "scene.dae: merged 3 vertex copies; ignored: 2 materials";
  sent.parts = "faces 0-0 'A', faces 1-2 'B'";
  const SceneSoup got =
      detail::read_in_child_process("scene.dae", "COLLADA", small_limits(), [&] { return sent; });
  ASSERT_EQ(got.soup.points.size(), sent.soup.points.size());
  EXPECT_EQ(0, std::memcmp(got.soup.points.data(), sent.soup.points.data(),
                           sent.soup.points.size() * sizeof(Vec3)));
  EXPECT_EQ(got.soup.faces, sent.soup.faces);
  EXPECT_EQ(got.note, sent.note);
  EXPECT_EQ(got.parts, sent.parts);
  // An empty soup too.
  const SceneSoup empty =
      detail::read_in_child_process("e.dae", "COLLADA", small_limits(), [] { return SceneSoup{}; });
  EXPECT_TRUE(empty.soup.points.empty() && empty.soup.faces.empty() && empty.note.empty());
}

TEST(ReaderProcess, AnErrorInTheChildKeepsItsMessage) {
  EXPECT_EQ(child_error([]() -> SceneSoup { throw Error("scene.dae: cannot read: a reason"); }),
            "scene.dae: cannot read: a reason");
  EXPECT_EQ(child_error([]() -> SceneSoup { throw std::runtime_error("bad XML"); }),
            "scene.dae: cannot read: not a valid COLLADA file (Assimp: bad XML)");
}

TEST(ReaderProcess, ACrashInTheChildIsAnErrorNamingTheFile) {
  const std::string what = child_error([]() -> SceneSoup {
    std::raise(SIGSEGV);
    return {};
  });
  EXPECT_NE(what.find("scene.dae: cannot read: Assimp's COLLADA reader crashed on this file ("),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("Segmentation fault"), std::string::npos) << what;
  // An abort (a failed check in a library) too.
  EXPECT_NE(child_error([]() -> SceneSoup { std::abort(); }).find("crashed"), std::string::npos);
  // And this process reads on.
  EXPECT_EQ(child_error([] { return SceneSoup{}; }), "");
}

TEST(ReaderProcess, AMemoryBombStopsAtTheLimit) {
  const std::string what = child_error([]() -> SceneSoup {
    std::vector<std::vector<char>> blocks;
    for (int i = 0; i < 1000; ++i) blocks.emplace_back(size_t(32) << 20, char(i));  // 32 GB
    return {};
  });
  EXPECT_EQ(what,
            "scene.dae: cannot read: reading this COLLADA file needs more than 0.3 GB of memory "
            "(the limit for a file of its size)");
}

TEST(ReaderProcess, AHangStopsAtTheTimeLimit) {
  ReaderProcessLimits limits = small_limits();
  limits.seconds = 0.5;
  const std::string what = child_error(
      []() -> SceneSoup {
        for (volatile bool forever = true; forever;) {
        }
        return {};
      },
      limits);
  EXPECT_EQ(what, "scene.dae: cannot read: reading this COLLADA file took longer than 0.5 s");
}

TEST(ReaderProcess, LimitsGrowWithTheInputWithinTheMachinesMemory) {
  const auto small = detail::reader_process_limits(1000);
  const auto large = detail::reader_process_limits(size_t(100) << 20);
  EXPECT_GE(small.memory_bytes, size_t(1) << 30);
  EXPECT_GT(large.memory_bytes, small.memory_bytes);
  EXPECT_GT(large.seconds, small.seconds);
  const auto huge = detail::reader_process_limits(size_t(1) << 50);
  EXPECT_LE(double(huge.memory_bytes), double(sysconf(_SC_PHYS_PAGES)) * sysconf(_SC_PAGESIZE));
}

TEST(ReaderProcess, AssimpCrashingOnAFileIsAnError) {
  // Assimp's COLLADA reader follows instance_node links without a cycle check and crashes on
  // a node that instances itself. PriMo's COLLADA check refuses such a file before Assimp sees
  // it; here Assimp reads it unchecked, in the child, as it would any defect no check
  // foresaw, and the editor that read it in its own process would have gone down.
  std::string text = test::read_text(test::source_path("tests/data/scenes/cube_emptyTags.dae"));
  const std::string geometry = "<instance_geometry url=\"#box-lib\">";
  ASSERT_NE(text.find(geometry), std::string::npos);
  text.replace(text.find(geometry), 0, "<instance_node url=\"#Box\"/>");
  const std::string looped = test::temp_dir() + "/own-instance.dae";
  test::write_text(looped, text);
  const std::string what = child_error([&]() -> SceneSoup {
    Assimp::Importer importer;
    importer.ReadFile(looped, 0);
    return {};
  });
  EXPECT_NE(what.find("scene.dae: cannot read: Assimp's COLLADA reader crashed on this file"),
            std::string::npos)
      << what;
}

}  // namespace
}  // namespace primo
