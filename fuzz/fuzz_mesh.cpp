// libFuzzer target for one mesh reader: the format is PRIMO_FUZZ_EXTENSION (".obj", ".off",
// ".ply", ".stl", ".om"), chosen at compile time. Bytes go through parse_mesh_bytes and, when
// they parse, mesh_from_soup's validation. A primo::Error is the expected outcome for bad
// bytes; anything else (a crash, a sanitizer report, another exception, a hang, a large
// allocation) is a finding.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "primo/util/error.h"
#include "primo/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const primo::PolygonSoup soup = primo::parse_mesh_bytes(bytes, "fuzz" PRIMO_FUZZ_EXTENSION);
    primo::mesh_from_soup(soup, "fuzz" PRIMO_FUZZ_EXTENSION);
  } catch (const primo::Error&) {
  }
  return 0;
}
