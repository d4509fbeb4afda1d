// libFuzzer target: the editor's --script files (parse_script), then played against a host
// that does nothing, with the clock advancing 1,000 s a frame: every script must finish within
// a bound set by its commands (a `wait nan` or `move ... over inf` never did).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "primo/util/error.h"
#include "input/script.h"

namespace {

class NullHost : public primo::editor::ScriptHost {
 public:
  void push_input(const primo::editor::InputEvent&) override {}
  void locate(const primo::editor::ScriptCommand&, double& x, double& y) override { x = y = 1.0; }
  void cursor(double& x, double& y) override { x = y = 0.0; }
  bool settled() override { return true; }
  void run(const primo::editor::ScriptCommand&) override {}
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<primo::editor::ScriptCommand> commands;
  try {
    commands = primo::editor::parse_script(text, "fuzz.script");
  } catch (const primo::Error&) {
    return 0;
  }
  size_t bound = 10;
  for (const auto& c : commands)
    if (c.kind != primo::editor::ScriptCommand::Kind::Report &&  // prints: not played
        c.kind != primo::editor::ScriptCommand::Kind::WaitFile)  // touches the file system
      bound += c.text.size() + 200;
  commands.erase(std::remove_if(commands.begin(), commands.end(),
                                [](const auto& c) {
                                  return c.kind == primo::editor::ScriptCommand::Kind::Report ||
                                         c.kind == primo::editor::ScriptCommand::Kind::WaitFile;
                                }),
                 commands.end());
  primo::editor::ScriptPlayer player(std::move(commands));
  NullHost host;
  double now = 0.0;
  for (size_t frame = 0; frame < bound && !player.finished(); ++frame, now += 1000.0)
    player.update(now, host);
  if (!player.finished()) std::abort();  // a script that never ends
  return 0;
}
