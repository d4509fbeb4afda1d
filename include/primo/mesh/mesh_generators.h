#pragma once
// Procedural meshes for tests, benchmarks and the shipped examples.

#include "primo/mesh/mesh.h"

namespace primo {

enum class FaceShape { Quads, Triangles };

// Open cylinder around the y axis from y = 0 to y = height: `segments` around, `bands` along.
// Vertex (ring r, segment s) has index r * segments + s; triangles split each quad along
// the same diagonal.
Mesh make_cylinder(double radius, double height, int segments, int bands, FaceShape shape);

// Planar grid in the xy plane, [0, size_x] x [0, size_y], nx by ny cells, normal +z.
Mesh make_grid(double size_x, double size_y, int nx, int ny, FaceShape shape);

// Closed box-shaped bar [-w/2, w/2] x [0, length] x [-w/2, w/2] of quads: `n_around` cells
// across each side and `n_along` along y. Polygon meshes stay polygons.
Mesh make_bar(double width, double length, int n_across, int n_along);

// Unit icosphere after `subdivisions` 1:4 splits (20 * 4^s triangles).
Mesh make_icosphere(int subdivisions);

}  // namespace primo
