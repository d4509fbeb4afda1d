#pragma once
// Autosaved work: the editor writes the open document as a scenario (with its solved pose)
// every few minutes while it has unsaved changes, and on SIGINT/SIGTERM/SIGHUP, into
// state_folder()/autosave; a clean save, or leaving the work by choice, removes the file. At
// the next start whatever is left there is offered for recovery (docs/editor.md, "Files").

#include <string>
#include <vector>

namespace primo::editor {

// The autosave file of the document whose mesh is `mesh_path` (one per mesh, so two
// documents of different meshes never overwrite each other's work).
std::string autosave_path(const std::string& mesh_path);

struct AutosavedWork {
  std::string path;   // the autosaved scenario
  std::string label;  // its file name and age, for the recovery prompt
  long long age_seconds = 0;
};
// Every autosaved scenario, newest first.
std::vector<AutosavedWork> list_autosaved_work();

// Writes the scenario text atomically, creating the folder. Throws primo::Error.
void write_autosave(const std::string& path, const std::string& scenario_json);
void remove_autosave(const std::string& path);  // quietly; a missing file is fine

}  // namespace primo::editor
