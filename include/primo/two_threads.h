#pragma once
// Splitting a loop over two threads, the cores this application is built for. A second
// thread is started only for ranges large enough to pay for it (tens of microseconds).

#include <cstddef>
#include <thread>

namespace primo {

// Bodies or joints worth a second thread for per-item work of a few hundred flops.
inline constexpr size_t kSecondThreadFrom = 20000;

// Calls body(begin, end) on [0, n/2) and [n/2, n) on two threads when n >= min_parallel,
// otherwise body(0, n) on the calling thread. The halves are fixed, so results that depend on
// the split (sums) are reproducible.
template <class Body>
void on_two_threads(size_t n, size_t min_parallel, Body&& body) {
  if (n < min_parallel) {
    body(size_t(0), n);
    return;
  }
  const size_t middle = n / 2;
  std::thread other([&] { body(middle, n); });
  body(size_t(0), middle);
  other.join();
}

}  // namespace primo
