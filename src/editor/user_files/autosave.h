#pragma once
// Autosaved work: the editor writes the open document as a scenario (with its solved pose)
// every few minutes while it has unsaved changes, and on SIGINT/SIGTERM/SIGHUP, into
// state_folder()/autosave; a clean save, or leaving the work by choice, removes the file. At
// the next start whatever is left there is offered for recovery (docs/editor.md, "Files").

#include <string>
#include <vector>

namespace primo::editor {

// The autosave file of the document whose mesh is `mesh_path` (one per mesh, so two
// documents of different meshes never overwrite each other's work). Its name is UTF-8 text
// whatever the mesh's name is (other bytes become %XX).
std::string autosave_path(const std::string& mesh_path);

// The mesh path the autosaved scenario at `autosave` names: `mesh_path` itself when it is
// UTF-8 text; otherwise a JSON string cannot hold it, and a symbolic link beside the autosave,
// with a text name, points at the mesh (made or replaced here). Throws primo::Error.
std::string autosave_mesh_reference(const std::string& autosave, const std::string& mesh_path);

// The mesh a recovered scenario's `mesh_path` stands for: the target of such a link, else
// `mesh_path`.
std::string recovered_mesh_path(const std::string& mesh_path);

struct AutosavedWork {
  std::string path;   // the autosaved scenario
  std::string label;  // its file name and age, for the recovery prompt
  long long age_seconds = 0;
};
// Every autosaved scenario, newest first.
std::vector<AutosavedWork> list_autosaved_work();

// Writes the scenario text atomically, creating the folder. Throws primo::Error.
void write_autosave(const std::string& path, const std::string& scenario_json);
// Quietly, with its mesh link if any; a missing file is fine.
void remove_autosave(const std::string& path);

}  // namespace primo::editor
