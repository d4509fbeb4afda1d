#include "primo/io/input_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "primo/util/error.h"

namespace fs = std::filesystem;

namespace primo {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw Error(path + ": " + problem);
}

// "a named pipe": what the user gave instead of a file, in their words.
const char* kind_of(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory:
      return "a folder";
    case fs::file_type::fifo:
      return "a named pipe";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "a special file";
  }
}

fs::file_type type_of(mode_t mode) {
  if (S_ISREG(mode)) return fs::file_type::regular;
  if (S_ISDIR(mode)) return fs::file_type::directory;
  if (S_ISFIFO(mode)) return fs::file_type::fifo;
  if (S_ISCHR(mode)) return fs::file_type::character;
  if (S_ISBLK(mode)) return fs::file_type::block;
  if (S_ISSOCK(mode)) return fs::file_type::socket;
  return fs::file_type::unknown;
}

[[noreturn]] void fail_too_large(const std::string& path, std::uintmax_t bytes) {
  char limit[32];
  std::snprintf(limit, sizeof limit, "%g GiB", double(kMaxInputFileBytes) / double(1 << 30));
  fail(path, "the file is " + std::to_string(bytes) + " bytes, more than an input may be (" +
                 limit + " = " + std::to_string(kMaxInputFileBytes) + " bytes)");
}

void check_type_and_size(const std::string& path, fs::file_type type, std::uintmax_t bytes) {
  if (type != fs::file_type::regular)
    fail(path, std::string("not a regular file (") + kind_of(type) + ")");
  if (bytes > kMaxInputFileBytes) fail_too_large(path, bytes);
}

// Closes the descriptor on every way out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(FileDescriptor&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

// The checks of check_input_file, and the file opened for reading. The type is checked before
// the open, which a pipe would block and a device may answer to, and again after it on what
// was opened, in case the file was replaced in between: the open does not block (O_NONBLOCK;
// reads of a regular file ignore the flag).
FileDescriptor open_input_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found)
    fail(path, std::string("cannot open: ") + std::strerror(ENOENT));
  if (ec) fail(path, "cannot open: " + ec.message());
  const std::uintmax_t bytes = fs::is_regular_file(status) ? fs::file_size(path, ec) : 0;
  if (ec) fail(path, "cannot open: " + ec.message());
  check_type_and_size(path, status.type(), bytes);

  FileDescriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (file.get() < 0) fail(path, std::string("cannot open: ") + std::strerror(errno));
  struct stat info {};
  if (::fstat(file.get(), &info) != 0)
    fail(path, std::string("cannot read: ") + std::strerror(errno));
  check_type_and_size(path, type_of(info.st_mode), std::uintmax_t(info.st_size));
  return file;
}

}  // namespace

void check_input_file(const std::string& path) { open_input_file(path); }

std::string read_input_file(const std::string& path) {
  const FileDescriptor file = open_input_file(path);
  struct stat info {};
  std::string bytes;
  if (::fstat(file.get(), &info) == 0) bytes.reserve(size_t(info.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t count = ::read(file.get(), buffer, sizeof buffer);
    if (count == 0) break;
    if (count < 0) {
      if (errno == EINTR) continue;
      fail(path, std::string("cannot read: ") + std::strerror(errno));
    }
    bytes.append(buffer, size_t(count));
    // The size was checked, but a file may grow while it is read (or lie, as in /proc).
    if (bytes.size() > kMaxInputFileBytes) fail_too_large(path, bytes.size());
  }
  return bytes;
}

}  // namespace primo
