// libFuzzer target: session JSON (parse_session), validated against a small bar mesh
// (validate_session, as `primo replay` does before solving), then written back and read again.

#include <cstddef>
#include <cstdint>
#include <string>

#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/sessions/session.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const primo::Mesh bar = primo::make_bar(0.2, 1.0, 2, 10);
  const std::string text(reinterpret_cast<const char*>(data), size);
  primo::Session session;
  try {
    session = primo::parse_session(text, "fuzz.session.json");
    primo::validate_session(session, int(bar.n_faces()));
  } catch (const primo::Error&) {
    return 0;
  }
  primo::parse_session(primo::session_to_json(session, ""),
                       "written.session.json");  // must not throw
  return 0;
}
