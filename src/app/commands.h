#pragma once
// Subcommands of the `primo` executable. Each registers its options on the CLI11 app and
// returns it with the function that runs it and gives the process exit code.

#include <functional>

namespace CLI {
class App;
}

namespace primo::app {

struct Command {
  CLI::App* subcommand;
  std::function<int()> run;
};

Command register_deform(CLI::App& app);
// `primo bench engine | drag | quality` (the benchmarks themselves are in src/bench).
Command register_bench(CLI::App& app);
Command register_metrics(CLI::App& app);
Command register_generate(CLI::App& app);
Command register_edit(CLI::App& app);
Command register_replay(CLI::App& app);
// `primo` without a subcommand: the editor on the bundled example mesh.
int run_default_editor();

}  // namespace primo::app
