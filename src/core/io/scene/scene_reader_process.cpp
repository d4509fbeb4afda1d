#include "scene_reader_process.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <new>

#include "mesh_attributes_codec.h"
#include "primo/util/error.h"

#if defined(__SANITIZE_ADDRESS__)
#define PRIMO_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PRIMO_ADDRESS_SANITIZER 1
#endif
#endif

namespace primo::detail {
namespace {

constexpr uint32_t kMagic = 0x53534d50;  // "PMSS"

enum class Outcome : uint8_t { kSoup = 0, kError = 1, kOutOfMemory = 2, kOtherException = 3 };

// The child's side: everything goes into one buffer, written when complete, so a crash while
// baking leaves an incomplete reply, never a plausible one.
class ReplyWriter {
 public:
  void u8(uint8_t v) { bytes_.push_back(char(v)); }
  void u64(uint64_t v) { raw(&v, sizeof v); }
  void text(const std::string& s) {
    u64(s.size());
    bytes_ += s;
  }
  void raw(const void* data, size_t n) { bytes_.append(static_cast<const char*>(data), n); }

  void soup(const SceneSoup& scene) {
    size_t size = 3 * sizeof(uint64_t) + 1 + scene.note.size() + scene.parts.size() +
                  2 * sizeof(uint64_t) + scene.soup.points.size() * 3 * sizeof(double);
    for (const auto& face : scene.soup.faces) size += sizeof(uint64_t) + face.size() * sizeof(int);
    bytes_.reserve(size);
    u64(kMagic);
    u8(uint8_t(Outcome::kSoup));
    text(scene.note);
    text(scene.parts);
    u64(scene.soup.points.size());
    for (const Vec3& p : scene.soup.points) raw(p.data(), 3 * sizeof(double));
    u64(scene.soup.faces.size());
    for (const auto& face : scene.soup.faces) {
      u64(face.size());
      raw(face.data(), face.size() * sizeof(int));
    }
    text(encode_attributes(scene.soup.attributes));
  }

  void message(Outcome outcome, const std::string& what) {
    bytes_.clear();
    u64(kMagic);
    u8(uint8_t(outcome));
    text(what);
  }

  // The reply's size first, so the parent takes it in one buffer.
  bool send(int fd) const {
    const uint64_t size = bytes_.size();
    return send(fd, &size, sizeof size) && send(fd, bytes_.data(), bytes_.size());
  }

 private:
  static bool send(int fd, const void* data, size_t n) {
    const char* bytes = static_cast<const char*>(data);
    size_t sent = 0;
    while (sent < n) {
      const ssize_t written = ::write(fd, bytes + sent, n - sent);
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) return false;
      sent += size_t(written);
    }
    return true;
  }

  std::string bytes_;
};

// The parent's side; a reply that does not hold together reads as incomplete.
class ReplyReader {
 public:
  explicit ReplyReader(const std::string& bytes) : bytes_(bytes) {}
  bool u8(uint8_t& v) { return raw(&v, 1); }
  bool u64(uint64_t& v) { return raw(&v, sizeof v); }
  bool text(std::string& s) {
    uint64_t n;
    if (!u64(n) || n > left()) return false;
    s.assign(bytes_, at_, size_t(n));
    at_ += size_t(n);
    return true;
  }
  bool raw(void* out, size_t n) {
    if (n > left()) return false;
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
    return true;
  }
  size_t left() const { return bytes_.size() - at_; }

