#pragma once
// The files the user opened or saved last, newest first, kept between runs in
// config_folder()/recent.json (File > Open Recent).

#include <string>
#include <vector>

namespace primo::editor {

class RecentFiles {
 public:
  static constexpr size_t kMaxEntries = 10;
  // Reads `path` (default: config_folder()/recent.json). A missing or unreadable file is an
  // empty list: the list is a convenience, never a reason to fail.
  explicit RecentFiles(std::string path = {});
  const std::vector<std::string>& entries() const { return entries_; }
  // Puts the absolute form of `file` first (once), drops the oldest beyond kMaxEntries, and
  // writes the list. Returns false when it could not be written.
  bool add(const std::string& file);
  bool remove(const std::string& file);
  const std::string& path() const { return path_; }

 private:
  bool write() const;
  std::string path_;
  std::vector<std::string> entries_;
};

}  // namespace primo::editor
