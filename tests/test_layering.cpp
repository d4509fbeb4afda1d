// The layers of the house (docs/architecture.md), checked on every include line of the
// sources: a layer includes only itself and the layers below it, and the GUI-free layers no
// window, GL or command-line library. The rule this enforces is the one a newcomer reads in the
// layout: core <- sessions, quality <- bench, editor model <- viewport drawing <- editor window
// <- app. Inside the core, each room is a layer of its own: util <- mesh <- io, mesh <- model <-
// solve <- scenario, and the scenarios read their files through io; the prism model and the
// solvers never see a file.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "support/test_support.h"

namespace {

namespace fs = std::filesystem;

// The folders that make up each layer, relative to the repository. The core's rooms are
// "core/<room>"; a rule that names "core" means every room.
const std::vector<std::pair<std::string, std::string>> kFolders = {
    {"include/primo/util", "core/util"},
    {"src/core/util", "core/util"},
    {"include/primo/mesh", "core/mesh"},
    {"src/core/mesh", "core/mesh"},
    {"include/primo/io", "core/io"},
    {"src/core/io", "core/io"},
    {"src/core/io/scene", "core/io"},
    {"src/core/io/scene/checks", "core/io"},
    {"include/primo/model", "core/model"},
    {"src/core/model", "core/model"},
    {"include/primo/solve", "core/solve"},
    {"src/core/solve", "core/solve"},
    {"include/primo/scenario", "core/scenario"},
    {"src/core/scenario", "core/scenario"},
    {"src/datadir", "datadir"},  // where an installed primo finds its shaders and assets
    {"include/primo/sessions", "sessions"},
    {"src/sessions", "sessions"},
    {"src/quality", "quality"},
    {"src/bench", "bench"},
    {"src/editor", "editor"},
    {"src/editor/document", "editor"},
    {"src/editor/document/selection", "editor"},
    {"src/editor/view", "editor"},
    {"src/editor/input", "editor"},
    {"src/editor/user_files", "editor"},
    {"src/editor/recording", "editor"},
    {"src/editor/ui/render", "render"},  // the viewport's drawing, below the windows and panels
    {"src/editor/ui", "window"},
    {"src/app", "app"},
};

// Who may include whom (besides itself).
const std::map<std::string, std::set<std::string>> kAllowed = {
    {"core/util", {"core/util"}},
    {"core/mesh", {"core/util", "core/mesh"}},
    {"core/io", {"core/util", "core/mesh", "core/io"}},
    {"core/model", {"core/util", "core/mesh", "core/model"}},
    {"core/solve", {"core/util", "core/mesh", "core/model", "core/solve"}},
    {"core/scenario",
     {"core/util", "core/mesh", "core/io", "core/model", "core/solve", "core/scenario"}},
    {"datadir", {"datadir"}},
    {"sessions", {"core", "sessions"}},
    {"quality", {"core", "quality"}},
    {"bench", {"core", "sessions", "quality", "datadir", "bench"}},
    {"editor", {"core", "sessions", "editor"}},
    {"render", {"core", "sessions", "editor", "render"}},
    {"window", {"core", "sessions", "editor", "datadir", "render", "window"}},
    {"app", {"core", "sessions", "quality", "bench", "app"}},
};

// The one exception: `primo edit` launches the window.
const std::set<std::string> kMayIncludeTheWindow = {"src/app/edit_command.cpp"};

// The layers that may include the system headers of a window, GL and the command line.
const std::set<std::string> kGuiLayers = {"editor", "render", "window", "app"};
// System headers of the window and of the command line, which the GUI-free layers never see.
const std::vector<std::string> kWindowHeaders = {"<GL/", "<GLFW/", "<imgui", "<glm/", "<CLI/"};

// The prism model and the solvers work on what they are given: files and the console are the
// business of io, the scenarios and the layers above.
const std::set<std::string> kFileFreeLayers = {"core/model", "core/solve"};
const std::vector<std::string> kFileHeaders = {"<fstream>", "<filesystem>", "<cstdio>",
                                               "<iostream>"};

// Where the compiler looks for a quoted include besides the including file's folder: the core's
// and the sessions' public headers (include/), quality/ and bench/ (src/), the editor model's
// rooms (src/editor), the window's and the data folders' headers.
const std::vector<std::string> kIncludeRoots = {"include", "src", "src/editor", "src/editor/ui",
                                                "src/datadir"};

std::string layer_of(const std::string& folder) {
  for (const auto& [f, layer] : kFolders)
    if (f == folder) return layer;
  return "";
}

bool may_include(const std::string& from, const std::string& to) {
  const std::set<std::string>& allowed = kAllowed.at(from);
  return to == from || allowed.count(to) || (to.rfind("core/", 0) == 0 && allowed.count("core"));
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

// The folder of the file a quoted include names, found as the compiler finds it: beside the
// including file, else under one of kIncludeRoots; else, for a bare name, the one folder that
// has it. "" when none does (or, for a bare name, more than one).
std::string resolve(const std::string& included, const std::string& from_folder,
                    const std::vector<Source>& all) {
  std::vector<std::string> roots = {from_folder};
  roots.insert(roots.end(), kIncludeRoots.begin(), kIncludeRoots.end());
  for (const std::string& root : roots) {
    const fs::path path = (fs::path(root) / included).lexically_normal();
    const std::string folder = path.parent_path().generic_string();
    const std::string name = path.filename().string();
    for (const Source& s : all)
      if (s.folder == folder && s.name == name) return folder;
  }
  std::vector<std::string> found;
  for (const Source& s : all)
    if (s.name == included) found.push_back(s.folder);
  return found.size() == 1 ? found[0] : "";
}

}  // namespace

TEST(Layering, EachLayerIncludesOnlyTheLayersBelowIt) {
  const std::vector<Source> all = sources();
  ASSERT_GT(all.size(), 100u);
  int checked = 0;
  for (const Source& s : all) {
    const std::string layer = layer_of(s.folder);
    const std::string path = s.folder + "/" + s.name;
    std::ifstream in(primo::test::source_path(path));
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      if (line.rfind("#include ", 0) != 0) continue;
      const std::string where = path + ":" + std::to_string(number) + ": " + line;
      const std::string target = line.substr(9);
      if (target.front() == '<') {
        if (kGuiLayers.count(layer)) continue;
        for (const std::string& header : kWindowHeaders)
          if (target.rfind(header, 0) == 0) ADD_FAILURE() << where << " (" << layer << " is GUI-free)";
        if (kFileFreeLayers.count(layer))
          for (const std::string& header : kFileHeaders)
            if (target.rfind(header, 0) == 0)
              ADD_FAILURE() << where << " (" << layer << " reads and writes no files: core/io does)";
        continue;
      }
      const std::string included = target.substr(1, target.find('"', 1) - 1);
      const std::string folder = resolve(included, s.folder, all);
      if (folder.empty()) {
        ADD_FAILURE() << where << ": no single source folder has " << included;
        continue;
      }
      const std::string to = layer_of(folder);
      const bool allowed =
          may_include(layer, to) || (to == "window" && kMayIncludeTheWindow.count(path));
      EXPECT_TRUE(allowed) << where << " (" << layer << " includes " << to << ")";
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

// A new folder of sources must be given its layer (and its rules) before anything in it builds
// on the rest: otherwise the test above would never read its include lines.
TEST(Layering, EverySourceFolderBelongsToALayer) {
  const fs::path repository = fs::path(primo::test::source_path("src")).parent_path();
  int files = 0;
  for (const std::string top : {"include", "src"}) {
    for (const auto& entry : fs::recursive_directory_iterator(primo::test::source_path(top))) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      const std::string path =
          entry.path().lexically_relative(repository).generic_string();
      const std::string folder = fs::path(path).parent_path().generic_string();
      EXPECT_FALSE(layer_of(folder).empty())
          << path << ": the folder " << folder
          << " is in no layer; add it to kFolders in tests/test_layering.cpp (a core room also"
             " to kAllowed) and to the table in docs/architecture.md";
      ++files;
    }
  }
  EXPECT_GT(files, 100);
}

// Every layer a rule names is one kFolders gives a folder, and the core's rooms form a stack: no
// room may include a room that may include it.
TEST(Layering, TheCoreRoomsFormAStack) {
  std::set<std::string> layers = {"core"};
  for (const auto& [folder, layer] : kFolders) layers.insert(layer);
  for (const auto& [layer, allowed] : kAllowed) {
    EXPECT_TRUE(layers.count(layer)) << layer << " has rules but no folder";
    for (const std::string& to : allowed) {
      EXPECT_TRUE(layers.count(to)) << layer << " may include " << to << ", which has no folder";
      if (to != layer && kAllowed.count(to)) {
        EXPECT_FALSE(may_include(to, layer)) << layer << " and " << to << " include each other";
      }
    }
  }
  for (const auto& [folder, layer] : kFolders)
    EXPECT_TRUE(kAllowed.count(layer)) << folder << ": layer " << layer << " has no rules";
}
