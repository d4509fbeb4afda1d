#pragma once
// The editor's window: GLFW + OpenGL 3.3 core + Dear ImGui around an Editor.

#include <string>

namespace primo::editor {

struct EditorOptions {
  std::string input;            // mesh or scenario to open ("" : nothing)
  std::string screenshot;       // render until the solve has settled, save this PNG, exit
  bool screenshot_ui = false;   // ... with the panels (default: the view alone)
  std::string script;           // timed input events and commands (see script.h)
  int width = 1280, height = 800;
  double timeout = 300.0;  // seconds a --screenshot or --script run may take
};

// Opens the window and runs until it is closed (or the screenshot/script is done). Returns
// the process exit status; problems are reported on stderr, never thrown.
int run_editor(const EditorOptions& options);

}  // namespace primo::editor
