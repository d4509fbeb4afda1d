#include "proxy_mesh.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <algorithm>
#include <chrono>
#include <exception>
#include <mutex>
#include <numeric>
#include <thread>

#include "collapse_check.h"
#include "primo/solve/body_partition.h"

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

// The mesh the stand-in is decimated on: the decimater asks its mesh type whether a collapse
// is allowed, and this one answers with the test compiled here (collapse_check.h says why).
struct ProxyMesh : OpenMesh::TriMesh_ArrayKernelT<ProxyTraits> {
  bool is_collapse_ok(HalfedgeHandle v0v1) const { return collapse_keeps_manifold(*this, v0v1); }
};

// A collapse may turn no triangle's normal by more than this: the stand-in keeps the
// silhouette and never shows a triangle's back.
constexpr float kMaxNormalDeviationDegrees = 45.0f;
// Longest edge over height: no needles.
constexpr float kMaxAspectRatio = 8.0f;
// Meshes of at least twice this many triangles are decimated in 2^kProxyPartLevels parts at
// once, each to kPartSlack times its share of the budget (decimate_triangles).
constexpr size_t kTrianglesPerPart = 20000;
constexpr int kProxyPartLevels = 3;
constexpr double kPartSlack = 1.25;

bool cancelled(const DecimationSignals* signals) {
  return signals && signals->cancel.load(std::memory_order_relaxed);
}

// Returns at once unless paused; then when unpaused or cancelled.
void wait_while_paused(const DecimationSignals* signals) {
  constexpr auto kPausePoll = std::chrono::milliseconds(20);
  while (signals && signals->paused.load(std::memory_order_relaxed) && !cancelled(signals))
    std::this_thread::sleep_for(kPausePoll);
}

// OpenMesh's decimater asks its observer every kCheckCollapses collapses whether to stop; a
// paused build waits there (the collapses made so far stay, so the result is the same).
class SignalObserver : public OpenMesh::Decimater::Observer {
 public:
  static constexpr size_t kCheckCollapses = 500;
  explicit SignalObserver(const DecimationSignals* signals)
      : Observer(kCheckCollapses), signals_(signals) {}
  void notify(size_t) override { wait_while_paused(signals_); }
  bool abort() const override { return cancelled(signals_); }

 private:
  const DecimationSignals* signals_;
};

void append_triangle(ProxyTriangles& to, const unsigned* corners, int face) {
  to.triangles.insert(to.triangles.end(), corners, corners + 3);
  to.triangle_face.push_back(face);
}

void append(ProxyTriangles& to, const ProxyTriangles& from) {
  to.triangles.insert(to.triangles.end(), from.triangles.begin(), from.triangles.end());
  to.triangle_face.insert(to.triangle_face.end(), from.triangle_face.begin(),
                          from.triangle_face.end());
}

// Decimates `input` (triangles indexing `points`) to about `budget` triangles, its
// boundary (an open rim, or a seam where the caller cut the mesh into parts) kept as it is.
ProxyTriangles decimate_part(const std::vector<Vec3>& points, const ProxyTriangles& input,
                             size_t budget, const DecimationSignals* signals) {
  wait_while_paused(signals);
  SignalObserver observer(signals);
  ProxyMesh mesh;
  std::vector<int> local(points.size(), -1);  // the mesh's vertex of each point used
  std::vector<unsigned> point_of;
  for (const unsigned v : input.triangles)
    if (local[v] < 0) {
      local[v] = int(point_of.size());
      point_of.push_back(v);
    }
  mesh.reserve(point_of.size(), 3 * input.triangle_face.size() / 2, input.triangle_face.size());
  for (const unsigned v : point_of)
    mesh.add_vertex(ProxyMesh::Point(points[v].x(), points[v].y(), points[v].z()));
  std::vector<int> source_triangle;  // OpenMesh face index -> triangle of `input`
  source_triangle.reserve(input.triangle_face.size());
  ProxyTriangles kept_as_is;
  for (size_t i = 0; i < input.triangle_face.size(); ++i) {
    const unsigned* c = &input.triangles[3 * i];
    const auto f = mesh.add_face(mesh.vertex_handle(local[c[0]]), mesh.vertex_handle(local[c[1]]),
                                 mesh.vertex_handle(local[c[2]]));
    if (f.is_valid()) {
      source_triangle.push_back(int(i));
      continue;
    }
    append_triangle(kept_as_is, c, input.triangle_face[i]);
  }
  // Corners of triangles left out of the decimation, and boundary loops, stay where they are.
  for (const unsigned v : kept_as_is.triangles)
    mesh.status(mesh.vertex_handle(local[v])).set_locked(true);
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
  const size_t target =
      std::max<size_t>(1, budget - std::min(budget, kept_as_is.triangle_face.size()));
  decimater.decimate_to_faces(0, target);
  if (observer.abort()) return {};

  ProxyTriangles proxy;
  proxy.triangles.reserve(3 * target + kept_as_is.triangles.size());
  proxy.triangle_face.reserve(target + kept_as_is.triangle_face.size());
  for (const auto f : mesh.faces()) {  // skips deleted faces
    for (const auto v : f.vertices()) proxy.triangles.push_back(point_of[size_t(v.idx())]);
    proxy.triangle_face.push_back(input.triangle_face[size_t(source_triangle[size_t(f.idx())])]);
  }
  append(proxy, kept_as_is);
  return proxy;
}