 private:
  const std::string& bytes_;
  size_t at_ = 0;
};

bool decode_soup(ReplyReader& in, SceneSoup& scene) {
  uint64_t n_points, n_faces;
  if (!in.text(scene.note) || !in.text(scene.parts) || !in.u64(n_points) ||
      n_points > in.left() / (3 * sizeof(double)))
    return false;
  scene.soup.points.resize(size_t(n_points));
  for (Vec3& p : scene.soup.points)
    if (!in.raw(p.data(), 3 * sizeof(double))) return false;
  if (!in.u64(n_faces) || n_faces > in.left() / sizeof(uint64_t)) return false;
  scene.soup.faces.resize(size_t(n_faces));
  for (auto& face : scene.soup.faces) {
    uint64_t size;
    if (!in.u64(size) || size > in.left() / sizeof(int)) return false;
    face.resize(size_t(size));
    if (!in.raw(face.data(), face.size() * sizeof(int))) return false;
  }
  std::string attributes;
  if (!in.text(attributes) || !decode_attributes(attributes, scene.soup.attributes)) return false;
  return in.left() == 0;
}

// Resident and virtual sizes from /proc/<pid>/statm, in bytes (0 when unreadable).
struct MemoryUse {
  size_t virtual_bytes = 0, resident_bytes = 0;
};

MemoryUse memory_use(const std::string& statm) {
  std::ifstream in(statm);
  size_t pages_virtual = 0, pages_resident = 0;
  in >> pages_virtual >> pages_resident;
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  return {pages_virtual * page, pages_resident * page};
}

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g s", seconds);
  return text;
}

std::string gigabytes(size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GB", double(bytes) / 1e9);
  return text;
}

[[noreturn]] void run_child(int fd, const ReaderProcessLimits& limits,
                            const std::function<SceneSoup()>& read) {
  // The parent's handlers (the editor saves its work on SIGTERM) are not the child's.
  // A crash ends the child plainly, under its own signal, which the parent reports.
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT})
    std::signal(sig, SIG_DFL);
  rlimit none{0, 0};
  setrlimit(RLIMIT_CORE, &none);
  // A hard limit on the address space makes a memory bomb a bad_alloc, not a machine that
  // swaps; AddressSanitizer reserves terabytes of address space, so there the parent's watch
  // of the resident size is the limit.
#ifndef PRIMO_ADDRESS_SANITIZER
  const rlimit space{memory_use("/proc/self/statm").virtual_bytes + limits.memory_bytes,
                     RLIM_INFINITY};
  setrlimit(RLIMIT_AS, &space);
#endif
  const rlim_t cpu = rlim_t(limits.seconds) + 1;
  const rlimit time{cpu, cpu + 1};
  setrlimit(RLIMIT_CPU, &time);

  ReplyWriter reply;
  try {
    reply.soup(read());
  } catch (const Error& e) {
    reply.message(Outcome::kError, e.what());
  } catch (const std::bad_alloc&) {
    reply.message(Outcome::kOutOfMemory, "");
  } catch (const std::exception& e) {
    reply.message(Outcome::kOtherException, e.what());
  } catch (...) {
    reply.message(Outcome::kOtherException, "an unknown exception");
  }
  // _exit: the parent's atexit handlers, static destructors and buffered streams are its own.
  _exit(reply.send(fd) ? 0 : 1);
}

// Kills and reaps the child unless it was reaped.
struct ChildProcess {
  pid_t pid = -1;
  ~ChildProcess() {
    if (pid > 0) {
      kill(pid, SIGKILL);
      wait_status();
    }
  }
  // The wait status, blocking; -1 when the child was reaped elsewhere (SIGCHLD ignored).
  int wait_status() {
    int status = 0;
    pid_t r;
    do r = waitpid(pid, &status, 0);
    while (r < 0 && errno == EINTR);
    pid = -1;
    return r < 0 ? -1 : status;
  }
  bool exited() {
    int status = 0;
    return waitpid(pid, &status, WNOHANG) == pid ? (saved = status, pid = -1, true) : false;
  }
  int saved = 0;
};

struct FileDescriptor {
  int fd = -1;
  ~FileDescriptor() { close_now(); }
  void close_now() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw Error(path + ": cannot read: " + what);
}

}  // namespace

ReaderProcessLimits reader_process_limits(size_t input_bytes) {
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  const double wanted = 2e9 + 200.0 * double(input_bytes);
  ReaderProcessLimits limits;
  limits.memory_bytes = size_t(physical > 0 ? std::min(wanted, 0.75 * physical) : wanted);
  limits.seconds = 60.0 + 2.0 * double(input_bytes) / 1e6;
  return limits;
}

