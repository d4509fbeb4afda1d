#include "primo/sessions/session_animation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "primo/util/error.h"
#include "primo/io/output_files.h"
#include "primo/sessions/session_replay.h"

namespace primo {
namespace {

// A frame with a time of its own: the first event's of a frame with events, or frame 0 at 0.
struct TimedFrame {
  int frame;
  double t;
};

std::string megabytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f MB", double(bytes) / 1e6);
  return text;
}

}  // namespace

std::string session_frame_name(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d", frame);
  return name;
}

double session_frame_time(const Session& session, int frame) {
  TimedFrame before{0, 0.0};
  bool timed = false;  // `before` has an event's time
  for (const SessionEvent& e : session.events) {
    if (e.frame <= frame) {
      if (!timed || e.frame > before.frame) before = {e.frame, e.t}, timed = true;
      continue;
    }
    // The first frame with events after `frame`: in between, evenly spaced.
    const double share = double(frame - before.frame) / double(e.frame - before.frame);
    return before.t + share * (e.t - before.t);
  }
  return before.t;
}

SessionAnimation::SessionAnimation(const Session& session, const Mesh& mesh, int every,
                                   std::string path, const MeshAttributes& attributes)
    : session_(session), path_(std::move(path)), animation_(mesh, attributes) {
  check_animation_output_path(path_);
  if (every < 1) throw Error(path_ + ": the frame step must be at least 1");
  const std::uint64_t frames = std::uint64_t((std::max(session.frames(), 1) - 1) / every + 1);
  const std::uint64_t bound = mesh_animation_size_bound(mesh, frames, path_, attributes);
  const std::string help = "; keep fewer frames with a larger --every (now " +
                           std::to_string(every) + ")";
  if (bound > kMaxAnimationFileBytes)
    throw Error(path_ + ": the animation of " + std::to_string(frames) + " frames of " +
                std::to_string(mesh.n_vertices()) + " vertices could take up to " +
                megabytes(bound) + ", more than the " +
                std::to_string(kMaxAnimationFileBytes >> 30) + " GiB limit; nothing was written" +
                help);
}

void SessionAnimation::add(int frame, const Deformer& deformer) {
  animation_.add_frame(session_frame_time(session_, frame), deformer.vertex_positions(),
                       session_frame_name(frame));
}

void save_session_animation(const Session& session, const Mesh& mesh, int every,
                            const std::string& path, const MeshAttributes& attributes) {
  SessionAnimation animation(session, mesh, every, path, attributes);
  ReplayOptions options;
  options.every = every;
  options.on_frame = [&](int frame, const Deformer& d) { animation.add(frame, d); };
  replay_session(session, mesh, options);
  StagedOutputs out;
  out.stage(path, animation.file_bytes());
  out.commit();
}

}  // namespace primo
