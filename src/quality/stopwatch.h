#pragma once
// Wall and CPU time of a piece of work. On this project's shared 2-core machine the wall time
// of a run depends on what else runs; the process CPU time (all threads) does much less, so the
// quality benchmark reports both.

#include <time.h>

#include <chrono>

namespace primo::quality {

struct Seconds {
  double wall = 0.0;
  double cpu = 0.0;  // of the whole process, summed over its threads
};

class Stopwatch {
 public:
  Stopwatch() : wall_start_(std::chrono::steady_clock::now()), cpu_start_(process_cpu()) {}
  Seconds elapsed() const {
    return {std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count(),
            process_cpu() - cpu_start_};
  }

 private:
  static double process_cpu() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
  std::chrono::steady_clock::time_point wall_start_;
  double cpu_start_;
};

}  // namespace primo::quality
