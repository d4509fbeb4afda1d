#pragma once
// The user's defaults, kept between runs in config_folder()/preferences.json and edited in
// Edit > Preferences: display, brushes, autosave, and the solver tolerance of meshes opened
// without a scenario. A missing or broken file gives the defaults (the file is a convenience,
// never a reason not to start); unknown keys are ignored so that newer files still load.

#include <string>

#include "paint.h"

namespace primo::editor {

struct Preferences {
  // Display (View menu).
  bool smooth = true;
  bool wireframe = false;
  bool prisms = false;
  bool heat_map = false;
  bool paint_overlay = true;
  // Brushes.
  double brush_radius = 32.0;  // viewport pixels
  double paint_strength = 1.0;
  Falloff paint_falloff = Falloff::Constant;
  // Work.
  double autosave_minutes = 2.0;  // 0: never
  double tolerance = 1e-8;        // the settle tolerance of a mesh opened without a scenario
};

// Reads `path` (default: config_folder()/preferences.json); values out of range are clamped.
Preferences load_preferences(const std::string& path = {});
// Writes atomically; false when it could not.
bool save_preferences(const Preferences& preferences, const std::string& path = {});
std::string preferences_path();

}  // namespace primo::editor
