#pragma once
// Commands that run the engine on a file (`primo deform`, `primo replay`) report its errors as
// one line naming that file.

#include <string>

namespace primo::app {

// Inside a catch block: rethrows the exception being handled as a primo::Error whose message
// starts with `file` (unchanged when it already does); std::bad_alloc becomes "out of memory".
[[noreturn]] void rethrow_naming(const std::string& file);

}  // namespace primo::app
