// `primo replay SESSION.json -o OUT.ext [--frames DIR --every N --frame-format EXT]
// [--animation OUT.glb] [--stats STATS.json]`: replays a recorded editor session headless
// (docs/sessions.md) and writes the final mesh, with --frames one mesh per N frames
// (DIR/frame_000000.obj, ...; .glb with --frame-format glb), and with --animation the same
// frames as one animated glTF. The whole session is validated
// against the mesh before anything is solved; frames go to a temporary folder inside DIR and
// are moved into place only when the replay succeeded, so a failure writes nothing.

#include <dlfcn.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>
#include <vector>

#include "commands.h"
#include "number_options.h"
#include "primo/util/error.h"
#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "primo/io/output_files.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_animation.h"
#include "primo/sessions/session_mapping.h"
#include "primo/sessions/session_replay.h"
#include "rethrow_naming.h"

namespace primo::app {
namespace {

namespace fs = std::filesystem;

struct ReplayArguments {
  std::string session;
  std::string output;
  std::string frames;
  std::string stats;
  std::string animation;
  std::string mesh;
  std::string frame_format = "obj";
  int every = 1;
  int iterations_per_frame = 1;
  int threads = 1;
};

// Threaded BLAS (OpenBLAS under CHOLMOD's supernodal factorization) and OpenMP sum in an
// order that depends on the thread count, so results differ in the last bits between machines.
// A replay uses one thread by default: the same build gives bitwise the same meshes anywhere.
// Looked up at run time so that nothing is linked for it.
void limit_threads(int threads) {
  if (threads <= 0) return;
  if (auto f = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) f(threads);
  if (auto f = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"))) f(threads);
}

// More frame files than this is a mistake (--every forgotten on a long session), not a request.
constexpr long kMaxFrameFiles = 100000;

// Whether `path` names a frame file of `format` in the folder `frames` ("frame_" and six or
// more digits), which the replay would write over.
bool is_frame_file(const std::string& path, const std::string& frames, const std::string& format) {
  if (path.empty()) return false;
  std::error_code error;
  const fs::path folder = fs::weakly_canonical(fs::absolute(frames), error);
  const fs::path file = fs::weakly_canonical(fs::absolute(path), error);
  if (error || file.parent_path() != folder) return false;
  const std::string name = file.filename().string();
  const std::string prefix = "frame_", suffix = "." + format;
  if (name.size() < prefix.size() + 6 + suffix.size() || name.rfind(prefix, 0) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  return std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); });
}

// Refuses, before any work, every input or output that a frame file would replace.
void check_frames_spare(const std::string& frames, const std::string& format,
                        const std::vector<NamedFile>& files) {
  for (const NamedFile& f : files)
    if (is_frame_file(f.path, frames, format))
      throw Error(f.path + ": " + f.role + " lies in --frames " + frames +
                  " under a frame's name, which the replay would write over; nothing was written");
}

int run_replay(const ReplayArguments& args) {
  limit_threads(args.threads);
  const auto start = std::chrono::steady_clock::now();
  // Every output is checked before any work (see deform_command.cpp).
  check_mesh_output_path(args.output);
  if (!args.stats.empty()) check_output_path(args.stats);
  if (!args.animation.empty()) check_animation_output_path(args.animation);
  if (!args.frames.empty()) {
    const fs::path frames_parent = fs::absolute(fs::path(args.frames)).parent_path();
    if (!fs::is_directory(frames_parent))
      throw Error(args.frames + ": the folder " + frames_parent.string() + " does not exist");
    std::error_code error;
    if (fs::exists(args.frames, error) && !fs::is_directory(args.frames, error))
      throw Error(args.frames + ": --frames names a file, not a folder; nothing was written");
  }
  const std::vector<NamedFile> outputs = {{"-o", args.output},
                                          {"--stats", args.stats},
                                          {"--frames", args.frames},
                                          {"--animation", args.animation}};
  check_distinct_files(outputs, {{"the session", args.session}, {"--mesh", args.mesh}});
  const Session session = load_session(args.session);
  check_distinct_files(outputs, {{"the session", args.session},
                                 {"--mesh", args.mesh},
                                 {"the session's mesh", session.mesh_path}});
  if (!args.frames.empty())
    check_frames_spare(args.frames, args.frame_format,
                       {{"the session", args.session}, {"--mesh", args.mesh},
                        {"the session's mesh", session.mesh_path}, {"-o", args.output},
                        {"--stats", args.stats}, {"--animation", args.animation}});
  if (!args.frames.empty() && session.frames() / args.every + 1 > kMaxFrameFiles)
    throw Error(args.session + ": --frames --every " + std::to_string(args.every) + " would write " +
                std::to_string(session.frames() / args.every + 1) + " files (at most " +
                std::to_string(kMaxFrameFiles) + "); use a larger --every");
  Session session_on_mesh;
  // A scene file (glTF, FBX, ...) says what was joined, merged or left out: a note, not an error.
  const auto load = [](const std::string& path) {
    LoadedMesh loaded = load_mesh_noted(path);
    if (!loaded.note.empty()) std::fprintf(stderr, "primo replay: note: %s\n", loaded.note.c_str());
    return loaded;
  };
  // The replayed mesh's UVs, normals, colours and materials go into every file written.
  LoadedMesh loaded = load(session.mesh_path);
  Mesh mesh = std::move(loaded.mesh);
  MeshAttributes attributes = std::move(loaded.attributes);
  if (!args.mesh.empty()) {  // a finer version of the recorded mesh
    LoadedMesh fine = load(args.mesh);
    session_on_mesh = map_session_to_mesh(session, mesh, fine.mesh);
    mesh = std::move(fine.mesh);
    attributes = std::move(fine.attributes);
  } else {
    session_on_mesh = session;
  }
  validate_session(session_on_mesh, int(mesh.n_faces()));  // before anything is written
  // Its size is checked here, before anything is solved.
  std::unique_ptr<SessionAnimation> animation;
  if (!args.animation.empty())
    animation = std::make_unique<SessionAnimation>(session_on_mesh, mesh, args.every, args.animation,
                                                   attributes);

  // Frames are written into a hidden folder inside DIR and moved into place at the end; a
  // killed replay leaves that folder, which the next replay into DIR removes.
  fs::path temp;
  std::vector<std::string> written;
  ReplayOptions options;
  options.iterations_per_frame = args.iterations_per_frame;
  if (!args.frames.empty()) {
    if (fs::is_directory(args.frames)) remove_stale_partials(args.frames, ".primo-replay-");
    temp = fs::path(args.frames) / (".primo-replay-" + std::to_string(::getpid()));
  }
  if (!args.frames.empty() || animation) {
    options.every = args.every;
    options.on_frame = [&](int frame, const Deformer& d) {
      if (animation) animation->add(frame, d);
      if (args.frames.empty()) return;
      if (written.empty()) fs::create_directories(temp);
      const std::string name = session_frame_name(frame) + "." + args.frame_format;
      save_mesh(d.deformed_mesh(mesh), attributes, (temp / name).string());
      written.push_back(name);
    };
  }
  ReplayResult result;
  try {
    try {
      result = replay_session(session_on_mesh, mesh, options);
    } catch (...) {
      rethrow_naming(args.session);
    }
    Mesh final_mesh = mesh;
    for (auto v : final_mesh.vertices()) final_mesh.set_point(v, result.positions[size_t(v.idx())]);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Every frame's place takes a file (a folder there would make its rename fail after the
    // final mesh was written).
    for (const std::string& name : written) {
      std::error_code error;
      const fs::path target = fs::path(args.frames) / name;
      if (fs::is_directory(fs::symlink_status(target, error)))
        throw Error(target.string() + ": a folder is where the frame goes; nothing was written");
    }
    // The final mesh, the animation and the statistics together, or none; then the frames.
    StagedOutputs out;
    out.stage_mesh(args.output, final_mesh, attributes);
    if (animation) out.stage(args.animation, animation->file_bytes());
    if (!args.stats.empty())
      out.stage(args.stats, nlohmann::json{{"frames", result.frames},
                                           {"events", session.events.size()},
                                           {"rebuilds", result.rebuilds},
                                           {"iterations", result.iterations},
                                           {"converged", result.converged},
                                           {"energy", result.energy},
                                           {"frames_written", written.size()},
                                           {"animation_frames", animation ? animation->frames() : 0},
                                           {"seconds", seconds}}
                                    .dump(2) + "\n");
    out.commit();
    for (const std::string& name : written) fs::rename(temp / name, fs::path(args.frames) / name);
  } catch (...) {
    std::error_code ignored;
    if (!temp.empty()) fs::remove_all(temp, ignored);
    throw;
  }
  std::error_code ignored;
  if (!temp.empty()) fs::remove_all(temp, ignored);
  if (!result.converged)
    std::fprintf(stderr, "primo replay: warning: %s: the final pose did not converge within "
                 "solver.max_iterations\n", args.session.c_str());
  return 0;
}

}  // namespace