// The triangles cut into 2^levels parts by recursive bisection of their centroids (the
// solver's body partition: median cuts along the longest axis, fixed by the mesh).
std::vector<ProxyTriangles> spatial_parts(const MeshTopology& t, int levels) {
  const size_t n = t.triangle_face.size();
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  std::vector<Vec3> centroid(n);
  for (size_t i = 0; i < n; ++i)
    centroid[i] = (t.rest_points[t.triangles[3 * i]] + t.rest_points[t.triangles[3 * i + 1]] +
                   t.rest_points[t.triangles[3 * i + 2]]) /
                  3.0;
  const size_t parts = size_t(1) << levels;
  const BodyPartition partition =
      partition_bodies(std::move(all), centroid, {}, (n + parts - 1) / parts, levels);
  std::vector<ProxyTriangles> out(partition.parts.size());
  for (size_t p = 0; p < out.size(); ++p)
    for (const int i : partition.parts[p])
      append_triangle(out[p], &t.triangles[3 * size_t(i)], t.triangle_face[size_t(i)]);
  return out;
}

}  // namespace

ProxyTriangles decimate_triangles(const MeshTopology& t, int max_triangles,
                                  const DecimationSignals* signals, int threads) {
  const size_t n = t.triangle_face.size(), budget = size_t(std::max(1, max_triangles));
  if (n <= budget) return {};
  // OpenMesh's decimater is serial (238,656 triangles: 1.6-1.7 s in parts on one thread,
  // 0.8-0.9 s on two; the koala's 99,994 0.5 s on two). Big meshes
  // are cut into parts decimated side by side, their seams kept, then the joined parts are
  // decimated once more to the budget, seams free: the parts go to a little above their share
  // so that the last pass has their seams' extra triangles and some more to take. The parts
  // are fixed by the mesh, not by the cores, so the stand-in is the same on any machine.
  wait_while_paused(signals);
  if (n < kTrianglesPerPart * 2)
    return decimate_part(t.rest_points, {t.triangles, t.triangle_face}, budget, signals);
  std::vector<ProxyTriangles> pieces = spatial_parts(t, kProxyPartLevels);
  // On threads of their own, not the solver's pool: a part takes a second or so, and a
  // solver thread waiting in that pool could pick one up in the middle of a drag.
  std::atomic<size_t> next{0};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  auto work = [&] {
    try {
      for (size_t p = next++; p < pieces.size(); p = next++) {
        const double share =
            kPartSlack * double(budget) * double(pieces[p].triangle_face.size()) / double(n);
        pieces[p] = decimate_part(t.rest_points, pieces[p], size_t(share), signals);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
  const unsigned cores = threads > 0 ? unsigned(threads) : std::thread::hardware_concurrency();
  const unsigned workers = std::clamp(cores, 1u, unsigned(pieces.size()));
  std::vector<std::thread> helpers;
  for (unsigned k = 1; k < workers; ++k) helpers.emplace_back(work);
  work();
  for (std::thread& h : helpers) h.join();
  if (failure) std::rethrow_exception(failure);
  if (cancelled(signals)) return {};
  ProxyTriangles joined;
  for (const ProxyTriangles& piece : pieces) append(joined, piece);
  return decimate_part(t.rest_points, joined, budget, signals);
}

ProxyBuild::ProxyBuild(std::shared_ptr<const MeshTopology> topology, int max_triangles) {
  if (int(topology->triangle_face.size()) <= max_triangles) {
    result_.emplace();
    return;
  }
  signals_.paused = true;
  future_ = std::async(std::launch::async, [this, topology, max_triangles] {
    return decimate_triangles(*topology, max_triangles, &signals_);
  });
}

ProxyBuild::~ProxyBuild() {
  signals_.cancel = true;
  if (future_.valid()) future_.wait();
}

const ProxyTriangles* ProxyBuild::ready() {
  if (!result_ && future_.valid() &&
      future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
    result_ = future_.get();
  return result_ ? &*result_ : nullptr;
}

const ProxyTriangles& ProxyBuild::wait() {
  set_paused(false);
  if (!result_) result_ = future_.get();
  return *result_;
}

void ProxyBuild::set_paused(bool paused) {
  signals_.paused.store(paused, std::memory_order_relaxed);
}

bool stand_in_waits(bool drawn_in_software, bool editor_settled, bool in_motion) {
  return !drawn_in_software && !editor_settled && !in_motion;
}

}  // namespace primo::editor
