#include "primo/mesh/mesh_order.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>

#include "primo/util/error.h"

namespace primo {

namespace {

bool point_less(const Vec3& a, const Vec3& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

// A face's corners in file order.
void face_corners(const Mesh& mesh, int face, std::vector<int>& corners) {
  corners.clear();
  for (auto v : mesh.fv_range(mesh.face_handle(face))) corners.push_back(v.idx());
}

std::vector<int> inverse(const std::vector<int>& of) {
  std::vector<int> at(of.size());
  for (size_t i = 0; i < of.size(); ++i) at[size_t(of[i])] = int(i);
  return at;
}

// The faces breadth first over their edges (Cuthill-McKee), each component from a face at its
// far end, neighbours taken in the order of `rank_order` (every face once): the faces a face
// touches lie in the fronts just before and after its own, so sweeps over faces read their
// neighbours' data as two forward streams that the processor prefetches. (A Hilbert curve alone keeps neighbours closer on average
// but jumps back and forth: the energy pass at 238k faces took 7 ms instead of 4.5 ms.)
// Ties are broken by the rank, which the geometry gives, so the order is the file's in no way.
std::vector<int> breadth_first_faces(const Mesh& mesh, const std::vector<int>& rank_order) {
  const size_t n_faces = rank_order.size();
  const std::vector<int> rank = inverse(rank_order);
  std::vector<int> seen(n_faces, 0), queue, next;
  std::vector<char> placed(n_faces, 0);
  int stamp = 0;
  auto visit_from = [&](int start) {  // the unplaced faces reached from start, in visiting order
    ++stamp;
    queue.clear();
    queue.push_back(start);
    seen[size_t(start)] = stamp;
    for (size_t q = 0; q < queue.size(); ++q) {
      next.clear();
      for (auto g : mesh.ff_range(mesh.face_handle(queue[q]))) {
        const int n = g.idx();
        if (seen[size_t(n)] == stamp || placed[size_t(n)]) continue;
        seen[size_t(n)] = stamp;
        next.push_back(n);
      }
      std::sort(next.begin(), next.end(), [&](int a, int b) { return rank[size_t(a)] < rank[size_t(b)]; });
      queue.insert(queue.end(), next.begin(), next.end());
    }
  };
  std::vector<int> faces;
  faces.reserve(n_faces);
  for (int first : rank_order) {
    if (placed[size_t(first)]) continue;
    // Two searches lead towards a peripheral face, where fronts are short.
    int start = first;
    for (int round = 0; round < 2; ++round) {
      visit_from(start);
      start = queue.back();
    }
    visit_from(start);
    for (int f : queue) placed[size_t(f)] = 1, faces.push_back(f);
  }
  return faces;
}

}  // namespace

std::vector<int> MeshOrder::solver_faces() const { return inverse(face_of); }
std::vector<int> MeshOrder::solver_vertices() const { return inverse(vertex_of); }

std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits) {
  // J. Skilling, "Programming the Hilbert curve" (AIP Conf. Proc. 707, 2004): the axes turned
  // into the curve's "transposed" index, whose bits are then interleaved.
  std::array<std::uint32_t, 3> X{x, y, z};
  const std::uint32_t M = std::uint32_t(1) << (bits - 1);
  for (std::uint32_t Q = M; Q > 1; Q >>= 1) {
    const std::uint32_t P = Q - 1;
    for (int i = 0; i < 3; ++i) {
      if (X[size_t(i)] & Q) {
        X[0] ^= P;
      } else {
        const std::uint32_t t = (X[0] ^ X[size_t(i)]) & P;
        X[0] ^= t;
        X[size_t(i)] ^= t;
      }
    }
  }
  for (int i = 1; i < 3; ++i) X[size_t(i)] ^= X[size_t(i - 1)];
  std::uint32_t t = 0;
  for (std::uint32_t Q = M; Q > 1; Q >>= 1)
    if (X[2] & Q) t ^= Q - 1;
  for (std::uint32_t& c : X) c ^= t;
  std::uint64_t index = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (int i = 0; i < 3; ++i) index = (index << 1) | ((X[size_t(i)] >> b) & 1u);
  return index;
}

MeshOrder identity_order(const Mesh& mesh) {
  MeshOrder order;
  order.face_of.resize(mesh.n_faces());
  std::iota(order.face_of.begin(), order.face_of.end(), 0);
  order.face_rotation.assign(mesh.n_faces(), 0);
  order.vertex_of.resize(mesh.n_vertices());
  std::iota(order.vertex_of.begin(), order.vertex_of.end(), 0);
  return order;
}

MeshOrder locality_order(const Mesh& mesh) {
  const int n_faces = int(mesh.n_faces());
  MeshOrder order;
  order.face_rotation.resize(size_t(n_faces));
  // Each face's cycle from its smallest point, and its centroid summed in that cycle order
  // (as the solver mesh's own geometry will sum it), so both are the same for any file order.
  std::vector<Vec3> centroid(static_cast<size_t>(n_faces));
  std::vector<int> corners;
  for (int f = 0; f < n_faces; ++f) {
    face_corners(mesh, f, corners);
    const int n = int(corners.size());
    int start = 0;
    for (int k = 1; k < n; ++k)
      if (point_less(mesh.point(mesh.vertex_handle(corners[size_t(k)])),
                     mesh.point(mesh.vertex_handle(corners[size_t(start)]))))
        start = k;
    order.face_rotation[size_t(f)] = start;
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < n; ++k) c += mesh.point(mesh.vertex_handle(corners[size_t((start + k) % n)]));
    centroid[size_t(f)] = c / double(n);
  }