SceneSoup read_in_child_process(const std::string& path, const std::string& format,
                                const ReaderProcessLimits& limits,
                                const std::function<SceneSoup()>& read) {
  const auto fail = [&](const std::string& what) { refuse(path, what); };
  // The two limits, whether the parent's watch or the child's own rlimit met them first.
  const auto out_of_time = [&] {
    fail("reading this " + format + " file took longer than " + seconds_text(limits.seconds));
  };
  const auto out_of_memory = [&] {
    fail("reading this " + format + " file needs more than " + gigabytes(limits.memory_bytes) +
         " of memory (the limit for a file of its size)");
  };
  int ends[2];
  if (pipe2(ends, O_CLOEXEC) != 0)
    fail(std::string("could not start the ") + format + " reader (" + std::strerror(errno) + ")");
  FileDescriptor from_child{ends[0]}, to_parent{ends[1]};
  // The child starts with the parent's resident pages (shared until written): its growth is
  // what it allocates.
  const size_t resident_at_start = memory_use("/proc/self/statm").resident_bytes;
  ChildProcess child;
  child.pid = fork();
  if (child.pid < 0)
    fail(std::string("could not start the ") + format + " reader (" + std::strerror(errno) + ")");
  if (child.pid == 0) {
    from_child.fd = -1;
    run_child(to_parent.fd, limits, read);
  }
  to_parent.close_now();
  fcntl(from_child.fd, F_SETFL, O_NONBLOCK);

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto last_memory_check = start;
  const std::string statm = "/proc/" + std::to_string(child.pid) + "/statm";
  std::string reply;
  char chunk[1 << 16];
  bool exited = false, announced = false;
  for (;;) {
    pollfd watch{from_child.fd, POLLIN, 0};
    const int ready = poll(&watch, 1, 50);
    bool end = false;
    if (ready > 0) {
      for (;;) {
        const ssize_t n = ::read(from_child.fd, chunk, sizeof chunk);
        if (n > 0) {
          reply.append(chunk, size_t(n));
          // The size the child announced, within its memory limit, is taken in one buffer.
          if (!announced && reply.size() >= sizeof(uint64_t)) {
            announced = true;
            uint64_t size;
            std::memcpy(&size, reply.data(), sizeof size);
            if (size <= limits.memory_bytes) reply.reserve(size_t(size) + sizeof size);
          }
          continue;
        }
        if (n == 0) end = true;
        break;  // EAGAIN: drained for now; EINTR: poll again
      }
    } else if (!exited && child.exited()) {
      // A pipe held open by another process forked meanwhile gives no end of file: the
      // child's exit ends the reply.
      exited = true;
      continue;  // read what it left
    } else if (exited) {
      end = true;
    }
    if (end) break;
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - start).count() > limits.seconds) out_of_time();
    if (now - last_memory_check > std::chrono::milliseconds(50) && !exited) {
      last_memory_check = now;
      const size_t resident = memory_use(statm).resident_bytes;
      if (resident > resident_at_start + limits.memory_bytes) out_of_memory();
    }
  }
  from_child.close_now();
  const int status = exited ? child.saved : child.wait_status();

  ReplyReader in(reply);
  uint64_t size = 0, magic = 0;
  uint8_t outcome = 0;
  if (in.u64(size) && size == in.left() && in.u64(magic) && magic == kMagic && in.u8(outcome)) {
    SceneSoup scene;
    std::string what;
    switch (Outcome(outcome)) {
      case Outcome::kSoup:
        if (decode_soup(in, scene)) return scene;
        break;
      case Outcome::kError:
        if (in.text(what)) throw Error(what);
        break;
      case Outcome::kOutOfMemory:
        out_of_memory();
        break;
      case Outcome::kOtherException:
        if (in.text(what)) fail("not a valid " + format + " file (Assimp: " + what + ")");
        break;
    }
  }
  // No complete reply: how the child ended says why.
  if (status != -1 && WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    if (sig == SIGXCPU) out_of_time();
    if (sig == SIGKILL)
      fail("the " + format + " reader was killed (out of memory?) while reading this file");
    const char* name = strsignal(sig);
    fail("Assimp's " + format + " reader crashed on this file (" +
         (name ? std::string(name) : "signal " + std::to_string(sig)) +
         "); the file is damaged or uses what that reader mishandles");
  }
  fail("Assimp's " + format + " reader failed on this file (it ended with status " +
       std::to_string(status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
       " and no result); the file is damaged or uses what that reader mishandles");
  return {};  // fail throws
}

}  // namespace primo::detail
