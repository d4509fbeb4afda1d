#pragma once
// Limits on JSON text read from files (scenarios, sessions), checked before the text is parsed.

#include <string>
#include <string_view>

namespace primo {

// Arrays and objects nested deeper than this are refused: no PriMo file nests deeper than 6,
// and nlohmann's parser with a position-tracking callback takes time and memory quadratic in
// the depth (30,000 levels: 38 s and 1.7 GB).
inline constexpr int kMaxJsonDepth = 64;

// Throws primo::Error "<label>: (root): nesting deeper than 64 levels at line L, column C"
// when `text` opens more than kMaxJsonDepth arrays or objects at once (strings are skipped).
void check_json_depth(std::string_view text, const std::string& label);

}  // namespace primo
