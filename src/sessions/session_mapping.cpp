#include "primo/sessions/session_mapping.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <utility>

#include "primo/util/error.h"

namespace primo {
namespace {

std::vector<Vec3> centroids(const Mesh& mesh) {
  std::vector<Vec3> c;
  c.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    Vec3 s = Vec3::Zero();
    int n = 0;
    for (auto v : mesh.fv_range(f)) s += mesh.point(v), ++n;
    c.push_back(s / double(std::max(n, 1)));
  }
  return c;
}

}  // namespace

Session map_session_to_mesh(const Session& session, const Mesh& coarse, const Mesh& fine) {
  validate_session(session, int(coarse.n_faces()));
  const std::vector<Vec3> cc = centroids(coarse), fc = centroids(fine);
  // Fine faces of each coarse face (brute force: fine enough for editor-sized meshes).
  std::vector<std::vector<int>> children(cc.size());
  for (size_t f = 0; f < fc.size(); ++f) {
    size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (size_t c = 0; c < cc.size(); ++c) {
      const double d = (cc[c] - fc[f]).squaredNorm();
      if (d < best_d) best_d = d, best = c;
    }
    children[best].push_back(int(f));
  }
  auto map_handles = [&](std::vector<SessionHandle>& handles) {
    for (SessionHandle& g : handles) {
      std::vector<int> faces;
      for (int c : *g.faces)
        faces.insert(faces.end(), children[size_t(c)].begin(), children[size_t(c)].end());
      std::sort(faces.begin(), faces.end());
      if (faces.empty()) throw Error("handle '" + g.name + "' has no face on the finer mesh");
      g.faces = std::make_shared<const std::vector<int>>(std::move(faces));
      if (!g.falloff) continue;
      // A coarse face's weight goes to each of its fine faces.
      std::vector<std::pair<int, double>> fw;
      for (size_t i = 0; i < g.falloff->faces.size(); ++i)
        for (int x : children[size_t(g.falloff->faces[i])]) fw.push_back({x, g.falloff->weights[i]});
      std::sort(fw.begin(), fw.end());
      auto falloff = std::make_shared<SessionFalloff>();
      falloff->radius = g.falloff->radius;
      for (const auto& [x, w] : fw) falloff->faces.push_back(x), falloff->weights.push_back(w);
      g.falloff = falloff;
    }
  };
  auto map_factors = [&](FaceFactors& f) {
    if (!f) return;
    auto a = std::make_shared<std::vector<double>>(fc.size(), 1.0);
    for (size_t c = 0; c < f->size() && c < children.size(); ++c)
      for (int x : children[c]) (*a)[size_t(x)] = (*f)[c];
    f = a;
  };
  Session s = session;
  s.initial = initial_state(session, int(coarse.n_faces()));  // listed factors made arrays
  map_handles(s.initial.handles);
  map_factors(s.initial.height_factor);
  map_factors(s.initial.width_factor);
  for (SessionEvent& e : s.events) {
    if (e.type == SessionEvent::Type::Handles) map_handles(e.handles);
    if (e.type == SessionEvent::Type::Factors) {
      std::vector<std::pair<int, double>> fv;
      for (size_t i = 0; i < e.faces.size(); ++i)
        for (int x : children[size_t(e.faces[i])]) fv.push_back({x, e.values[i]});
      std::sort(fv.begin(), fv.end());
      e.faces.clear(), e.values.clear();
      for (const auto& [f, v] : fv) e.faces.push_back(f), e.values.push_back(v);
    }
  }
  return s;
}

}  // namespace primo
