#pragma once
// A modal file browser drawn with ImGui (no native dialog on a bare X server): a path bar,
// places (home, working folder, bundled assets), folders first, files filtered by
// extension, a name field for saving. Double-click or Enter accepts.

#include <string>
#include <vector>

namespace primo::editor {

class FileDialog {
 public:
  enum class Mode { Open, Save };

  // Starts the dialog in `folder` (for Save, proposing `file_name`). `extensions` such as
  // ".obj" filter the files shown; the first one is added to a saved name without one.
  void open(Mode mode, std::string title, std::vector<std::string> extensions, std::string folder,
            std::string file_name = "");
  bool is_open() const { return open_; }
  // Draws the dialog if it is open. Returns true once, when the user accepts; `path` is then
  // the chosen file.
  bool draw(std::string& path);

 private:
  void refresh();
  void enter(const std::string& folder);
  bool accept(std::string& path);

  struct Entry {
    std::string name;
    bool folder = false;
    unsigned long long size = 0;
  };
  Mode mode_ = Mode::Open;
  std::string title_;
  std::vector<std::string> extensions_;
  std::string folder_, name_, path_field_, error_;
  std::vector<Entry> entries_;
  int selected_ = -1;
  bool open_ = false, request_popup_ = false;
  bool focus_name_ = false;  // the name field takes the keyboard at the next frame drawn
  int openings_ = 0;         // the name field's ID at each opening (file_dialog.cpp)
};

}  // namespace primo::editor
