// libFuzzer target: scenario JSON (parse_scenario), then writing it back (scenario_to_json) and
// reading that again, which must succeed: what PriMo writes it must read.

#include <cstddef>
#include <cstdint>
#include <string>

#include "primo/util/error.h"
#include "primo/scenario/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  primo::Scenario scenario;
  try {
    scenario = primo::parse_scenario(text, "fuzz.json");
  } catch (const primo::Error&) {
    return 0;
  }
  primo::parse_scenario(primo::scenario_to_json(scenario), "written.json");  // must not throw
  return 0;
}
