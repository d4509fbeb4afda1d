#include "proxy_mesh.h"

#include <algorithm>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

namespace primo::editor {
namespace {

struct ProxyTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using ProxyMesh = OpenMesh::TriMesh_ArrayKernelT<ProxyTraits>;

// A collapse may turn no triangle's normal by more than this: the stand-in keeps the
// silhouette and never shows a triangle's back.
constexpr float kMaxNormalDeviationDegrees = 45.0f;
// Longest edge over height: no needles.
constexpr float kMaxAspectRatio = 8.0f;

class CancelObserver : public OpenMesh::Decimater::Observer {
 public:
  explicit CancelObserver(const std::atomic<bool>* cancel) : Observer(500), cancel_(cancel) {}
  void notify(size_t) override {}
  bool abort() const override { return cancel_ && cancel_->load(std::memory_order_relaxed); }

 private:
  const std::atomic<bool>* cancel_;
};

}  // namespace

ProxyTriangles decimate_triangles(const MeshTopology& t, int max_triangles,
                                  const std::atomic<bool>* cancel) {
  if (int(t.triangle_face.size()) <= max_triangles) return {};
  CancelObserver observer(cancel);
  ProxyMesh mesh;
  mesh.reserve(size_t(t.n_vertices), 3 * t.triangle_face.size() / 2, t.triangle_face.size());
  for (int v = 0; v < t.n_vertices; ++v) {
    const Vec3& p = t.rest_points[v];
    mesh.add_vertex(ProxyMesh::Point(p.x(), p.y(), p.z()));
  }
  std::vector<int> source_triangle;  // OpenMesh face index -> triangle of the topology
  source_triangle.reserve(t.triangle_face.size());
  ProxyTriangles kept_as_is;
  for (size_t i = 0; i < t.triangle_face.size(); ++i) {
    const unsigned a = t.triangles[3 * i], b = t.triangles[3 * i + 1], c = t.triangles[3 * i + 2];
    const auto f = mesh.add_face(mesh.vertex_handle(a), mesh.vertex_handle(b),
                                 mesh.vertex_handle(c));
    if (f.is_valid()) {
      source_triangle.push_back(int(i));
      continue;
    }
    kept_as_is.triangles.insert(kept_as_is.triangles.end(), {a, b, c});
    kept_as_is.triangle_face.push_back(t.triangle_face[i]);
  }
  // Corners of triangles left out of the decimation, and boundary loops, stay where they are.
  for (const unsigned v : kept_as_is.triangles) mesh.status(mesh.vertex_handle(v)).set_locked(true);
  for (const auto v : mesh.vertices())
    if (mesh.is_boundary(v)) mesh.status(v).set_locked(true);
  mesh.update_face_normals();

  OpenMesh::Decimater::DecimaterT<ProxyMesh> decimater(mesh);
  OpenMesh::Decimater::ModQuadricT<ProxyMesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalFlippingT<ProxyMesh>::Handle normal_flipping;
  OpenMesh::Decimater::ModAspectRatioT<ProxyMesh>::Handle aspect_ratio;
  decimater.add(quadric);
  decimater.add(normal_flipping);
  decimater.add(aspect_ratio);
  decimater.module(quadric).unset_max_err();
  decimater.module(normal_flipping).set_max_normal_deviation(kMaxNormalDeviationDegrees);
  decimater.module(aspect_ratio).set_aspect_ratio(kMaxAspectRatio);
  decimater.set_observer(&observer);
  decimater.initialize();
  if (observer.abort()) return {};
  const int budget = std::max(1, max_triangles - int(kept_as_is.triangle_face.size()));
  decimater.decimate_to_faces(0, size_t(budget));
  if (observer.abort()) return {};

  ProxyTriangles proxy;
  proxy.triangles.reserve(3 * size_t(budget) + kept_as_is.triangles.size());
  proxy.triangle_face.reserve(size_t(budget) + kept_as_is.triangle_face.size());
  for (const auto f : mesh.faces()) {  // skips deleted faces
    for (const auto v : f.vertices()) proxy.triangles.push_back(unsigned(v.idx()));
    proxy.triangle_face.push_back(t.triangle_face[size_t(source_triangle[size_t(f.idx())])]);
  }
  proxy.triangles.insert(proxy.triangles.end(), kept_as_is.triangles.begin(),
                         kept_as_is.triangles.end());
  proxy.triangle_face.insert(proxy.triangle_face.end(), kept_as_is.triangle_face.begin(),
                             kept_as_is.triangle_face.end());
  return proxy;
}

ProxyBuild::ProxyBuild(std::shared_ptr<const MeshTopology> topology, int max_triangles) {
  if (int(topology->triangle_face.size()) <= max_triangles) {
    result_.emplace();
    return;
  }
  future_ = std::async(std::launch::async, [this, topology, max_triangles] {
    return decimate_triangles(*topology, max_triangles, &cancel_);
  });
}

ProxyBuild::~ProxyBuild() {
  cancel_ = true;
  if (future_.valid()) future_.wait();
}

const ProxyTriangles* ProxyBuild::ready() {
  if (!result_ && future_.valid() &&
      future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
    result_ = future_.get();
  return result_ ? &*result_ : nullptr;
}

const ProxyTriangles& ProxyBuild::wait() {
  if (!result_) result_ = future_.get();
  return *result_;
}

}  // namespace primo::editor
