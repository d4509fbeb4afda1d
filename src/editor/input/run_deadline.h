#pragma once
// The --timeout of an automated editor run (`primo edit --script` or `--screenshot`,
// docs/editor.md). The window's loop asks expired() every frame and stops on its own,
// autosaving unsaved work as on SIGTERM. A loop that cannot get there (a frame or the shutdown
// waiting on a file that never ends, such as a FIFO) is ended by a watchdog thread, `grace`
// seconds after the deadline, with one line on stderr and exit status 1.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace primo::editor {

class RunDeadline {
 public:
  using Clock = std::chrono::steady_clock;

  // Starts counting and the watchdog. `what` begins the watchdog's message (e.g. the script).
  RunDeadline(double seconds, std::string what, double grace = 15.0);
  RunDeadline(const RunDeadline&) = delete;
  RunDeadline& operator=(const RunDeadline&) = delete;
  ~RunDeadline();  // stops the watchdog

  bool expired() const { return Clock::now() > deadline_; }
  double seconds() const { return seconds_; }
  // "20 s", "0.5 s": the timeout as messages show it.
  std::string shown() const;

 private:
  void watch();

  double seconds_, grace_;
  Clock::time_point deadline_;
  Clock::time_point last_chance_;
  std::string what_;
  std::mutex mutex_;
  std::condition_variable stop_requested_;
  bool stopping_ = false;
  std::thread watchdog_;
};

}  // namespace primo::editor
