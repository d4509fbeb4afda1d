#pragma once
// A recorded session as one animated glTF (docs/sessions.md, "As one animated glTF"): the
// rest mesh with every N-th replayed frame as a morph target and one animation over the
// session's time (primo/io/mesh_animation_gltf.h). `primo replay --animation` and the editor's
// Session panel write it.

#include <string>

#include "primo/solve/deformer.h"
#include "primo/mesh/mesh.h"
#include "primo/io/mesh_animation_gltf.h"
#include "primo/sessions/session.h"

namespace primo {

// The time of `frame` in seconds, from the timeline: a frame with events is at its first
// event's `t`, frame 0 at 0 unless it has events, and the frames between two of these at
// times evenly spaced between them (the editor recorded no time for frames without events).
double session_frame_time(const Session& session, int frame);

// "frame_000010": frame 10's file of `primo replay --frames` (with its extension) and its
// target in the animation.
std::string session_frame_name(int frame);

// Collects the frames of a replay (ReplayOptions::on_frame with `every`) into the file.
class SessionAnimation {
 public:
  // Checks before anything is solved: `path` is a .glb or .gltf that can be written, and the
  // file the frames 0, every, 2 every, ... of the session would make stays within
  // kMaxAnimationFileBytes; else throws Error naming `path`, the size and
  // what helps (a larger --every). The file's mesh carries `attributes`, those `mesh` was read
  // with (its UVs, colours and materials), as save_mesh writes them.
  SessionAnimation(const Session& session, const Mesh& mesh, int every, std::string path,
                   const MeshAttributes& attributes = {});

  // The replayed frame: its positions at session_frame_time, named frame_000010.
  void add(int frame, const Deformer& deformer);
  size_t frames() const { return animation_.frames(); }
  // The file's bytes (stage them with StagedOutputs, or save_session_animation).
  std::string file_bytes() const { return animation_.file_bytes(path_); }

 private:
  const Session& session_;
  std::string path_;
  MeshAnimation animation_;
};

// Replays `session` on `mesh` (as replay_session, one solver iteration a frame) and writes
// every `every`-th frame as the animation at `path`, atomically. Throws Error as
// SessionAnimation and replay_session do; nothing is written then.
void save_session_animation(const Session& session, const Mesh& mesh, int every,
                            const std::string& path, const MeshAttributes& attributes = {});

}  // namespace primo
