#pragma once
// Checks of the command line's number options. CLI11's Range, PositiveNumber and
// NonNegativeNumber compare with < and >, which NaN passes (`--drag-prediction nan` ran the
// benchmark on NaN), and the last two take infinity. Every number option of `primo` is checked
// by one of these instead: a word, nan or inf is one error line naming the option.
// Header-only: the app's sources are listed one by one in src/CMakeLists.txt.

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace primo::app {
namespace detail {

inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

// A validator accepting finite numbers for which `accept` holds; `bounds` says which ("from 0
// to 2"), in --help and in the error.
template <typename Accept>
CLI::Validator finite_number(const std::string& bounds, Accept accept) {
  return CLI::Validator(
      [bounds, accept](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(value) || !accept(value))
          return "expected a number " + bounds + ", got " + text;
        return "";
      },
      bounds);
}

}  // namespace detail

// A finite number from `lowest` to `highest`, both included. For integer options too: CLI11
// then refuses a fraction ("Could not convert").
inline CLI::Validator finite_range(double lowest, double highest) {
  return detail::finite_number(
      "from " + detail::number_text(lowest) + " to " + detail::number_text(highest),
      [lowest, highest](double value) { return value >= lowest && value <= highest; });
}

// A finite number more than 0 and at most `highest` (sizes, durations).
inline CLI::Validator finite_positive(double highest) {
  return detail::finite_number("more than 0 and at most " + detail::number_text(highest),
                               [highest](double value) { return value > 0.0 && value <= highest; });
}

}  // namespace primo::app
