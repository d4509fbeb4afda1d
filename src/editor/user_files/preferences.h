#pragma once
// The user's defaults, kept between runs in config_folder()/preferences.json and edited in
// Edit > Preferences: display, brushes, autosave, the solver's limits and tolerance for meshes
// opened without a scenario, and the key map. A missing or broken file gives the defaults (the
// file is a convenience, never a reason not to start) and says what was wrong; unknown keys
// are ignored so that newer files still load.

#include <string>
#include <vector>

#include "input/key_map.h"
#include "document/paint.h"

namespace primo::editor {

struct Preferences {
  // Display (View menu).
  bool smooth = true;
  bool wireframe = false;
  bool prisms = false;
  bool heat_map = false;
  bool paint_overlay = true;
  bool grid = true;  // the ground grid
  // Brushes.
  double brush_radius = 32.0;  // viewport pixels
  double paint_strength = 1.0;
  Falloff paint_falloff = Falloff::Constant;
  // Work.
  double autosave_minutes = 2.0;  // 0: never
  // Solver, for a mesh opened without a scenario (a scenario keeps its own `solver`).
  double tolerance = 1e-8;        // the settle tolerance
  int max_iterations = 100;       // solver.max_iterations of the scenarios it saves (batch runs)
  // How long the editor settles after an edit before it stops by itself (Continue solves
  // on); 0: until converged.
  double settle_seconds = 0.0;
  KeyMap keys;
  // What load_preferences could not use, one line each, naming the file and the key.
  std::vector<std::string> problems;
};

// Reads `path` (default: config_folder()/preferences.json); values out of range are clamped,
// wrong types and unreadable keys are left at their defaults and listed in `problems`.
Preferences load_preferences(const std::string& path = {});
// Writes atomically; false when it could not.
bool save_preferences(const Preferences& preferences, const std::string& path = {});
std::string preferences_path();

}  // namespace primo::editor
