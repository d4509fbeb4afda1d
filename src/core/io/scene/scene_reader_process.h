#pragma once
// Assimp reads scene files in a child process of its own. Its readers crash, overflow the heap
// or exhaust memory on files that no check before them can fully describe (a COLLADA node that
// instances itself or nests 7,000 deep, an accessor offset of 4e9, FBX models that are their own
// parents, a 3MF component that refers to itself, instancing bombs in each format), and in the
// editor such a crash took the unsaved work with it. In a child, a crash, a memory bomb or a
// hang ends that process only and becomes one line naming the file. The child sends the baked
// soup back through a pipe; the parent kills it when it outgrows its memory or time.

#include <cstddef>
#include <functional>
#include <string>

#include "mesh_import_assimp.h"

namespace primo::detail {

struct ReaderProcessLimits {
  size_t memory_bytes = 0;  // resident memory the child may reach
  double seconds = 0;       // wall-clock time the child may take
};

// The limits for an input of `input_bytes` (the file and the files it refers to): 2 GB plus
// 200 bytes per input byte (a zlib-compressed FBX array inflates at most ~1,000 times, a real
// scene's structures take tens of bytes per byte read) within three quarters of the machine's
// memory, and 60 s plus 2 s per MB.
ReaderProcessLimits reader_process_limits(size_t input_bytes);

// Runs `read` in a child process and returns the soup it made. Throws Error "<path>: cannot
// read: ..." with `format` named (e.g. "COLLADA") when `read` throws (its message is kept),
// when the child crashes, outgrows `limits` or cannot be started. `read` runs in a forked copy
// of this process with one thread: it must not use the thread pool.
SceneSoup read_in_child_process(const std::string& path, const std::string& format,
                                const ReaderProcessLimits& limits,
                                const std::function<SceneSoup()>& read);

}  // namespace primo::detail
