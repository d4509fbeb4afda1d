#pragma once

#include <stdexcept>
#include <string>

namespace primo {

// Every user-facing failure of the core (bad file, bad scenario, degenerate input) is an Error
// whose message is one line that names the file or JSON path and the problem.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace primo
