#include "primo/io/json_limits.h"

#include "primo/util/error.h"

namespace primo {

void check_json_depth(std::string_view text, const std::string& label) {
  int depth = 0;
  bool in_string = false;
  size_t line = 1, line_start = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') line = line + 1, line_start = i + 1;
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw Error(label + ": (root): arrays and objects nested deeper than " +
                    std::to_string(kMaxJsonDepth) + " levels at line " + std::to_string(line) +
                    ", column " + std::to_string(i - line_start + 1));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

}  // namespace primo
