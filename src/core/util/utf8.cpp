#include "primo/util/utf8.h"

#include <cstdint>
#include <cstdio>

namespace primo {
namespace {

// The length of the well-formed UTF-8 sequence at text[i], or 0 when there is none.
size_t sequence_length(std::string_view text, size_t i) {
  const auto byte = [&](size_t k) { return uint8_t(text[k]); };
  const uint8_t lead = byte(i);
  if (lead < 0x80) return 1;
  size_t n;
  uint32_t code;
  if (lead >= 0xC2 && lead <= 0xDF) n = 2, code = lead & 0x1Fu;
  else if (lead >= 0xE0 && lead <= 0xEF) n = 3, code = lead & 0x0Fu;
  else if (lead >= 0xF0 && lead <= 0xF4) n = 4, code = lead & 0x07u;
  else return 0;
  if (i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3Fu);
  }
  const bool overlong = (n == 3 && code < 0x800) || (n == 4 && code < 0x10000);
  const bool surrogate = code >= 0xD800 && code <= 0xDFFF;
  return overlong || surrogate || code > 0x10FFFF ? 0 : n;
}

}  // namespace

bool is_valid_utf8(std::string_view text) {
  for (size_t i = 0; i < text.size();) {
    const size_t n = sequence_length(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string escape_invalid_utf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const size_t n = sequence_length(text, i);
    if (n == 0) {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", unsigned(uint8_t(text[i])));
      out += hex;
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
}

}  // namespace primo
