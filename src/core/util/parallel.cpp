#include "primo/util/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>
#include <mutex>

namespace primo {
namespace {

// With a chosen count, loops run in an arena of that many slots, and a global_control lets
// oneTBB start that many workers even beyond the cores (so that 8 threads can be tested on 2).
// Without one, the default arena: every core the process may use.
std::mutex control_mutex;
std::unique_ptr<tbb::global_control> control;
std::unique_ptr<tbb::task_arena> arena;
int chosen_threads = 0;

}  // namespace

void set_thread_count(int threads) {
  std::lock_guard<std::mutex> lock(control_mutex);
  arena.reset();
  control.reset();
  chosen_threads = std::max(0, threads);
  if (chosen_threads > 0) {
    control = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, size_t(chosen_threads));
    arena = std::make_unique<tbb::task_arena>(chosen_threads);
  }
}

int thread_count() {
  if (chosen_threads > 0) return chosen_threads;
  return std::max(1, tbb::info::default_concurrency());
}

size_t chunk_count(size_t n, size_t grain) {
  return std::clamp<size_t>(n / std::max<size_t>(grain, 1), 1, 256);
}

void parallel_tasks(size_t count, const std::function<void(size_t)>& task) {
  if (count == 0) return;
  if (count == 1 || thread_count() == 1) {
    for (size_t k = 0; k < count; ++k) task(k);
    return;
  }
  // One task per chunk (simple_partitioner, grain 1): which thread runs a chunk never
  // changes what it computes.
  auto run = [&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, count, 1),
        [&](const tbb::blocked_range<size_t>& r) {
          for (size_t k = r.begin(); k != r.end(); ++k) task(k);
        },
        tbb::simple_partitioner());
  };
  if (arena)
    arena->execute(run);
  else
    run();
}

}  // namespace primo
