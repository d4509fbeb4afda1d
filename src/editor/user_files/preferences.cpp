#include "preferences.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "primo/util/error.h"
#include "primo/io/input_files.h"
#include "primo/io/output_files.h"
#include "user_folders.h"

namespace primo::editor {
namespace {

using json = nlohmann::json;

template <typename T>
void read(const json& j, const char* key, T& value, std::vector<std::string>& problems) {
  if (!j.contains(key)) return;
  const json& v = j[key];
  if constexpr (std::is_same_v<T, bool>) {
    if (v.is_boolean()) return void(value = v.get<bool>());
    problems.push_back(std::string(key) + ": expected true or false");
  } else {
    if (v.is_number() && std::isfinite(v.get<double>()))
      return void(value = T(std::clamp(v.get<double>(), -1e9, 1e9)));
    problems.push_back(std::string(key) + ": expected a number");
  }
}

const char* falloff_name(Falloff f) {
  switch (f) {
    case Falloff::Linear: return "linear";
    case Falloff::Smooth: return "smooth";
    case Falloff::Constant: break;
  }
  return "constant";
}

}  // namespace

std::string preferences_path() { return config_folder() + "/preferences.json"; }

Preferences load_preferences(const std::string& path) {
  Preferences p;
  const std::string file = path.empty() ? preferences_path() : path;
  std::error_code ignored;
  if (!std::filesystem::exists(file, ignored)) return p;  // never saved: the defaults, quietly
  std::string text;
  try {
    text = read_input_file(file);  // a pipe or a device there must not stop the editor starting
  } catch (const Error& e) {
    p.problems.push_back(std::string(e.what()) + "; using the defaults");
    return p;
  }
  const json j = json::parse(text, nullptr, false);
  if (!j.is_object()) {
    p.problems.push_back(file + ": not a JSON object; using the defaults");
    return p;
  }
  std::vector<std::string> problems;
  read(j, "smooth", p.smooth, problems);
  read(j, "wireframe", p.wireframe, problems);
  read(j, "prisms", p.prisms, problems);
  read(j, "heat_map", p.heat_map, problems);
  read(j, "paint_overlay", p.paint_overlay, problems);
  read(j, "grid", p.grid, problems);
  read(j, "brush_radius", p.brush_radius, problems);
  read(j, "paint_strength", p.paint_strength, problems);
  read(j, "autosave_minutes", p.autosave_minutes, problems);
  read(j, "tolerance", p.tolerance, problems);
  read(j, "max_iterations", p.max_iterations, problems);
  read(j, "settle_seconds", p.settle_seconds, problems);
  if (j.contains("paint_falloff") && j["paint_falloff"].is_string()) {
    const std::string f = j["paint_falloff"].get<std::string>();
    p.paint_falloff = f == "linear" ? Falloff::Linear : f == "smooth" ? Falloff::Smooth : Falloff::Constant;
  }
  if (j.contains("keys"))
    for (std::string& problem : p.keys.apply_overrides(j["keys"])) problems.push_back(problem);
  for (const std::string& problem : problems) p.problems.push_back(file + ": " + problem);
  // What the widgets can make.
  p.brush_radius = std::clamp(p.brush_radius, 2.0, 200.0);
  p.paint_strength = std::clamp(p.paint_strength, 0.05, 1.0);
  p.autosave_minutes = std::clamp(p.autosave_minutes, 0.0, 60.0);
  p.tolerance = std::clamp(p.tolerance, 1e-14, 1e-2);
  p.max_iterations = std::clamp(p.max_iterations, 1, 100000);
  p.settle_seconds = std::clamp(p.settle_seconds, 0.0, 3600.0);
  return p;
}

bool save_preferences(const Preferences& p, const std::string& path) {
  const std::string file = path.empty() ? preferences_path() : path;
  const json j = {{"smooth", p.smooth},
                  {"wireframe", p.wireframe},
                  {"prisms", p.prisms},
                  {"heat_map", p.heat_map},
                  {"paint_overlay", p.paint_overlay},
                  {"grid", p.grid},
                  {"brush_radius", p.brush_radius},
                  {"paint_strength", p.paint_strength},
                  {"paint_falloff", falloff_name(p.paint_falloff)},
                  {"autosave_minutes", p.autosave_minutes},
                  {"tolerance", p.tolerance},
                  {"max_iterations", p.max_iterations},
                  {"settle_seconds", p.settle_seconds},
                  {"keys", p.keys.overrides()}};
  try {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ec);
    write_text_atomically(file, j.dump(2) + "\n");
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace primo::editor
