#include "session_support.h"

#include <memory>
#include <utility>
#include <vector>

#include "primo/mesh/geometry.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/sessions/session_recorder.h"

namespace primo::test {
namespace {

std::vector<int> faces_with(const Mesh& mesh, double y_min, double y_max) {
  std::vector<int> out;
  for (auto f : mesh.faces()) {
    Vec3 c = Vec3::Zero();
    int n = 0;
    for (auto v : mesh.fv_range(f)) c += mesh.point(v), ++n;
    c /= n;
    if (c.y() >= y_min && c.y() <= y_max) out.push_back(f.idx());
  }
  return out;
}

// A handle made where its faces are at rest, as the editor makes one (pivot: the faces' rest
// area-weighted centroid).
SessionHandle make_handle(std::string name, std::vector<int> faces, SessionHandleMode mode,
                          int color, const FaceGeometry& rest) {
  SessionHandle h;
  h.name = std::move(name);
  h.mode = mode;
  h.center = area_weighted_centroid(rest, faces);
  h.faces = std::make_shared<const std::vector<int>>(std::move(faces));
  h.color = color;
  return h;
}

}  // namespace

RecordedSession record_bar_session(const std::string& mesh_path) {
  RecordedSession r;
  r.mesh = make_bar(0.2, 1.0, 2, 10);
  const Mesh& mesh = r.mesh;
  const FaceGeometry rest = compute_face_geometry(mesh);
  const int n_faces = int(mesh.n_faces());
  SessionState state;
  SessionRecorder rec;
  double t = 0.0;
  rec.start(state, mesh_path, SolverSpec{}, t);
  auto frame = [&] { t += 1.0 / 60.0; rec.observe(state, n_faces, t); };
  frame();  // nothing changed: no event
  state.handles.push_back(
      make_handle("Fixed 1", faces_with(mesh, -1.0, 0.05), SessionHandleMode::Fixed, 0, rest));
  frame();
  state.handles.push_back(
      make_handle("Handle 2", faces_with(mesh, 0.95, 2.0), SessionHandleMode::Pose, 1, rest));
  frame();
  for (int k = 1; k <= 12; ++k) {
    state.handles[1].pose.translate = Vec3(0.02 * k, 0.0, 0.01 * k);
    state.handles[1].pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.03 * k, Vec3::UnitZ()));
    frame();
  }
  auto softer = std::make_shared<std::vector<double>>(size_t(n_faces), 1.0);
  for (int f : faces_with(mesh, 0.4, 0.6)) (*softer)[size_t(f)] = 0.5;
  state.height_factor = softer;
  frame();
  const SessionState before_width = state;
  state.prisms.width = 0.9;
  frame();
  const SessionState after_width = state;
  // Undo, then redo, the width change: a marker, then the change it caused, in one frame.
  state = before_width;
  t += 1.0 / 60.0;
  rec.note_undo(false, t);
  rec.observe(state, n_faces, t);
  state = after_width;
  t += 1.0 / 60.0;
  rec.note_undo(true, t);
  rec.observe(state, n_faces, t);
  r.session = rec.stop();
  r.final_state = state;
  return r;
}

}  // namespace primo::test
