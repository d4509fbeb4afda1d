#include "primo/io/output_files.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "primo/util/error.h"
#include "primo/io/mesh_io.h"

namespace fs = std::filesystem;

namespace primo {
namespace {

// Lower-case extension with the dot (".obj"), or "" when there is none.
std::string extension_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

fs::path folder_of(const std::string& path) {
  const fs::path target(path);
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

bool process_alive(long pid) { return pid > 0 && (::kill(pid_t(pid), 0) == 0 || errno != ESRCH); }

// Writes all of `bytes` to a new file and flushes it to disk; returns errno, 0 on success.
int write_whole_file(const std::string& file, const std::string& bytes) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) return errno;
  size_t done = 0;
  int error = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      error = errno;
      break;
    }
    done += size_t(n);
  }
  if (error == 0 && ::fsync(fd) != 0 && errno != EINVAL) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  return error;
}

// Removes files[from...], skipping empty names; ignores every error.
void remove_quietly(const std::vector<std::string>& files, size_t from = 0) {
  for (size_t i = from; i < files.size(); ++i) {
    std::error_code ignored;
    if (!files[i].empty()) fs::remove(files[i], ignored);
  }
}

}  // namespace

void check_output_path(const std::string& path) {
  const fs::path folder = folder_of(path);
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw Error(path + ": the folder " + fs::absolute(folder, ec).string() + " does not exist");
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) throw Error(path + ": cannot write: this is a folder, not a file");
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw Error(path +
                ": cannot write: this is a device or another special file, not a regular file");
}

void check_mesh_output_path(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl" && ext != ".om" &&
      ext != ".gltf" && ext != ".glb")
    throw Error(path + ": unknown output format '" + ext +
                "' (use .obj, .off, .ply, .stl, .om, .gltf or .glb)");
  check_output_path(path);
}

void check_distinct_files(const std::vector<NamedFile>& outputs,
                          const std::vector<NamedFile>& inputs) {
  const auto same = [](const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
    return fs::weakly_canonical(fs::absolute(a, ec), ec) ==
           fs::weakly_canonical(fs::absolute(b, ec), ec);
  };
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].path.empty()) continue;
    const auto refuse = [&](const NamedFile& other, const char* kind) {
      throw Error(outputs[i].path + ": " + outputs[i].role + " is the same file as " + kind +
                  other.role + " (" + other.path + "); nothing was written");
    };
    for (size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && same(outputs[i].path, outputs[j].path))
        refuse(outputs[j], "");
    for (const NamedFile& input : inputs)
      if (!input.path.empty() && same(outputs[i].path, input.path)) refuse(input, "");
  }
}

void remove_stale_partials(const std::string& folder, const std::string& prefix) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    size_t i = prefix.size();
    long pid = 0;
    while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i])) && pid < 1000000000)
      pid = pid * 10 + (name[i++] - '0');
    if (i == prefix.size() || (i < name.size() && name[i] != '-') || process_alive(pid)) continue;
    std::error_code ignored;
    fs::remove_all(it->path(), ignored);
  }
}

StagedOutputs::~StagedOutputs() {
  for (const auto& [temp, target] : staged_) {
    std::error_code ignored;
    fs::remove(temp, ignored);
  }
}

// ".<name>.primo-<kind>-" beside `path`: hidden, clearly PriMo's, and short enough that the
// whole name stays within the file system's limit.
std::string StagedOutputs::hidden_prefix(const std::string& path, const char* kind) {
  return "." + fs::path(path).filename().string().substr(0, 100) + ".primo-" + kind + "-";
}

// "<folder>/<prefix><pid>-<n><ext>": unique within this process and among live processes.
std::string StagedOutputs::hidden_name(const std::string& path, const std::string& prefix) {
  static std::atomic<unsigned> counter{0};
  return (folder_of(path) / (prefix + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
                             extension_of(path)))
      .string();
}

void StagedOutputs::stage(const std::string& path, const std::string& bytes) {
  check_output_path(path);
  const std::string folder = folder_of(path).string();
  // Ending in the real extension, so that a left-over partial still opens as what it is.
  const std::string prefix = hidden_prefix(path, "partial");
  remove_stale_partials(folder, prefix);
  remove_stale_partials(folder, hidden_prefix(path, "backup"));
  const std::string temp = hidden_name(path, prefix);
  const int error = write_whole_file(temp, bytes);
  if (error != 0) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw Error(path + ": cannot save: " + std::strerror(error) + " (nothing was written)");
  }
  staged_.emplace_back(temp, path);
}

void StagedOutputs::stage_mesh(const std::string& path, const Mesh& mesh) {
  stage(path, mesh_file_bytes(mesh, path));
}

void StagedOutputs::stage_mesh(const std::string& path, const Mesh& mesh,
                               const MeshAttributes& attributes) {
  stage(path, mesh_file_bytes(mesh, attributes, path));
}

// A second name for each existing target (a hard link: no copy, and restoring it is one
// atomic rename), so that a rename failing half-way through can put the earlier targets back.
// Throws before any target changed when a backup cannot be made.
std::vector<std::string> StagedOutputs::back_up_targets() const {
  std::vector<std::string> backups;
  for (const auto& staged : staged_) {
    const std::string& target = staged.second;
    std::string backup;  // none for a missing target (a rollback removes what the commit made)
    std::error_code ec;  // and none for a folder, which no file can be renamed onto
    const fs::file_status status = fs::symlink_status(target, ec);
    if (fs::exists(status) && !fs::is_directory(status)) {
      backup = hidden_name(target, hidden_prefix(target, "backup"));
      // A copy where the file system has no hard links.
      if (::link(target.c_str(), backup.c_str()) != 0 && !fs::copy_file(target, backup, ec)) {
        remove_quietly(backups);
        throw Error(target + ": cannot save: cannot keep a copy of the existing file (" +
                    ec.message() + "); nothing was written");
      }
    }
    backups.push_back(backup);
  }
  return backups;
}

void StagedOutputs::commit() {
  const std::vector<std::string> backups = back_up_targets();
  for (size_t i = 0; i < staged_.size(); ++i) {
    const auto& [temp, target] = staged_[i];
    if (std::rename(temp.c_str(), target.c_str()) != 0) {
      const int error = errno;
      throw Error(target + ": cannot save: cannot move the temporary file into place: " +
                  std::strerror(error) + roll_back(i, backups));
    }
  }
  remove_quietly(backups);
  staged_.clear();
}

// Puts the first `renamed` targets back as they were before commit(); returns the end of the
// error message: what was restored, or where the earlier file is when it could not be.
std::string StagedOutputs::roll_back(size_t renamed, const std::vector<std::string>& backups) {
  std::string restored, lost;
  for (size_t j = renamed; j-- > 0;) {
    const std::string& target = staged_[j].second;
    std::error_code ec;
    const bool ok = backups[j].empty() ? fs::remove(target, ec) || !ec
                                       : std::rename(backups[j].c_str(), target.c_str()) == 0;
    if (ok)
      restored += (restored.empty() ? "" : ", ") + target;
    else
      lost += "; " + target + " could not be put back: " +
              (backups[j].empty() ? "it is new" : "its earlier version is " + backups[j]);
  }
  remove_quietly(backups, renamed);
  if (!lost.empty()) return lost;
  return restored.empty() ? " (nothing was written)"
                          : " (nothing was written: " + restored + " put back as it was)";
}

void write_text_atomically(const std::string& path, const std::string& text) {
  StagedOutputs out;
  out.stage(path, text);
  out.commit();
}

}  // namespace primo
