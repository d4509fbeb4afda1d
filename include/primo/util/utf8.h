#pragma once
// File names on Linux are bytes; JSON strings (scenarios, sessions, the editor's lists) hold
// Unicode text only. These tell the two apart where a name goes into JSON.

#include <string>
#include <string_view>

namespace primo {

// Whether `text` is well-formed UTF-8 (no stray continuation bytes, overlong forms, surrogates
// or code points beyond U+10FFFF).
bool is_valid_utf8(std::string_view text);

// `text` with each byte that is not part of well-formed UTF-8 written as %XX (hex), so that a
// name made from it is text: "caf\xE9.obj" -> "caf%E9.obj". Valid text is returned unchanged.
std::string escape_invalid_utf8(std::string_view text);

}  // namespace primo
