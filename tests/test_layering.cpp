// The layers of the house (docs/architecture.md), checked on every include line of the
// sources: a layer includes only itself and the layers below it, and the GUI-free layers no
// window, GL or command-line library. The rule this enforces is the one a newcomer reads in the
// layout: core <- sessions, quality <- bench, editor model <- editor window <- app.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "test_support.h"

namespace {

namespace fs = std::filesystem;

// The folders that make up each layer, relative to the repository.
const std::vector<std::pair<std::string, std::string>> kFolders = {
    {"include/primo", "core"},  // primo/sessions/ belong to "sessions", see layer_of_header
    {"src/core", "core"},
    {"src/datadir", "datadir"},  // where an installed primo finds its shaders and assets
    {"src/sessions", "sessions"},
    {"src/quality", "quality"},
    {"src/bench", "bench"},
    {"src/editor", "editor"},
    {"src/editor/ui", "window"},
    {"src/app", "app"},
};

// Who may include whom (besides itself).
const std::map<std::string, std::set<std::string>> kAllowed = {
    {"core", {"core"}},
    {"datadir", {"datadir"}},
    {"sessions", {"core", "sessions"}},
    {"quality", {"core", "quality"}},
    {"bench", {"core", "sessions", "quality", "datadir", "bench"}},
    {"editor", {"core", "sessions", "editor"}},
    {"window", {"core", "sessions", "editor", "datadir", "window"}},
    {"app", {"core", "sessions", "quality", "bench", "app"}},
};

// The one exception: `primo edit` launches the window.
const std::set<std::string> kMayIncludeTheWindow = {"src/app/edit_command.cpp"};

// System headers of the window and of the command line, which the GUI-free layers never see.
const std::vector<std::string> kWindowHeaders = {"<GL/", "<GLFW/", "<imgui", "<glm/", "<CLI/"};

std::string layer_of_header(const std::string& folder, const std::string& name) {
  if (folder == "include/primo" && name.rfind("session", 0) == 0) return "sessions";
  for (const auto& [f, layer] : kFolders)
    if (f == folder) return layer;
  return "";
}

struct Source {
  std::string folder;  // relative to the repository
  std::string name;
};

std::vector<Source> sources() {
  std::vector<Source> out;
  for (const auto& [folder, layer] : kFolders) {
    const fs::path dir = primo::test::source_path(folder);
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string ext = entry.path().extension().string();
      if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp"))
        out.push_back({folder, entry.path().filename().string()});
    }
  }
  return out;
}

// The folder a quoted include names: "primo/x.h" in include/primo, "quality/x.h" in src/quality,
// "bench/x.h" in src/bench; a bare name beside the including file, else the one folder that
// has it. "" when no folder (or more than one) has it.
std::string resolve(const std::string& included, const std::string& from_folder,
                    const std::vector<Source>& all) {
  for (const auto& [prefix, folder] : std::vector<std::pair<std::string, std::string>>{
           {"primo/", "include/primo"}, {"quality/", "src/quality"}, {"bench/", "src/bench"}})
    if (included.rfind(prefix, 0) == 0) return folder;
  std::vector<std::string> found;
  for (const Source& s : all) {
    if (s.name != included) continue;
    if (s.folder == from_folder) return s.folder;
    found.push_back(s.folder);
  }
  return found.size() == 1 ? found[0] : "";
}

std::string base_name(const std::string& included) {
  return fs::path(included).filename().string();
}

}  // namespace

TEST(Layering, EachLayerIncludesOnlyTheLayersBelowIt) {
  const std::vector<Source> all = sources();
  ASSERT_GT(all.size(), 100u);
  int checked = 0;
  for (const Source& s : all) {
    const std::string layer = layer_of_header(s.folder, s.name);
    const std::string path = s.folder + "/" + s.name;
    std::ifstream in(primo::test::source_path(path));
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      if (line.rfind("#include ", 0) != 0) continue;
      const std::string where = path + ":" + std::to_string(number) + ": " + line;
      const std::string target = line.substr(9);
      if (target.front() == '<') {
        if (layer == "editor" || layer == "window" || layer == "app") continue;
        for (const std::string& header : kWindowHeaders)
          if (target.rfind(header, 0) == 0) ADD_FAILURE() << where << " (" << layer << " is GUI-free)";
        continue;
      }
      const std::string included = target.substr(1, target.find('"', 1) - 1);
      const std::string folder = resolve(included, s.folder, all);
      if (folder.empty()) {
        ADD_FAILURE() << where << ": no single source folder has " << included;
        continue;
      }
      const std::string to = layer_of_header(folder, base_name(included));
      const bool allowed = kAllowed.at(layer).count(to) ||
                           (to == "window" && kMayIncludeTheWindow.count(path));
      EXPECT_TRUE(allowed) << where << " (" << layer << " includes " << to << ")";
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}
