// `primo edit [MESH_OR_SCENARIO] [--screenshot OUT.png] [--script FILE] [--timeout SECONDS]`, and
// `primo` with no arguments: the interactive editor (docs/editor.md).

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "app.h"
#include "commands.h"
#include "paths.h"

namespace primo::app {
namespace {

// More than 0 and at most a day, as a script's waits. CLI11's ranges let "nan" through, and a
// timeout of nan or 1e300 would never run out.
const CLI::Validator kTimeoutSeconds(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      const double seconds = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || !std::isfinite(seconds) || seconds <= 0.0 ||
          seconds > 86400.0)
        return "expected seconds, more than 0 and at most 86400, got " + text;
      return "";
    },
    "SECONDS");

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
      ->check(CLI::ExistingFile);
  cmd->add_option("--width", options->width, "Window width")->check(CLI::Range(320, 8192));
  cmd->add_option("--height", options->height, "Window height")->check(CLI::Range(240, 8192));
  cmd->add_option("--timeout", options->timeout,
                  "Seconds a --screenshot or --script run may take (default 300): then exit 1, "
                  "unsaved work autosaved")
      ->check(kTimeoutSeconds);
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
