#pragma once
// Asks the processor to bring memory in ahead of its use. Loops whose next reads are out of
// order (a coupling's bodies, a sparse matrix's rows in a sweep) wait on memory: the hardware
// prefetchers only follow streams, so such loops fetch a few items ahead. Few requests per
// item: restricting the 240k drag's couplings with every line of each body's state requested
// (about 12 a coupling) was no faster than without prefetching, and with the first line of
// each (7) a quarter faster.

#include <cstddef>

namespace primo {

constexpr size_t kCacheLine = 64;

// The line holding `p`.
inline void prefetch_line(const void* p) { __builtin_prefetch(p); }

// The lines at begin, begin + 64, ... below begin + bytes.
inline void prefetch_bytes(const void* begin, size_t bytes) {
  const char* p = static_cast<const char*>(begin);
  for (size_t offset = 0; offset < bytes; offset += kCacheLine) __builtin_prefetch(p + offset);
}

}  // namespace primo
