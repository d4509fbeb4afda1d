#include "recent_files.h"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "primo/util/error.h"
#include "primo/io/input_files.h"
#include "primo/io/output_files.h"
#include "primo/util/utf8.h"
#include "user_folders.h"

namespace primo::editor {
namespace fs = std::filesystem;

RecentFiles::RecentFiles(std::string path)
    : path_(path.empty() ? config_folder() + "/recent.json" : std::move(path)) {
  std::error_code ec;
  if (!fs::exists(path_, ec)) return;
  std::string text;
  try {
    text = read_input_file(path_);  // a pipe or device in its place must not block the start
  } catch (const Error&) {
    return;  // the list is a convenience: unreadable, it starts empty
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object() || !j.contains("files") || !j["files"].is_array()) return;
  for (const auto& f : j["files"])
    if (f.is_string() && entries_.size() < kMaxEntries) entries_.push_back(f.get<std::string>());
}

bool RecentFiles::add(const std::string& file) {
  std::error_code ec;
  const std::string absolute = fs::absolute(file, ec).lexically_normal().string();
  const std::string entry = ec ? file : absolute;
  entries_.erase(std::remove(entries_.begin(), entries_.end(), entry), entries_.end());
  entries_.insert(entries_.begin(), entry);
  if (entries_.size() > kMaxEntries) entries_.resize(kMaxEntries);
  return write();
}

bool RecentFiles::remove(const std::string& file) {
  entries_.erase(std::remove(entries_.begin(), entries_.end(), file), entries_.end());
  return write();
}

bool RecentFiles::write() const {
  try {
    std::error_code ec;
    fs::create_directories(fs::path(path_).parent_path(), ec);
    // A file name that is not UTF-8 cannot be a JSON string: it stays in the menu for this
    // run, not in the file.
    std::vector<std::string> text;
    for (const std::string& entry : entries_)
      if (is_valid_utf8(entry)) text.push_back(entry);
    write_text_atomically(path_, nlohmann::json{{"files", text}}.dump(2) + "\n");
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace primo::editor
