// `primo generate cylinder|bar|grid|icosphere [options] -o OUT.ext`: the procedural meshes the
// tests use, written to a file (the shipped examples in assets/ were made this way); and
// `primo generate loop IN --steps K -o OUT.ext`: a triangle mesh Loop-subdivided, the large
// meshes of the benchmarks as a file the editor opens.

#include <CLI/CLI.hpp>
#include <memory>

#include "commands.h"
#include "primo/error.h"
#include "primo/mesh_generators.h"
#include "primo/mesh_io.h"
#include "primo/mesh_subdivision.h"
#include "primo/output_files.h"

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
  cylinder->add_option("--radius", args->radius)->capture_default_str();
  cylinder->add_option("--length", args->length)->capture_default_str();
  cylinder->add_option("--segments", args->segments, "Faces around")->capture_default_str();
  cylinder->add_option("--bands", args->bands, "Faces along")->capture_default_str();
  cylinder->add_flag("--triangles", args->triangles, "Split each quad into two triangles");

  CLI::App* bar = cmd->add_subcommand("bar", "Closed quad bar along +y with a square section");
  shape(bar);
  bar->add_option("--width", args->width)->capture_default_str();
  bar->add_option("--length", args->length)->capture_default_str();
  bar->add_option("--across", args->across, "Faces across each side")->capture_default_str();
  bar->add_option("--along", args->along, "Faces along")->capture_default_str();

  CLI::App* grid = cmd->add_subcommand("grid", "Planar grid in the xy plane");
  shape(grid);
  grid->add_option("--size-x", args->size_x)->capture_default_str();
  grid->add_option("--size-y", args->size_y)->capture_default_str();
  grid->add_option("--nx", args->nx)->capture_default_str();
  grid->add_option("--ny", args->ny)->capture_default_str();
  grid->add_flag("--triangles", args->triangles, "Split each quad into two triangles");

  CLI::App* sphere = cmd->add_subcommand("icosphere", "Unit icosphere");
  shape(sphere);
  sphere->add_option("--subdivisions", args->subdivisions)->capture_default_str();

  CLI::App* loop = cmd->add_subcommand("loop", "A triangle mesh Loop-subdivided (each step: 4x the faces)");
  shape(loop);
  loop->add_option("input", args->input, "Triangle mesh to subdivide")->required();
  loop->add_option("--steps", args->steps, "Loop steps")->capture_default_str()->check(CLI::Range(1, 4));

  auto run = [args, cylinder, bar, grid, sphere, loop]() -> int {
    check_mesh_output_path(args->output);
    const FaceShape faces = args->triangles ? FaceShape::Triangles : FaceShape::Quads;
    if (cylinder->parsed())
      return write(make_cylinder(args->radius, args->length, args->segments, args->bands, faces), args->output);
    if (bar->parsed()) return write(make_bar(args->width, args->length, args->across, args->along), args->output);
    if (grid->parsed())
      return write(make_grid(args->size_x, args->size_y, args->nx, args->ny, faces), args->output);
    if (loop->parsed())
      return write(loop_subdivide(load_mesh(args->input), args->steps, args->input), args->output);
    if (args->subdivisions < 0 || args->subdivisions > 8)
      throw Error("--subdivisions must be between 0 and 8");
    return write(make_icosphere(args->subdivisions), args->output);
  };
  return {cmd, run};
}

}  // namespace primo::app
