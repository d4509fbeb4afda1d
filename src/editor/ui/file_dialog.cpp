#include "file_dialog.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>

#include "paths.h"

namespace primo::editor {
namespace fs = std::filesystem;
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

std::string human_size(unsigned long long bytes) {
  char text[32];
  if (bytes >= 1ull << 20)
    std::snprintf(text, sizeof text, "%.1f MB", double(bytes) / double(1ull << 20));
  else if (bytes >= 1ull << 10)
    std::snprintf(text, sizeof text, "%.0f kB", double(bytes) / double(1ull << 10));
  else
    std::snprintf(text, sizeof text, "%llu B", bytes);
  return text;
}

}  // namespace

void FileDialog::open(Mode mode, std::string title, std::vector<std::string> extensions,
                      std::string folder, std::string file_name) {
  mode_ = mode;
  title_ = std::move(title);
  extensions_ = std::move(extensions);
  name_ = std::move(file_name);
  error_.clear();
  std::error_code ec;
  if (folder.empty() || !fs::is_directory(folder, ec)) folder = fs::current_path(ec).string();
  enter(folder);
  open_ = request_popup_ = focus_name_ = true;
  ++openings_;
}

void FileDialog::enter(const std::string& folder) {
  std::error_code ec;
  fs::path p = fs::absolute(folder, ec).lexically_normal();
  if (p.has_filename() == false && p != p.root_path()) p = p.parent_path();
  folder_ = p.string();
  path_field_ = folder_;
  selected_ = -1;
  refresh();
}

void FileDialog::refresh() {
  entries_.clear();
  error_.clear();
  std::error_code ec;
  fs::directory_iterator it(folder_, fs::directory_options::skip_permission_denied, ec);
  if (ec) {
    error_ = "Cannot list " + folder_ + ": " + ec.message();
    return;
  }
  for (const fs::directory_entry& e : it) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::error_code ignored;
    Entry entry{name, e.is_directory(ignored), 0};
    if (!entry.folder) {
      const std::string ext = lower(e.path().extension().string());
      if (!extensions_.empty() && std::find(extensions_.begin(), extensions_.end(), ext) == extensions_.end())
        continue;
      // A mesh's orientation file (model_orientation.h) is .json but no scenario to open.
      const std::string suffix = ".orientation.json";
      if (lower(name).size() > suffix.size() &&
          lower(name).compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        continue;
      entry.size = e.file_size(ignored);
    }
    entries_.push_back(entry);
  }
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    if (a.folder != b.folder) return a.folder;
    return lower(a.name) < lower(b.name);
  });
}

bool FileDialog::accept(std::string& path) {
  std::string name = name_;
  if (name.empty()) {
    error_ = "Choose a file";
    return false;
  }
  fs::path p = fs::path(name).is_absolute() ? fs::path(name) : fs::path(folder_) / name;
  std::error_code ec;
  if (fs::is_directory(p, ec)) {
    enter(p.string());
    name_.clear();
    return false;
  }
  if (mode_ == Mode::Save && p.extension().empty() && !extensions_.empty()) p += extensions_.front();
  if (mode_ == Mode::Open && !fs::exists(p, ec)) {
    error_ = p.string() + " does not exist";
    return false;
  }
  path = p.string();
  open_ = false;
  ImGui::CloseCurrentPopup();
  return true;
}

bool FileDialog::draw(std::string& path) {
  if (!open_) return false;
  if (request_popup_) {
    ImGui::OpenPopup(title_.c_str());
    request_popup_ = false;
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowSize(ImVec2(std::min(720.0f, display.x - 40), std::min(480.0f, display.y - 40)),
                           ImGuiCond_Appearing);
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  bool keep = true;
  bool accepted = false;
  if (!ImGui::BeginPopupModal(title_.c_str(), &keep)) {
    if (!keep) open_ = false;
    return false;
  }
  // Places and path bar.
  if (ImGui::Button("Up")) enter(fs::path(folder_).parent_path().string());
  ImGui::SameLine();
  if (const char* home = std::getenv("HOME"); home && ImGui::Button("Home")) enter(home);
  ImGui::SameLine();
  if (ImGui::Button("Working folder")) enter(fs::current_path().string());
  ImGui::SameLine();
  if (ImGui::Button("Meshes")) enter(asset_dir() + "/meshes");
  ImGui::SameLine();
  if (ImGui::Button("Scenarios")) enter(asset_dir() + "/scenarios");
  ImGui::SetNextItemWidth(-1);
  if (ImGui::InputText("##path", &path_field_, ImGuiInputTextFlags_EnterReturnsTrue)) {
    std::error_code ec;
    if (fs::is_directory(path_field_, ec)) {
      enter(path_field_);
    } else {
      name_ = path_field_;
      accepted = accept(path);
    }
  }

  // Listing.
  const float footer = ImGui::GetFrameHeightWithSpacing() * 2.2f;
  ImGui::BeginChild("entries", ImVec2(0, -footer), true);
  std::string go_into;
  for (int i = 0; i < int(entries_.size()); ++i) {
    const Entry& e = entries_[i];
    const std::string label = (e.folder ? "[dir]  " : "       ") + e.name;
    if (ImGui::Selectable(label.c_str(), selected_ == i, ImGuiSelectableFlags_AllowDoubleClick)) {
      selected_ = i;
      if (!e.folder) name_ = e.name;
      if (ImGui::IsMouseDoubleClicked(0)) {
        if (e.folder)
          go_into = (fs::path(folder_) / e.name).string();
        else
          accepted = accept(path);
      }
    }
    if (!e.folder) {
      ImGui::SameLine(ImGui::GetWindowWidth() - 90);
      ImGui::TextDisabled("%s", human_size(e.size).c_str());
    }
  }
  if (entries_.empty()) ImGui::TextDisabled(error_.empty() ? "(no matching files)" : "%s", error_.c_str());
  ImGui::EndChild();
  if (!go_into.empty()) enter(go_into);

  // Name and buttons.
  ImGui::SetNextItemWidth(-200);
  if (focus_name_) {
    ImGui::SetKeyboardFocusHere();
    focus_name_ = false;
  }
  // A new field at each opening: Dear ImGui keeps the cursor of a text field it has seen and
  // selects the text only of a field new to it, so a name typed into the second dialog went
  // into the proposed name where the cursor had been.
  ImGui::PushID(openings_);
  if (ImGui::InputText("##name", &name_, ImGuiInputTextFlags_EnterReturnsTrue)) accepted = accept(path);
  ImGui::PopID();
  ImGui::SameLine();
  if (ImGui::Button(mode_ == Mode::Open ? "Open" : "Save", ImVec2(90, 0))) accepted = accept(path);
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(90, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
    open_ = false;
    ImGui::CloseCurrentPopup();
  }
  std::string filter;
  for (const auto& ext : extensions_) filter += (filter.empty() ? "" : " ") + ext;
  if (!error_.empty() && !entries_.empty())
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", error_.c_str());
  else if (mode_ == Mode::Save && !name_.empty() && fs::exists(fs::path(folder_) / name_))
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "%s exists and will be replaced", name_.c_str());
  else
    ImGui::TextDisabled("Files: %s", filter.c_str());
  ImGui::EndPopup();
  if (!keep) open_ = false;
  return accepted;
}

}  // namespace primo::editor
