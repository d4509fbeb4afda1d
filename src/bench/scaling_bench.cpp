#include "scaling_bench.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "inputs.h"
#include "machine.h"
#include "primo/util/error.h"
#include "primo/io/output_files.h"
#include "report.h"

extern char** environ;

namespace primo::bench {
namespace {

namespace fs = std::filesystem;

struct Case {
  int steps = 0;
  bool shuffled = false;
  std::optional<nlohmann::json> result;  // the drag bench's JSON; empty when the run failed
  std::string failure;
};

// Runs `primo bench drag` with `arguments` as a child process, its output into `log`; true
// when it exited with 0.
bool run_child(const std::vector<std::string>& arguments, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, arguments[0].c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return false;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

std::string last_lines(const fs::path& file, int count) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::string out;
  for (size_t i = lines.size() > size_t(count) ? lines.size() - size_t(count) : 0; i < lines.size(); ++i)
    out += "    " + lines[i] + "\n";
  return out;
}

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

// The case's figures, as the table and the JSON give them.
struct Figures {
  double faces, setup_s, median_ms, settle_s, full_solve_s, peak_mb, lag_percent;
  double frame_ns_per_face() const { return 1e6 * median_ms / faces; }
  double setup_us_per_face() const { return 1e6 * setup_s / faces; }
  double bytes_per_face() const { return 1024.0 * 1024.0 * peak_mb / faces; }
};

Figures figures_of(const nlohmann::json& r) {
  Figures f{};
  f.faces = number(r, "faces");
  f.setup_s = number(r, "setup_seconds") + number(r, "solver_setup_seconds");
  f.median_ms = number(r, "median_ms");
  f.settle_s = number(r, "converge_seconds");
  f.full_solve_s = r.contains("full_solve") ? number(r["full_solve"], "seconds") : std::nan("");
  f.peak_mb = number(r, "peak_memory_mb");
  f.lag_percent = 100.0 * number(r, "last_frame_max_distance");
  return f;
}

}  // namespace

int run_scaling_bench(const ScalingBenchOptions& options) {
  const std::string scenario =
      options.scenario.empty() ? asset_dir() + "/scenarios/bench/bunny-ears.json" : options.scenario;
  if (!fs::is_regular_file(scenario)) throw Error(scenario + ": no such scenario");
  if (options.steps.empty()) throw Error("--steps: no sizes given");
  for (int s : options.steps)
    if (s < 0 || s > 4) throw Error("--steps: " + std::to_string(s) + " Loop steps (0 to 4 are allowed)");
  if (options.seed == 0) throw Error("--seed: 0 is the file's own order; give another seed");
  if (!options.json.empty()) check_json_folder(options.json);
  const fs::path exe = fs::read_symlink("/proc/self/exe");
  const fs::path scratch = fs::temp_directory_path() / ("primo-scaling-" + std::to_string(getpid()));
  fs::create_directories(scratch);

  std::printf("%s\n", build_label().c_str());
  std::printf("Machine    %s, %u hardware threads\n", cpu_model().c_str(),
              std::thread::hardware_concurrency());
  std::printf("Pull       %s%s%s, %d frames; each case its own `primo bench drag` process\n\n",
              scenario.c_str(), options.mesh.empty() ? "" : (" on " + options.mesh).c_str(),
              options.bbox_handles ? " (--bbox-handles)" : "", options.frames);
  std::fflush(stdout);

  std::vector<Case> cases;
  for (int steps : options.steps)
    for (bool shuffled : {false, true}) {
      if (shuffled && options.ordered_only) continue;
      Case c;
      c.steps = steps;
      c.shuffled = shuffled;
      const fs::path json = scratch / ("case-" + std::to_string(cases.size()) + ".json");
      const fs::path log = scratch / ("case-" + std::to_string(cases.size()) + ".log");
      std::vector<std::string> args = {exe.string(), "bench", "drag", scenario,
                                       "--subdivide", std::to_string(steps),
                                       "--frames", std::to_string(options.frames),
                                       "--lag-every", "0", "--json", json.string()};
      if (!options.mesh.empty()) args.insert(args.end(), {"--mesh", options.mesh});
      if (options.bbox_handles) args.push_back("--bbox-handles");
      if (shuffled) args.insert(args.end(), {"--shuffle", std::to_string(options.seed)});
      std::printf("  %d Loop steps, %s ... ", steps, shuffled ? "renumbered" : "file order");
      std::fflush(stdout);
      const auto start = Clock::now();
      if (run_child(args, log)) {
        std::ifstream in(json);
        c.result = nlohmann::json::parse(in, nullptr, false);
        if (c.result->is_discarded()) c.result.reset(), c.failure = "its JSON could not be read";
      } else {
        c.failure = "`primo bench drag` failed:\n" + last_lines(log, 6);
      }
      if (c.result && c.result->contains("skipped")) {
        // A shared mesh that is not on this machine: every size would say the same.
        std::printf("skipped: %s\n", (*c.result)["skipped"].get<std::string>().c_str());
        std::error_code ignored;
        fs::remove_all(scratch, ignored);
        if (!options.json.empty())
          write_text_atomically(options.json,
                                nlohmann::json{{"skipped", (*c.result)["skipped"]}}.dump(2) + "\n");
        return 0;
      }
      std::printf("%s (%.0f s)\n", c.result ? "done" : "FAILED", seconds_since(start));
      if (!c.result) std::printf("%s", c.failure.c_str());
      std::fflush(stdout);
      cases.push_back(std::move(c));
    }
  std::error_code ignored;
  fs::remove_all(scratch, ignored);

  // The reference size: the one nearest 240k faces.
  const Case* reference = nullptr;
  for (const Case& c : cases)
    if (c.result && !c.shuffled &&
        (!reference || std::abs(std::log(number(*c.result, "faces") / 240000.0)) <
                           std::abs(std::log(number(*reference->result, "faces") / 240000.0))))
      reference = &c;

  const Figures reference_figures = reference ? figures_of(*reference->result) : Figures{};
  std::printf("\n  %9s %-10s %8s %9s %8s %8s %9s %9s %9s %8s %9s %9s %9s\n", "faces", "order",
              "setup s", "frame ms", "settle s", "full s", "peak MB", "ns/face", "B/face",
              "lag %", "renum/ord", "frame/ref", "setup/ref");
  nlohmann::json rows = nlohmann::json::array();
  int failures = 0;
  for (const Case& c : cases) {
    if (!c.result) {
      ++failures;
      std::printf("  %d Loop steps, %s: failed\n", c.steps, c.shuffled ? "renumbered" : "file order");
      continue;
    }
    const Figures f = figures_of(*c.result);
    double renumbered_ratio = std::nan("");
    if (c.shuffled)
      for (const Case& o : cases)
        if (!o.shuffled && o.steps == c.steps && o.result)
          renumbered_ratio = f.median_ms / figures_of(*o.result).median_ms;
    double frame_ratio = std::nan(""), setup_ratio = std::nan("");
    if (reference) {
      frame_ratio = f.frame_ns_per_face() / reference_figures.frame_ns_per_face();
      setup_ratio = f.setup_us_per_face() / reference_figures.setup_us_per_face();
    }
    std::printf("  %9.0f %-10s %8.2f %9.1f %8.2f %8.2f %9.0f %9.1f %9.0f %8.3f %9.2f %9.2f %9.2f\n",
                f.faces, c.shuffled ? "renumbered" : "file", f.setup_s, f.median_ms, f.settle_s,
                f.full_solve_s, f.peak_mb, f.frame_ns_per_face(), f.bytes_per_face(), f.lag_percent,
                renumbered_ratio, frame_ratio, setup_ratio);
    rows.push_back({{"loop_steps", c.steps},
                    {"renumbered", c.shuffled},
                    {"faces", f.faces},
                    {"setup_seconds", f.setup_s},
                    {"median_frame_ms", f.median_ms},
                    {"settle_seconds", f.settle_s},
                    {"full_solve_seconds", f.full_solve_s},
                    {"peak_memory_mb", f.peak_mb},
                    {"frame_ns_per_face", f.frame_ns_per_face()},
                    {"setup_us_per_face", f.setup_us_per_face()},
                    {"peak_bytes_per_face", f.bytes_per_face()},
                    {"last_frame_lag_percent", f.lag_percent},
                    {"renumbered_over_file_order", renumbered_ratio},
                    {"frame_per_face_over_reference", frame_ratio},
                    {"setup_per_face_over_reference", setup_ratio},
                    {"drag_bench", *c.result}});
  }
  std::printf("\n  ns/face and B/face: the median frame and the peak memory over the faces; "
              "renum/ord: the renumbered copy's frame over the file order's;\n  frame/ref, "
              "setup/ref: time a face against the size nearest 240k faces (%s); lag: the last "
              "frame's largest vertex distance\n  from its converged shape, %% of the "
              "bounding-box diagonal.\n",
              reference ? (std::to_string(int(number(*reference->result, "faces"))) + " faces").c_str()
                        : "none");
  if (!options.json.empty()) {
    nlohmann::json out = {{"scenario", scenario},
                          {"mesh", options.mesh},
                          {"bbox_handles", options.bbox_handles},
                          {"frames", options.frames},
                          {"seed", options.seed},
                          {"build", build_label()},
                          {"cpu", cpu_model()},
                          {"hardware_threads", std::thread::hardware_concurrency()},
                          {"cases", rows}};
    write_text_atomically(options.json, out.dump(2) + "\n");
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace primo::bench
