#include "draw_data_fingerprint.h"

#include <imgui.h>

#include <cstring>

namespace primo::editor {
namespace {

// FNV-1a over 8-byte words: a panel's draw lists are some 100 kB, hashed in well under a
// millisecond, against the milliseconds a software renderer takes to draw them.
class Fingerprint {
 public:
  void add(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
      std::uint64_t word;
      std::memcpy(&word, p + i, 8);
      mix(word);
    }
    std::uint64_t tail = 0;
    std::memcpy(&tail, p + i, bytes - i);
    mix(tail ^ (std::uint64_t(bytes) << 56));
  }
  template <class T>
  void add(const T& value) {
    add(&value, sizeof value);
  }
  std::uint64_t value() const { return hash_; }

 private:
  void mix(std::uint64_t word) {
    hash_ ^= word;
    hash_ *= 0x100000001b3ull;
    hash_ ^= hash_ >> 29;
  }
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace

std::uint64_t draw_data_fingerprint(const ImDrawData& data) {
  Fingerprint f;
  f.add(data.Valid);
  f.add(data.DisplayPos);
  f.add(data.DisplaySize);
  f.add(data.FramebufferScale);
  f.add(data.CmdListsCount);
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    f.add(list.VtxBuffer.Data, size_t(list.VtxBuffer.Size) * sizeof(ImDrawVert));
    f.add(list.IdxBuffer.Data, size_t(list.IdxBuffer.Size) * sizeof(ImDrawIdx));
    f.add(list.CmdBuffer.Size);
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      f.add(cmd.ClipRect);
      f.add(cmd.TextureId);
      f.add(cmd.VtxOffset);
      f.add(cmd.IdxOffset);
      f.add(cmd.ElemCount);
      f.add(cmd.UserCallback);
      f.add(cmd.UserCallbackData);
    }
  }
  return f.value();
}

}  // namespace primo::editor
