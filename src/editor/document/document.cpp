#include "document.h"

#include <algorithm>
#include <cctype>
#include <climits>

#include "model_orientation.h"
#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "scenario_bridge.h"

namespace primo::editor {

bool is_scenario_path(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return false;
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".json";
}

// A stand-in has at most this many triangles.
constexpr int kProxyTriangles = 30000;

std::unique_ptr<Document> make_document(Mesh mesh, std::string mesh_path, int stand_in_above) {
  auto doc = std::make_unique<Document>();
  doc->topology = std::make_shared<const MeshTopology>(build_topology(mesh));
  doc->proxy = std::make_shared<ProxyBuild>(
      doc->topology,
      int(doc->topology->triangle_face.size()) > stand_in_above ? kProxyTriangles : INT_MAX);
  doc->mesh = std::make_shared<const Mesh>(std::move(mesh));
  doc->mesh_path = std::move(mesh_path);
  doc->state = initial_edit_state(doc->n_faces());
  doc->history.reset(doc->state);
  doc->saved_state = doc->state;
  return doc;
}

namespace {

// The note of a scene file without its leading "<path>: ".
std::string note_without_path(const std::string& note, const std::string& path) {
  const std::string prefix = path + ": ";
  return note.rfind(prefix, 0) == 0 ? note.substr(prefix.size()) : note;
}

}  // namespace

std::unique_ptr<Document> load_document(const std::string& path, int stand_in_above) {
  if (!is_scenario_path(path)) {
    LoadedMesh loaded = load_mesh_noted(path);
    auto doc = make_document(std::move(loaded.mesh), path, stand_in_above);
    doc->load_note = note_without_path(loaded.note, path);
    doc->attributes = std::make_shared<const MeshAttributes>(std::move(loaded.attributes));
    doc->state.orientation = mesh_orientation(path);
    doc->saved_state = doc->state;
    doc->history.reset(doc->state);
    return doc;
  }
  const Scenario scenario = load_scenario(path);
  LoadedMesh loaded = load_mesh_noted(scenario.mesh_path);
  Mesh mesh = std::move(loaded.mesh);
  const ResolvedScenario resolved = resolve_scenario(scenario, mesh);
  auto doc = make_document(std::move(mesh), scenario.mesh_path, stand_in_above);
  doc->load_note = note_without_path(loaded.note, scenario.mesh_path);
  doc->attributes = std::make_shared<const MeshAttributes>(std::move(loaded.attributes));
  doc->scenario_path = path;
  doc->solver = scenario.solver;
  doc->state = import_scenario(scenario, resolved, *doc->topology);
  // The scenario's own orientation (imported above) wins over its mesh's.
  if (!scenario.editor || !scenario.editor->orientation)
    doc->state.orientation = mesh_orientation(scenario.mesh_path);
  doc->start_motions = resolved.start_motions;
  doc->saved_state = doc->state;
  doc->history.reset(doc->state);
  return doc;
}

}  // namespace primo::editor
