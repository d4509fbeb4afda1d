#pragma once
// Parallel loops that give the same result on any number of threads. Work is cut into chunks
// whose boundaries depend only on the size of the work, never on the number of threads, and
// whatever is summed over chunks is summed in chunk order; the chunks run on one persistent
// pool of worker threads (oneTBB's), as many as the machine has unless set_thread_count says
// otherwise. So a run on a 32-core workstation and one on a 2-core laptop produce the same
// bits, and `--threads 1` is a faithful way to measure the serial cost.

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace primo {

// Items (bodies, joints) per chunk below which a loop is not split: per-item work of a few
// hundred flops needs about this many to pay for a task.
inline constexpr size_t kParallelGrain = 8192;

// The threads every parallel loop may use: 0 (the default) all hardware threads. Affects
// speed only. Not to be called while a parallel loop runs.
void set_thread_count(int threads);
// What parallel loops use now (at least 1).
int thread_count();

// The chunks [0, n) is cut into: `chunks` consecutive ranges of nearly equal size, at most
// max(1, n / grain) of them and at most 256.
size_t chunk_count(size_t n, size_t grain);
inline size_t chunk_begin(size_t n, size_t chunks, size_t k) { return n * k / chunks; }

// Runs task(k) for k in [0, count), in parallel; returns when all have run. Tasks must not
// write what another task reads or writes.
void parallel_tasks(size_t count, const std::function<void(size_t)>& task);

// Calls body(begin, end) on the chunks of [0, n) (one call on the calling thread when n is
// below two grains).
template <class Body>
void parallel_chunks(size_t n, size_t grain, Body&& body) {
  const size_t chunks = chunk_count(n, grain);
  if (chunks <= 1) {
    if (n > 0) body(size_t(0), n);
    return;
  }
  parallel_tasks(chunks, [&](size_t k) {
    body(chunk_begin(n, chunks, k), chunk_begin(n, chunks, k + 1));
  });
}

// to = from, the elements copied in parallel when `to` has their number already (a state kept
// from iteration to iteration; otherwise copied at once). A state of 180,000 bodies is 17 MB:
// copied on one thread it left the other cores idle for 5-8 ms.
template <class T>
void parallel_copy(const std::vector<T>& from, std::vector<T>& to) {
  if (to.size() != from.size()) {  // a fresh copy at once: resizing first would construct
    to = from;
    return;
  }
  parallel_chunks(from.size(), kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) to[i] = from[i];
  });
}

// v = n copies of `value`, written in parallel: the first touch of fresh memory is a page
// fault per 4 KB, and the solver's work vectors at 240k faces are tens of MB each (types that
// initialize themselves are still constructed on the calling thread by the resize).
template <class T>
void parallel_assign(std::vector<T>& v, size_t n, const T& value) {
  v.resize(n);
  parallel_chunks(n, kParallelGrain, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) v[i] = value;
  });
}

// combine(...combine(combine(zero, part(chunk 0)), part(chunk 1))..., part(chunk K-1)): the
// chunks' results folded in chunk order, so the result does not depend on the thread count.
template <class T, class Part, class Combine>
T parallel_reduce(size_t n, size_t grain, T zero, Part&& part, Combine&& combine) {
  const size_t chunks = chunk_count(n, grain);
  if (chunks <= 1) return n > 0 ? T(combine(zero, part(size_t(0), n))) : zero;
  std::vector<T> partial(chunks, zero);
  parallel_tasks(chunks, [&](size_t k) {
    partial[k] = part(chunk_begin(n, chunks, k), chunk_begin(n, chunks, k + 1));
  });
  T total = zero;
  for (const T& p : partial) total = combine(total, p);
  return total;
}

// sum over the chunks of [0, n) of part(begin, end), added in chunk order.
template <class T, class Part>
T parallel_sum(size_t n, size_t grain, T zero, Part&& part) {
  return parallel_reduce(n, grain, zero, std::forward<Part>(part),
                         [](const T& a, const T& b) { return T(a + b); });
}

}  // namespace primo
