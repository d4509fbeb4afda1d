// Validation of a polygon soup and construction of the OpenMesh PolyMesh.
//
// Everything is checked on the raw soup, before OpenMesh sees it: OpenMesh's add_face either
// rejects a non-manifold face or silently works around it (it duplicates vertices), and in both
// cases the face and vertex indices of the file would no longer be those of the mesh.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "primo/util/error.h"
#include "mesh_validation.h"
#include "primo/mesh/polygon_soup.h"
#include "silence_openmesh.h"

namespace primo {
namespace {

// A face with more corners than this is listed as its first corners and a count.
constexpr size_t kMaxListedVertices = 8;
constexpr size_t kMaxListedFaces = 8;

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw Error(source + ": " + what);
}

// Shortest text that reads back as the same double; "nan" and "inf" as such.
std::string number_text(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string index_list(const std::vector<int>& indices, size_t max_listed) {
  std::string text;
  for (size_t i = 0; i < indices.size() && i < max_listed; ++i) {
    if (i > 0) text += ", ";
    text += std::to_string(indices[i]);
  }
  if (indices.size() > max_listed) text += ", ... (" + std::to_string(indices.size()) + " in all)";
  return text;
}

// "face 12 (vertices 3, 7, 9)"
std::string describe_face(const PolygonSoup& soup, int face) {
  const std::vector<int>& corners = soup.faces[face];
  if (corners.empty()) return "face " + std::to_string(face) + " (no vertices)";
  return "face " + std::to_string(face) + " (vertices " + index_list(corners, kMaxListedVertices) +
         ")";
}

std::string describe_faces(const std::vector<int>& faces) {
  return (faces.size() == 1 ? "face " : "faces ") + index_list(faces, kMaxListedFaces);
}

uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(uint32_t(a)) << 32) | uint32_t(b);
}

// The faces on one undirected edge, by the corner at which each face starts the edge
// (the face runs corner -> corner+1 along it). Only the first two are kept: a third is an error.
struct EdgeUse {
  int count = 0;
  int face[2] = {-1, -1};
  int corner[2] = {-1, -1};
};

using EdgeMap = std::unordered_map<uint64_t, EdgeUse>;

int next_corner(const std::vector<int>& face, int corner) {
  return corner + 1 == int(face.size()) ? 0 : corner + 1;
}

void check_coordinates_finite(const PolygonSoup& soup, const std::string& source) {
  for (size_t v = 0; v < soup.points.size(); ++v) {
    const Vec3& p = soup.points[v];
    if (std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())) continue;
    fail(source, "vertex " + std::to_string(v) + " has a non-finite coordinate (" +
                     number_text(p.x()) + ", " + number_text(p.y()) + ", " + number_text(p.z()) +
                     ")");
  }
}

void check_face_structure(const PolygonSoup& soup, const std::string& source) {
  const long long n_points = static_cast<long long>(soup.points.size());
  std::vector<int> sorted;
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const std::vector<int>& face = soup.faces[f];
    if (face.size() < 3)
      fail(source, describe_face(soup, int(f)) +
                       ": a face needs at least 3 vertices, this one has " +
                       std::to_string(face.size()));
    for (int v : face)
      if (v < 0 || v >= n_points)
        fail(source, describe_face(soup, int(f)) + ": vertex index " + std::to_string(v) +
                         " is out of range (the mesh has " + std::to_string(n_points) +
                         " vertices, indices start at 0)");
    sorted = face;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) continue;
    // Name the first corner, in the face's order, that revisits a vertex.
    std::unordered_set<int> seen;
    for (int v : face)
      if (!seen.insert(v).second)
        fail(source, describe_face(soup, int(f)) + ": vertex " + std::to_string(v) +
                         " appears more than once");
  }
}

