// The command line itself (src/app/main.cpp, src/app/number_options.h): a mistake in it is one
// line naming the command and the option, a non-zero exit and nothing written, like any other
// error; number options refuse words, NaN and infinity.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "support/test_support.h"

namespace {

using primo::test::CommandResult;
using primo::test::run_primo;
namespace fs = std::filesystem;

// Asserts that `primo ARGUMENTS` fails with exactly `line` (and its line break) on stderr.
void expect_one_line(const std::string& arguments, const std::string& line) {
  const CommandResult r = run_primo(arguments);
  EXPECT_NE(r.exit_code, 0) << arguments;
  EXPECT_EQ(r.err, line + "\n") << arguments;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(CliOptions, MistakesAreOneLineNamingTheCommandAndTheOption) {
  // CLI11 added "Run with --help for more information." on a second line.
  expect_one_line("deform s.json -o o.obj --bogus",
                  "primo deform: error: The following argument was not expected: --bogus "
                  "(see primo deform --help)");
  expect_one_line("deform s.json",
                  "primo deform: error: --output is required (see primo deform --help)");
  expect_one_line("replay", "primo replay: error: session is required (see primo replay --help)");
  expect_one_line("frobnicate",
                  "primo: error: The following argument was not expected: frobnicate (see "
                  "primo --help)");
  expect_one_line("bench", "primo bench: error: A subcommand is required (see primo bench --help)");
  expect_one_line("deform s.json -o o.obj --solver fast",
                  "primo deform: error: --solver: fast not in {global,local,hierarchical} (see "
                  "primo deform --help)");
  expect_one_line("replay s.json -o o.obj --every 2.5",
                  "primo replay: error: Could not convert: --every = 2.5 (see primo replay "
                  "--help)");
  // Bytes from the command line are not sent to the terminal raw.
  expect_one_line("deform s.json -o o.obj \"$(printf 'x\\033[2J')\"",
                  "primo deform: error: The following argument was not expected: x\\x1B[2J "
                  "(see primo deform --help)");
}

TEST(CliOptions, HelpIsStillPrintedWithExitZero) {
  const CommandResult r = run_primo("replay --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--every INT:from 1 to 10000000"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(CliOptions, VersionIsTheProjectVersion) {
  const CommandResult r = run_primo("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, std::string("primo ") + PRIMO_PROJECT_VERSION + "\n");
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(CliOptions, NumbersMustBeFiniteAndInRange) {
  // CLI11's Range and PositiveNumber let NaN through, and PositiveNumber infinity.
  expect_one_line("replay s.json -o o.obj --every nan",
                  "primo replay: error: --every: expected a number from 1 to 10000000, got nan "
                  "(see primo replay --help)");
  expect_one_line("--threads inf deform s.json -o o.obj",
                  "primo deform: error: --threads: expected a number from 0 to 4096, got inf "
                  "(see primo deform --help)");
  expect_one_line("bench drag s.json --drag-prediction nan",
                  "primo bench drag: error: --drag-prediction: expected a number from 0 to 2, got "
                  "nan (see primo bench drag --help)");
  expect_one_line("bench quality --half-thickness -nan",
                  "primo bench quality: error: --half-thickness: expected a number from 0 to 1, "
                  "got -nan (see primo bench quality --help)");
  expect_one_line("edit --timeout 1e999",
                  "primo edit: error: --timeout: expected a number more than 0 and at most 86400, "
                  "got 1e999 (see primo edit --help)");
  expect_one_line("edit --width x",
                  "primo edit: error: --width: expected a number from 320 to 8192, got x (see "
                  "primo edit --help)");
}

TEST(CliOptions, GeneratedMeshesHaveFiniteSizesAndABoundedFaceCount) {
  const std::string dir = primo::test::temp_dir();
  // A NaN radius wrote a mesh of NaN vertices, a negative one an inside-out cylinder.
  for (const char* radius : {"nan", "-1", "0", "inf"})
    expect_one_line("generate cylinder --radius " + std::string(radius) + " -o " + dir + "/c.obj",
                    "primo generate cylinder: error: --radius: expected a number more than 0 and "
                    "at most 1e+15, got " +
                        std::string(radius) + " (see primo generate cylinder --help)");
  // Ten billion faces ran until memory ran out.
  expect_one_line("generate cylinder --segments 100000 --bands 100000 -o " + dir + "/c.obj",
                  "primo generate: error: " + dir +
                      "/c.obj: the mesh would have 10000000000 faces, more than 16777216");
  EXPECT_FALSE(fs::exists(dir + "/c.obj"));
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(CliOptions, AScriptThatIsNotARegularFileIsRefusedBeforeTheWindowOpens) {
  const std::string dir = primo::test::temp_dir();
  ASSERT_EQ(0, ::mkfifo((dir + "/script.txt").c_str(), 0600));
  const CommandResult r = primo::test::run_primo_within(20, "edit --script " + dir + "/script.txt");
  EXPECT_EQ(r.exit_code, 105) << "124: still running after 20 s";
  EXPECT_EQ(r.err, "primo edit: error: --script: " + dir +
                       "/script.txt: not a regular file (a named pipe) (see primo edit --help)\n");
}

}  // namespace
