// `primo generate cylinder|bar|grid|icosphere [options] -o OUT.ext`: the procedural meshes the
// tests use, written to a file (the shipped examples in assets/ were made this way); and
// `primo generate loop IN --steps K -o OUT.ext`: a triangle mesh Loop-subdivided, the large
// meshes of the benchmarks as a file the editor opens.

#include <CLI/CLI.hpp>
#include <cmath>
#include <memory>
#include <string>

#include "commands.h"
#include "number_options.h"
#include "primo/util/error.h"
#include "primo/mesh/mesh_generators.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/mesh_subdivision.h"
#include "primo/io/output_files.h"
#include "primo/scenario/scenario.h"

namespace primo::app {
namespace {

struct GenerateArguments {
  std::string output;
  double radius = 0.25, length = 2.0, width = 0.2, size_x = 1.0, size_y = 1.0;
  int segments = 16, bands = 24, across = 2, along = 10, nx = 10, ny = 10, subdivisions = 3;
  bool triangles = false;
  std::string input;
  int steps = 1;
};

// Sizes within the bound of every scenario number, so that areas and squared lengths stay
// finite; NaN, infinite or negative sizes made meshes of NaN or inside-out faces.
const CLI::Validator kSize = finite_positive(kMaxScenarioMagnitude);
// 2^24 faces make an OBJ of about 1.5 GB, still within what PriMo reads back (kMaxInputFileBytes);
// more is a mistake (--bands 100000) that would write for minutes, not a request.
constexpr double kMaxFaces = double(1 << 24);
const CLI::Validator kCount = finite_range(1, kMaxFaces);

void check_face_count(double faces, const std::string& output) {
  if (faces > kMaxFaces)
    throw Error(output + ": the mesh would have " + std::to_string(std::llround(faces)) +
                " faces, more than " + std::to_string(std::llround(kMaxFaces)));
}

int write(const Mesh& mesh, const std::string& output) {
  save_mesh(mesh, output);
  std::printf("wrote %s: %zu vertices, %zu faces\n", output.c_str(), mesh.n_vertices(), mesh.n_faces());
  return 0;
}

}  // namespace

Command register_generate(CLI::App& app) {
  auto args = std::make_shared<GenerateArguments>();
  CLI::App* cmd = app.add_subcommand("generate", "Write a procedural mesh (cylinder, bar, grid, icosphere) or a subdivided one (loop)");
  cmd->require_subcommand(1);
  auto shape = [&](CLI::App* sub) { return sub->add_option("-o,--output", args->output, "Mesh file to write")->required(); };

  CLI::App* cylinder = cmd->add_subcommand("cylinder", "Open cylinder along +y");
  shape(cylinder);
  cylinder->add_option("--radius", args->radius)->capture_default_str()->check(kSize);
  cylinder->add_option("--length", args->length)->capture_default_str()->check(kSize);
  cylinder->add_option("--segments", args->segments, "Faces around")
      ->capture_default_str()
      ->check(finite_range(3, kMaxFaces));
  cylinder->add_option("--bands", args->bands, "Faces along")->capture_default_str()->check(kCount);
  cylinder->add_flag("--triangles", args->triangles, "Split each quad into two triangles");

  CLI::App* bar = cmd->add_subcommand("bar", "Closed quad bar along +y with a square section");
  shape(bar);
  bar->add_option("--width", args->width)->capture_default_str()->check(kSize);
  bar->add_option("--length", args->length)->capture_default_str()->check(kSize);
  bar->add_option("--across", args->across, "Faces across each side")
      ->capture_default_str()
      ->check(kCount);
  bar->add_option("--along", args->along, "Faces along")->capture_default_str()->check(kCount);

  CLI::App* grid = cmd->add_subcommand("grid", "Planar grid in the xy plane");
  shape(grid);
  grid->add_option("--size-x", args->size_x)->capture_default_str()->check(kSize);
  grid->add_option("--size-y", args->size_y)->capture_default_str()->check(kSize);
  grid->add_option("--nx", args->nx)->capture_default_str()->check(kCount);
  grid->add_option("--ny", args->ny)->capture_default_str()->check(kCount);
  grid->add_flag("--triangles", args->triangles, "Split each quad into two triangles");

  CLI::App* sphere = cmd->add_subcommand("icosphere", "Unit icosphere");
  shape(sphere);
  sphere->add_option("--subdivisions", args->subdivisions)
      ->capture_default_str()
      ->check(finite_range(0, 8));

  CLI::App* loop = cmd->add_subcommand("loop", "A triangle mesh Loop-subdivided (each step: 4x the faces)");
  shape(loop);
  loop->add_option("input", args->input, "Triangle mesh to subdivide")->required();
  loop->add_option("--steps", args->steps, "Loop steps")
      ->capture_default_str()
      ->check(finite_range(1, 4));

  auto run = [args, cylinder, bar, grid, sphere, loop]() -> int {
    check_mesh_output_path(args->output);
    const FaceShape faces = args->triangles ? FaceShape::Triangles : FaceShape::Quads;
    const double per_quad = args->triangles ? 2.0 : 1.0;
    if (cylinder->parsed()) {
      check_face_count(per_quad * args->segments * args->bands, args->output);
      return write(make_cylinder(args->radius, args->length, args->segments, args->bands, faces), args->output);
    }
    if (bar->parsed()) {
      const double across = args->across;  // four sides and two square ends
      check_face_count(4.0 * across * args->along + 2.0 * across * across, args->output);
      return write(make_bar(args->width, args->length, args->across, args->along), args->output);
    }
    if (grid->parsed()) {
      check_face_count(per_quad * args->nx * args->ny, args->output);
      return write(make_grid(args->size_x, args->size_y, args->nx, args->ny, faces), args->output);
    }
    if (loop->parsed()) {
      const Mesh input = load_mesh(args->input);
      check_face_count(double(input.n_faces()) * std::pow(4.0, args->steps), args->output);
      return write(loop_subdivide(input, args->steps, args->input), args->output);
    }
    return write(make_icosphere(args->subdivisions), args->output);
  };
  return {cmd, run};
}

}  // namespace primo::app