// Faces are scanned in file order; the first face that brings an edge to three faces is named.
EdgeMap collect_edges(const PolygonSoup& soup, const std::string& source) {
  EdgeMap edges;
  edges.reserve(soup.faces.size() * 2);
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const std::vector<int>& face = soup.faces[f];
    for (int k = 0; k < int(face.size()); ++k) {
      const int a = face[k];
      const int b = face[next_corner(face, k)];
      EdgeUse& use = edges[edge_key(a, b)];
      if (use.count == 2) {
        // Name every other face on this edge, including any that come later in the file.
        std::vector<int> others;
        for (size_t g = 0; g < soup.faces.size(); ++g) {
          if (g == f) continue;
          const std::vector<int>& other = soup.faces[g];
          for (int j = 0; j < int(other.size()); ++j)
            if (edge_key(other[j], other[next_corner(other, j)]) == edge_key(a, b)) {
              others.push_back(int(g));
              break;
            }
        }
        fail(source, describe_face(soup, int(f)) + ": edge " + std::to_string(a) + "-" +
                         std::to_string(b) + " has more than two faces (also " +
                         describe_faces(others) + ")");
      }
      use.face[use.count] = int(f);
      use.corner[use.count] = k;
      ++use.count;
    }
  }
  return edges;
}

// Two faces on an edge are consistently oriented when they run along it in opposite directions.
void check_orientation(const PolygonSoup& soup, const EdgeMap& edges, const std::string& source) {
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const std::vector<int>& face = soup.faces[f];
    for (int k = 0; k < int(face.size()); ++k) {
      const int a = face[k];
      const int b = face[next_corner(face, k)];
      const EdgeUse& use = edges.at(edge_key(a, b));
      if (use.count < 2 || use.face[1] != int(f)) continue;
      const std::vector<int>& first = soup.faces[use.face[0]];
      if (first[use.corner[0]] != a) continue;  // the first face runs b -> a: consistent
      fail(source, describe_face(soup, int(f)) + ": edge " + std::to_string(a) + "-" +
                       std::to_string(b) + " runs in the same direction in face " +
                       std::to_string(use.face[0]) +
                       ", so the two faces are inconsistently oriented");
    }
  }
}

class DisjointSets {
 public:
  explicit DisjointSets(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void join(int a, int b) { parent_[find(a)] = find(b); }

 private:
  std::vector<int> parent_;
};

// Around a manifold vertex the incident faces form one fan: a single chain (boundary vertex) or
// a single cycle (interior vertex), consecutive faces sharing an edge through the vertex. Face
// corners are joined across every interior edge; a vertex whose corners fall into more than one
// group is where two or more fans touch.
void check_vertex_fans(const PolygonSoup& soup, const EdgeMap& edges, const std::string& source) {
  std::vector<int> first_corner(soup.faces.size() + 1, 0);
  for (size_t f = 0; f < soup.faces.size(); ++f)
    first_corner[f + 1] = first_corner[f] + int(soup.faces[f].size());
  const auto corner_id = [&](int face, int corner) { return first_corner[face] + corner; };

  DisjointSets fans(first_corner.back());
  for (const auto& [key, use] : edges) {
    if (use.count < 2) continue;
    const std::vector<int>& face0 = soup.faces[use.face[0]];
    const std::vector<int>& face1 = soup.faces[use.face[1]];
    // Orientation is consistent by now: face0 runs a -> b, face1 runs b -> a.
    const int a0 = use.corner[0], b0 = next_corner(face0, a0);
    const int b1 = use.corner[1], a1 = next_corner(face1, b1);
    fans.join(corner_id(use.face[0], a0), corner_id(use.face[1], a1));
    fans.join(corner_id(use.face[0], b0), corner_id(use.face[1], b1));
  }

  // Corners grouped by vertex (counting sort keeps faces in file order within a vertex).
  std::vector<int> vertex_start(soup.points.size() + 1, 0);
  for (const auto& face : soup.faces)
    for (int v : face) ++vertex_start[v + 1];
  std::partial_sum(vertex_start.begin(), vertex_start.end(), vertex_start.begin());
  std::vector<int> fill = vertex_start;
  std::vector<int> corner_face(first_corner.back()), corner_fan(first_corner.back());
  for (size_t f = 0; f < soup.faces.size(); ++f)
    for (int k = 0; k < int(soup.faces[f].size()); ++k) {
      const int slot = fill[soup.faces[f][k]]++;
      corner_face[slot] = int(f);
      corner_fan[slot] = fans.find(corner_id(int(f), k));
    }

  for (size_t v = 0; v < soup.points.size(); ++v) {
    const int begin = vertex_start[v], end = vertex_start[v + 1];
    bool single_fan = true;
    for (int s = begin + 1; s < end && single_fan; ++s)
      single_fan = corner_fan[s] == corner_fan[begin];
    if (single_fan) continue;
    std::vector<int> fan_roots;
    std::vector<std::vector<int>> fan_faces;
    for (int s = begin; s < end; ++s) {
      const auto it = std::find(fan_roots.begin(), fan_roots.end(), corner_fan[s]);
      if (it == fan_roots.end()) {
        fan_roots.push_back(corner_fan[s]);
        fan_faces.push_back({corner_face[s]});
      } else {
        fan_faces[it - fan_roots.begin()].push_back(corner_face[s]);
      }
    }
    std::string groups;
    for (const auto& faces : fan_faces)
      groups += (groups.empty() ? "" : "; ") + describe_faces(faces);
    fail(source, "vertex " + std::to_string(v) + " is non-manifold: its faces form " +
                     std::to_string(fan_faces.size()) +
                     " separate fans that share only this vertex (" + groups + ")");
  }
}

// A face is degenerate when its Newell vector area (the spec's a_F) is zero up to the rounding
// that the coordinates themselves carry. Each coordinate is only known to about eps * |p|, and
// moving one corner by d changes the area by at most R * d (R the largest centroid distance), so
// an area below ~ n * eps * R * max|p| has no meaningful normal: collinear or coincident corners
// give such areas even when the decimal input does not land on exactly collinear doubles. The
// bound is relative to the face's own size and position, so a tiny but well-shaped face passes.
void check_face_areas(const PolygonSoup& soup, const std::string& source) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const std::vector<int>& face = soup.faces[f];
    const size_t n = face.size();
    Vec3 centroid = Vec3::Zero();
    for (int v : face) centroid += soup.points[v];
    centroid /= double(n);
    Vec3 vector_area = Vec3::Zero();
    double max_radius = 0.0, max_position = 0.0;
    for (size_t k = 0; k < n; ++k) {
      const Vec3& p = soup.points[face[k]];
      const Vec3& q = soup.points[face[(k + 1) % n]];
      vector_area += (p - centroid).cross(q - centroid);
      max_radius = std::max(max_radius, (p - centroid).norm());
      max_position = std::max(max_position, p.norm());
    }
    vector_area *= 0.5;
    const double area = vector_area.norm();  // exactly as compute_face_geometry computes |F|
    if (!std::isfinite(area))
      fail(source, describe_face(soup, int(f)) +
                       ": its area is not finite (the coordinates are too large)");
    const double rounding = 4.0 * double(n) * eps * max_radius * max_position;
    if (!(area > rounding))
      fail(source,
           describe_face(soup, int(f)) + ": zero area (its vertices are collinear or coincide)");
  }
}

}  // namespace

