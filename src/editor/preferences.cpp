#include "preferences.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "primo/output_files.h"
#include "user_folders.h"

namespace primo::editor {
namespace {

using json = nlohmann::json;

template <typename T>
void read(const json& j, const char* key, T& value) {
  if (!j.contains(key)) return;
  const json& v = j[key];
  if constexpr (std::is_same_v<T, bool>) {
    if (v.is_boolean()) value = v.get<bool>();
  } else {
    if (v.is_number() && std::isfinite(v.get<double>())) value = v.get<double>();
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
  std::ifstream in(path.empty() ? preferences_path() : path);
  if (!in) return p;
  std::stringstream text;
  text << in.rdbuf();
  const json j = json::parse(text.str(), nullptr, false);
  if (!j.is_object()) return p;
  read(j, "smooth", p.smooth);
  read(j, "wireframe", p.wireframe);
  read(j, "prisms", p.prisms);
  read(j, "heat_map", p.heat_map);
  read(j, "paint_overlay", p.paint_overlay);
  read(j, "brush_radius", p.brush_radius);
  read(j, "paint_strength", p.paint_strength);
  read(j, "autosave_minutes", p.autosave_minutes);
  read(j, "tolerance", p.tolerance);
  if (j.contains("paint_falloff") && j["paint_falloff"].is_string()) {
    const std::string f = j["paint_falloff"].get<std::string>();
    p.paint_falloff = f == "linear" ? Falloff::Linear : f == "smooth" ? Falloff::Smooth : Falloff::Constant;
  }
  // What the widgets can make.
  p.brush_radius = std::clamp(p.brush_radius, 2.0, 200.0);
  p.paint_strength = std::clamp(p.paint_strength, 0.05, 1.0);
  p.autosave_minutes = std::clamp(p.autosave_minutes, 0.0, 60.0);
  p.tolerance = std::clamp(p.tolerance, 1e-14, 1e-2);
  return p;
}

bool save_preferences(const Preferences& p, const std::string& path) {
  const std::string file = path.empty() ? preferences_path() : path;
  const json j = {{"smooth", p.smooth},
                  {"wireframe", p.wireframe},
                  {"prisms", p.prisms},
                  {"heat_map", p.heat_map},
                  {"paint_overlay", p.paint_overlay},
                  {"brush_radius", p.brush_radius},
                  {"paint_strength", p.paint_strength},
                  {"paint_falloff", falloff_name(p.paint_falloff)},
                  {"autosave_minutes", p.autosave_minutes},
                  {"tolerance", p.tolerance}};
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