  // The faces' rank: along the Hilbert curve through the centroids' bounding cube, 21 bits an
  // axis; centroids in one cell (only where faces nearly coincide) by their coordinates.
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const Vec3& c : centroid) low = low.cwiseMin(c), high = high.cwiseMax(c);
  constexpr int kBits = 21;
  const double extent = n_faces > 0 ? (high - low).maxCoeff() : 0.0;
  const double scale = extent > 0 && std::isfinite(extent) ? double((1u << kBits) - 1) / extent : 0.0;
  std::vector<std::uint64_t> key(static_cast<size_t>(n_faces));
  for (int f = 0; f < n_faces; ++f) {
    std::uint32_t cell[3];
    for (int i = 0; i < 3; ++i) {
      const double q = (centroid[size_t(f)][i] - low[i]) * scale;
      cell[i] = std::uint32_t(std::clamp(std::isfinite(q) ? q : 0.0, 0.0, double((1u << kBits) - 1)));
    }
    key[size_t(f)] = hilbert_index(cell[0], cell[1], cell[2], kBits);
  }
  order.face_of.resize(size_t(n_faces));
  std::iota(order.face_of.begin(), order.face_of.end(), 0);
  std::sort(order.face_of.begin(), order.face_of.end(), [&](int a, int b) {
    if (key[size_t(a)] != key[size_t(b)]) return key[size_t(a)] < key[size_t(b)];
    if (centroid[size_t(a)] != centroid[size_t(b)]) return point_less(centroid[size_t(a)], centroid[size_t(b)]);
    return a < b;  // faces with one centroid: only then does the file's order count
  });
  order.face_of = breadth_first_faces(mesh, order.face_of);
  order.face_rotation = order.faces_to_solver(order.face_rotation);  // was per file face

  // Vertices as the faces first reach them, so that a face's corners and its neighbours'
  // lie near each other in every per-vertex array.
  std::vector<char> placed(mesh.n_vertices(), 0);
  order.vertex_of.reserve(mesh.n_vertices());
  for (int i = 0; i < n_faces; ++i) {
    face_corners(mesh, order.face_of[size_t(i)], corners);
    const int n = int(corners.size());
    for (int k = 0; k < n; ++k) {
      const int v = corners[size_t((order.face_rotation[size_t(i)] + k) % n)];
      if (!placed[size_t(v)]) placed[size_t(v)] = 1, order.vertex_of.push_back(v);
    }
  }
  for (int v = 0; v < int(mesh.n_vertices()); ++v)
    if (!placed[size_t(v)]) order.vertex_of.push_back(v);
  return order;
}

Mesh reordered_mesh(const Mesh& mesh, const MeshOrder& order) {
  Mesh out;
  if (!build_reordered_mesh(mesh, order, out))
    throw Error("the mesh cannot be rebuilt in the solver's order");
  return out;
}

bool build_reordered_mesh(const Mesh& mesh, const MeshOrder& order, Mesh& out) {
  out.reserve(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
  for (int v : order.vertex_of) out.add_vertex(mesh.point(mesh.vertex_handle(v)));
  const std::vector<int> solver_vertex = order.solver_vertices();
  std::vector<int> corners;
  std::vector<Mesh::VertexHandle> cycle;
  for (int i = 0; i < order.n_faces(); ++i) {
    face_corners(mesh, order.face_of[size_t(i)], corners);
    const int n = int(corners.size());
    cycle.clear();
    for (int k = 0; k < n; ++k)
      cycle.push_back(out.vertex_handle(solver_vertex[size_t(corners[size_t((order.face_rotation[size_t(i)] + k) % n)])]));
    if (!out.add_face(cycle).is_valid()) return false;
  }
  return true;
}

Mesh shuffled_mesh(const Mesh& mesh, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  // Fisher-Yates with our own draw, so that a seed gives the same mesh with any library.
  auto shuffle = [&](std::vector<int>& items) {
    for (size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[size_t(random() % i)]);
  };
  MeshOrder order;
  order.vertex_of.resize(mesh.n_vertices());
  std::iota(order.vertex_of.begin(), order.vertex_of.end(), 0);
  shuffle(order.vertex_of);
  order.face_of.resize(mesh.n_faces());
  std::iota(order.face_of.begin(), order.face_of.end(), 0);
  shuffle(order.face_of);
  order.face_rotation.resize(mesh.n_faces());
  for (size_t i = 0; i < order.face_of.size(); ++i)
    order.face_rotation[i] = int(random() % mesh.valence(mesh.face_handle(order.face_of[i])));
  return reordered_mesh(mesh, order);
}

}  // namespace primo