namespace detail {
void check_soup_geometry(const PolygonSoup& soup, const std::string& source) {
  check_coordinates_finite(soup, source);
  check_face_areas(soup, source);
}
}  // namespace detail

Mesh mesh_from_soup(const PolygonSoup& soup, const std::string& source) {
  if (soup.faces.empty())
    fail(source, "empty mesh: no faces (" + std::to_string(soup.points.size()) + " vertices)");
  if (soup.points.size() > size_t(std::numeric_limits<int>::max()) ||
      soup.faces.size() > size_t(std::numeric_limits<int>::max()))
    fail(source, "too many vertices or faces");

  check_coordinates_finite(soup, source);
  check_face_structure(soup, source);
  const EdgeMap edges = collect_edges(soup, source);
  check_orientation(soup, edges, source);
  check_vertex_fans(soup, edges, source);
  check_face_areas(soup, source);

  // OpenMesh reports add_face failures on its error stream; the library prints nothing.
  silence_openmesh();

  Mesh mesh;
  mesh.reserve(soup.points.size(), edges.size(), soup.faces.size());
  for (const Vec3& p : soup.points) mesh.add_vertex(p);
  std::vector<Mesh::VertexHandle> corners;
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    corners.clear();
    for (int v : soup.faces[f]) corners.push_back(Mesh::VertexHandle(v));
    const Mesh::FaceHandle handle = mesh.add_face(corners);
    // Unreachable after the checks above; kept so a gap in them cannot renumber faces silently.
    if (!handle.is_valid() || handle.idx() != int(f))
      fail(source, describe_face(soup, int(f)) + ": OpenMesh could not add this face");
  }
  return mesh;
}

}  // namespace primo
