// `primo`: the PriMo editor (no arguments, or `primo edit`) and the headless subcommands.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "commands.h"
#include "huge_pages.h"
#include "number_options.h"
#include "primo/util/error.h"
#include "primo/util/parallel.h"

namespace {

// One line, whatever a file put into the message: control bytes (a terminal escape, a newline
// from a JSON string) are shown as \xNN, never sent to the terminal.
std::string printable(const char* message) {
  std::string out;
  for (const char* c = message; *c; ++c) {
    const unsigned char b = static_cast<unsigned char>(*c);
    if (b >= 0x20 && b != 0x7f) {
      out += char(b);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", b);
      out += hex;
    }
  }
  return out;
}

// "deform" or "bench drag": the deepest command the command line reached, "" for none.
std::string command_path(const CLI::App& app) {
  std::string path;
  for (const CLI::App* command = &app; !command->get_subcommands().empty();) {
    command = command->get_subcommands().front();
    path += (path.empty() ? "" : " ") + command->get_name();
  }
  return path;
}

// A command-line mistake is one line like any other error (CLI11 adds a second, "Run with
// --help for more information."), naming the command and pointing to its --help.
std::string one_line_failure(const CLI::App* app, const CLI::Error& e) {
  const std::string command = command_path(*app);
  const std::string primo = command.empty() ? "primo" : "primo " + command;
  return primo + ": error: " + printable(e.what()) + " (see " + primo + " --help)\n";
}

}  // namespace

int main(int argc, char** argv) {
  primo::app::restart_with_huge_pages(argv);
  CLI::App app{"PriMo: coupled prisms for intuitive surface modeling"};
  app.require_subcommand(0, 1);
  app.failure_message(one_line_failure);  // before the commands, which copy it
  app.set_version_flag("--version", "primo " PRIMO_VERSION, "Print the version and exit");
  // One option for every command (deform, replay, bench, edit...): given after the command's
  // name too, since the commands fall through to it.
  int threads = 0;
  app.add_option("--threads", threads,
                 "Threads the solver may use (default 0: every core). Results are the same "
                 "on any number of threads.")
      ->check(primo::app::finite_range(0, 4096));
  app.fallthrough();
  const std::vector<primo::app::Command> commands = {
      primo::app::register_edit(app), primo::app::register_deform(app),
      primo::app::register_generate(app), primo::app::register_bench(app),
      primo::app::register_replay(app),
      primo::app::register_metrics(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  primo::set_thread_count(threads);
  for (const auto& [sub, run] : commands) {
    if (!sub->parsed()) continue;
    try {
      return run();
    } catch (const primo::Error& e) {
      std::fprintf(stderr, "primo %s: error: %s\n", sub->get_name().c_str(), printable(e.what()).c_str());
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "primo %s: error: out of memory\n", sub->get_name().c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "primo %s: error: %s\n", sub->get_name().c_str(), printable(e.what()).c_str());
    }
    return 1;
  }
  return primo::app::run_default_editor();  // no subcommand
}
