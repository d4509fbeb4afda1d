#pragma once
// Writing result files so that a failure never loses work: the commands, the editor (scenarios,
// sessions, preferences, autosaves) and the benchmarks all write through these, and save_mesh
// (primo/io/mesh_io.h) too.
//
// Every file is first written in full to a temporary file beside its target, named
// ".<name>.primo-partial-<pid>-<n><ext>", flushed to disk, and only then renamed over the
// target. A command that writes several files (`deform -o OUT --stats STATS`) stages them all
// and renames them only when every one is complete, so either all results are new or all
// targets are as they were; should a rename fail after others succeeded, the earlier targets
// are put back from hard links kept during the commit (".<name>.primo-backup-<pid>-<n><ext>").
// A process killed while staging leaves its temporary file; the next write to the same target
// removes the temporaries and backups of processes that no longer run.

#include <string>
#include <utility>
#include <vector>

#include "primo/mesh/mesh.h"
#include "primo/mesh/mesh_attributes.h"

namespace primo {

// Throws primo::Error unless `path` has a mesh extension we can write and its folder exists:
// a command checks this before minutes of work rather than after them.
void check_mesh_output_path(const std::string& path);
// The same for any output file (statistics, scenarios): its folder exists and the path is not
// a folder, a device (/dev/full), a pipe or another special file.
void check_output_path(const std::string& path);

// A file a command reads or writes, with how its command line names it ("-o", "--stats",
// "the scenario", "the mesh"), for check_distinct_files.
struct NamedFile {
  std::string role;
  std::string path;
};
// Throws primo::Error "<path>: <role> is the same file as <other role> (<other path>); nothing
// was written" when two outputs, or an output and an input, are the same file (also through
// links or different spellings of the path). Empty paths are skipped.
void check_distinct_files(const std::vector<NamedFile>& outputs,
                          const std::vector<NamedFile>& inputs);

// Result files written together (see above). Nothing reaches a target before commit(); the
// destructor removes whatever was staged and not committed.
class StagedOutputs {
 public:
  StagedOutputs() = default;
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;
  ~StagedOutputs();

  // Writes the temporary file now; throws primo::Error naming `path` on any failure (missing
  // or read-only folder, full disk, special file at the target).
  void stage(const std::string& path, const std::string& bytes);
  void stage_mesh(const std::string& path, const Mesh& mesh);
  void stage_mesh(const std::string& path, const Mesh& mesh, const MeshAttributes& attributes);
  // Renames every staged file into place, in the order staged. When a rename fails, the
  // targets already replaced are put back (each existing target is kept under a second name,
  // a hard link, until every rename succeeded) and the error says so; a target that could not
  // be put back is named with where its earlier version is.
  void commit();

 private:
  static std::string hidden_prefix(const std::string& path, const char* kind);
  static std::string hidden_name(const std::string& path, const std::string& prefix);
  std::vector<std::string> back_up_targets() const;  // "" where a target does not exist
  std::string roll_back(size_t renamed, const std::vector<std::string>& backups);

  std::vector<std::pair<std::string, std::string>> staged_;  // temporary file, target
};

// Writes `text` to `path` through a StagedOutputs of one file. Throws primo::Error naming
// `path` when its folder does not exist or the file cannot be written.
void write_text_atomically(const std::string& path, const std::string& text);

// Removes what processes that no longer run left in `folder` under names that start with
// `prefix` and continue with "<pid>" and then '-' or the end ("primo-replay-" for the frames of
// a killed `primo replay --frames`). Ignores every error.
void remove_stale_partials(const std::string& folder, const std::string& prefix);

}  // namespace primo
