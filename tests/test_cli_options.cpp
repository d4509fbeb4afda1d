// The command line itself (src/app/main.cpp): a mistake in it is one line naming the command
// and the option, a non-zero exit and nothing written, like any other error.

#include <gtest/gtest.h>

#include <string>

#include "test_support.h"

namespace {

using primo::test::CommandResult;
using primo::test::run_primo;

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
  EXPECT_NE(r.out.find("--every"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

}  // namespace
