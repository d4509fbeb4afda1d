#include "run_deadline.h"

#include <cstdio>
#include <cstdlib>

namespace primo::editor {
namespace {

RunDeadline::Clock::time_point after(double seconds) {
  return RunDeadline::Clock::now() + std::chrono::duration_cast<RunDeadline::Clock::duration>(
                                         std::chrono::duration<double>(seconds));
}

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", seconds);
  return text;
}

}  // namespace

RunDeadline::RunDeadline(double seconds, std::string what, double grace)
    : seconds_(seconds),
      grace_(grace),
      deadline_(after(seconds)),
      last_chance_(after(seconds + grace)),
      what_(std::move(what)),
      watchdog_([this] { watch(); }) {}

RunDeadline::~RunDeadline() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_requested_.notify_all();
  watchdog_.join();
}

std::string RunDeadline::shown() const { return seconds_text(seconds_); }

void RunDeadline::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (stop_requested_.wait_until(lock, last_chance_, [this] { return stopping_; })) return;
  // The window's loop is stuck: nothing can be saved from this thread while it may be writing,
  // and waiting longer is the hang --timeout exists to prevent.
  std::fprintf(stderr,
               "primo edit: error: %s: still running %s after the --timeout of %s; stopped\n",
               what_.c_str(), seconds_text(grace_).c_str(), shown().c_str());
  std::fflush(stderr);
  std::_Exit(1);
}

}  // namespace primo::editor
