#include "primo/mesh/mesh_generators.h"

#include <cmath>
#include <map>
#include <vector>

#include "primo/util/error.h"

namespace primo {
namespace {

using Handle = Mesh::VertexHandle;

void add_quad(Mesh& mesh, const std::vector<Handle>& v, int a, int b, int c, int d,
              FaceShape shape) {
  if (shape == FaceShape::Quads) {
    mesh.add_face(std::vector<Handle>{v[a], v[b], v[c], v[d]});
  } else {
    mesh.add_face(v[a], v[b], v[c]);
    mesh.add_face(v[a], v[c], v[d]);
  }
}

}  // namespace

Mesh make_cylinder(double radius, double height, int segments, int bands, FaceShape shape) {
  if (segments < 3 || bands < 1) throw Error("a cylinder needs >= 3 segments and >= 1 band");
  Mesh mesh;
  std::vector<Handle> v;
  for (int r = 0; r <= bands; ++r)
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * M_PI * s / segments;
      v.push_back(mesh.add_vertex(
          Vec3(radius * std::cos(phi), height * r / bands, radius * std::sin(phi))));
    }
  // Counter-clockwise seen from outside: normals point away from the axis.
  for (int r = 0; r < bands; ++r)
    for (int s = 0; s < segments; ++s) {
      const int s1 = (s + 1) % segments;
      add_quad(mesh, v, r * segments + s, (r + 1) * segments + s, (r + 1) * segments + s1,
               r * segments + s1, shape);
    }
  return mesh;
}

Mesh make_grid(double size_x, double size_y, int nx, int ny, FaceShape shape) {
  if (nx < 1 || ny < 1) throw Error("a grid needs at least one cell in each direction");
  Mesh mesh;
  std::vector<Handle> v;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) v.push_back(mesh.add_vertex(Vec3(size_x * i / nx, size_y * j / ny, 0)));
  const int row = nx + 1;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      add_quad(mesh, v, j * row + i, j * row + i + 1, (j + 1) * row + i + 1, (j + 1) * row + i,
               shape);
  return mesh;
}

Mesh make_bar(double width, double length, int n_across, int n_along) {
  if (n_across < 1 || n_along < 1) throw Error("a bar needs at least one cell per direction");
  // Rings of the square cross-section, walked counter-clockwise seen from +y.
  std::vector<Vec3> ring;
  const double h = 0.5 * width;
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < n_across; ++k) {
      const double t = -h + width * k / n_across;
      switch (side) {
        case 0: ring.emplace_back(t, 0, h); break;
        case 1: ring.emplace_back(h, 0, -t); break;
        case 2: ring.emplace_back(-t, 0, -h); break;
        case 3: ring.emplace_back(-h, 0, t); break;
      }
    }
  const int m = int(ring.size());
  Mesh mesh;
  std::vector<Handle> v;
  for (int r = 0; r <= n_along; ++r)
    for (const Vec3& p : ring) v.push_back(mesh.add_vertex(Vec3(p.x(), length * r / n_along, p.z())));
  for (int r = 0; r < n_along; ++r)
    for (int s = 0; s < m; ++s) {
      const int s1 = (s + 1) % m;
      add_quad(mesh, v, r * m + s, r * m + s1, (r + 1) * m + s1, (r + 1) * m + s, FaceShape::Quads);
    }
  // Caps: a grid of quads over each end square, sharing the ring vertices on the border.
  for (int end = 0; end < 2; ++end) {
    const double y = end == 0 ? 0.0 : length;
    const int ring_offset = end == 0 ? 0 : n_along * m;
    std::vector<Handle> grid((n_across + 1) * (n_across + 1));
    auto ring_index = [&](int i, int j) -> int {  // border grid point -> ring index
      if (j == n_across) return i;                          // z = +h, x = -h + w i / n
      if (i == n_across) return n_across + (n_across - j);  // x = +h, z = h - w (n-j)/n
      if (j == 0) return 2 * n_across + (n_across - i);     // z = -h
      if (i == 0) return (3 * n_across + j) % m;            // x = -h
      return -1;
    };
    for (int j = 0; j <= n_across; ++j)
      for (int i = 0; i <= n_across; ++i) {
        const int ri = ring_index(i, j);
        grid[j * (n_across + 1) + i] =
            ri >= 0 ? v[ring_offset + ri]
                    : mesh.add_vertex(Vec3(-h + width * i / n_across, y, -h + width * j / n_across));
      }
    const int row = n_across + 1;
    for (int j = 0; j < n_across; ++j)
      for (int i = 0; i < n_across; ++i) {
        std::vector<Handle> quad{grid[j * row + i], grid[j * row + i + 1],
                                 grid[(j + 1) * row + i + 1], grid[(j + 1) * row + i]};
        // The bottom cap faces -y, the top cap +y.
        if (end == 1) std::swap(quad[1], quad[3]);
        mesh.add_face(quad);
      }
  }
  return mesh;
}

Mesh make_icosphere(int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> faces = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& p : points) p.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      points.push_back((points[a] + points[b]).normalized());
      return midpoint[key] = int(points.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    faces.swap(next);
  }
  Mesh mesh;
  std::vector<Handle> v;
  for (const Vec3& p : points) v.push_back(mesh.add_vertex(p));
  for (const auto& f : faces) mesh.add_face(v[f[0]], v[f[1]], v[f[2]]);
  return mesh;
}

}  // namespace primo