Command register_replay(CLI::App& app) {
  auto args = std::make_shared<ReplayArguments>();
  CLI::App* cmd = app.add_subcommand(
      "replay", "Replay a recorded editor session (primo-session/1) and write the final mesh");
  cmd->add_option("session", args->session, "Session file (.session.json)")->required();
  cmd->add_option("-o,--output", args->output, "Final mesh (.obj .off .ply .stl .om .gltf .glb)")
      ->required();
  cmd->add_option("--frames", args->frames,
                  "Also write one mesh per --every frames into this folder (created if missing)");
  cmd->add_option("--frame-format", args->frame_format,
                  "Format of the --frames meshes: obj (default), off, ply, stl, om, gltf or glb")
      ->check(CLI::IsMember({"obj", "off", "ply", "stl", "om", "gltf", "glb"}));
  cmd->add_option("--animation", args->animation,
                  "Also write the frames (every --every) as one animated glTF (.glb or .gltf): the "
                  "rest mesh with one morph target a frame, timed as recorded");
  cmd->add_option("--every", args->every, "Frame step for --frames and --animation (default 1)")
      ->check(finite_range(1, kMaxSessionFrame));
  cmd->add_option("--iterations-per-frame", args->iterations_per_frame,
                  "Solver iterations after each frame (default 1, as the editor while dragging)")
      ->check(finite_range(1, 1000));
  cmd->add_option(
         "--threads", args->threads,
         "BLAS/OpenMP threads (default 1: bitwise the same result on every machine; 0: "
         "the libraries' default, faster on big meshes but machine-dependent in the last bits)")
      ->check(finite_range(0, 1024));
  cmd->add_option("--mesh", args->mesh,
                  "Replay on this finer version of the recorded mesh (e.g. subdivided): faces are "
                  "matched by nearest centroid");
  cmd->add_option("--stats", args->stats, "Write replay statistics as JSON");
  return {cmd, [args] { return run_replay(*args); }};
}

}  // namespace primo::app
