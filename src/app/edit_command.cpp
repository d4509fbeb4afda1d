// `primo edit [MESH_OR_SCENARIO] [--screenshot OUT.png] [--script FILE] [--timeout SECONDS]`, and
// `primo` with no arguments: the interactive editor (docs/editor.md).

#include <CLI/CLI.hpp>
#include <memory>

#include "app.h"
#include "commands.h"
#include "number_options.h"
#include "paths.h"
#include "primo/util/error.h"
#include "primo/io/input_files.h"

namespace primo::app {
namespace {

// The script is read by the window before anything opens; a named pipe or a device there
// would block it, so the file is checked here as every input is (primo/io/input_files.h).
const CLI::Validator kInputFile(
    [](std::string& path) -> std::string {
      try {
        check_input_file(path);
      } catch (const Error& e) {
        return e.what();
      }
      return "";
    },
    "FILE");

}  // namespace

Command register_edit(CLI::App& app) {
  auto options = std::make_shared<editor::EditorOptions>();
  CLI::App* cmd = app.add_subcommand(
      "edit", "Open the interactive editor (the default when primo runs without arguments)");
  cmd->add_option("input", options->input,
                  "Mesh (.obj .off .ply .stl .om .gltf .glb .fbx .dae .3mf) or scenario (.json) to "
                  "open; default: the bundled Spot mesh");
  cmd->add_option("--screenshot", options->screenshot,
                  "Render until the solve has settled, save the view as PNG and exit");
  cmd->add_flag("--screenshot-ui", options->screenshot_ui, "Include the panels in the screenshot");
  cmd->add_option("--script", options->script,
                  "Play timed input events and commands from a file (docs/editor.md)")
      ->check(kInputFile);
  cmd->add_option("--width", options->width, "Window width")->check(finite_range(320, 8192));
  cmd->add_option("--height", options->height, "Window height")->check(finite_range(240, 8192));
  cmd->add_option("--timeout", options->timeout,
                  "Seconds a --screenshot or --script run may take (default 300): then exit 1, "
                  "unsaved work autosaved")
      ->check(finite_positive(86400));  // at most a day, as a script's waits
  return {cmd, [options] {
            editor::EditorOptions o = *options;
            if (o.input.empty()) o.input = editor::default_mesh_path();
            return editor::run_editor(o);
          }};
}

int run_default_editor() {
  editor::EditorOptions o;
  o.input = editor::default_mesh_path();
  return editor::run_editor(o);
}

}  // namespace primo::app
