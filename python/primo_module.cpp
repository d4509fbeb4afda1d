// The `primo` Python module: meshes, deformers, scenarios and sessions for NumPy users, as
// libigl's and CGAL's bindings offer them. A thin layer over the core (docs/python.md): every
// call is a core call, every primo::Error becomes primo.Error with the same message, and the
// arrays the solver makes are handed to NumPy without copying.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "primo/deformer.h"
#include "primo/error.h"
#include "primo/geometry.h"
#include "primo/mesh_io.h"
#include "primo/parallel.h"
#include "primo/scenario.h"
#include "primo/scenario_deformer.h"
#include "primo/scenario_solve.h"
#include "primo/session.h"
#include "primo/session_replay.h"

namespace py = pybind11;
using namespace primo;

namespace {

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Indices = py::array_t<long long, py::array::c_style | py::array::forcecast>;

// A vector of points handed to NumPy as an (n, 3) array that owns it: no copy (Vec3 is three
// contiguous doubles).
py::array_t<double> to_numpy(std::vector<Vec3> points) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
  auto* owned = new std::vector<Vec3>(std::move(points));
  py::capsule free_it(owned, [](void* p) { delete static_cast<std::vector<Vec3>*>(p); });
  const py::ssize_t n = py::ssize_t(owned->size());
  return py::array_t<double>({n, py::ssize_t(3)}, {py::ssize_t(sizeof(Vec3)), py::ssize_t(sizeof(double))},
                             owned->empty() ? nullptr : owned->front().data(), free_it);
}

std::vector<Vec3> from_numpy(const Points& array, const std::string& what) {
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error(what + ": expected an (n, 3) array");
  std::vector<Vec3> points(size_t(array.shape(0)));
  const double* p = array.data();
  for (size_t i = 0; i < points.size(); ++i) points[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  return points;
}

Vec3 vec3(const std::vector<double>& v, const std::string& what) {
  if (v.size() != 3) throw py::value_error(what + ": expected three numbers");
  return Vec3(v[0], v[1], v[2]);
}

// Faces as an (m, k) integer array (all faces k-gons) or any sequence of index sequences
// (polygons of any size).
std::vector<std::vector<int>> faces_from_python(const py::object& faces) {
  std::vector<std::vector<int>> out;
  if (py::isinstance<py::array>(faces) && py::array(faces).ndim() == 2) {
    const Indices a = faces.cast<Indices>();
    const long long* p = a.data();
    out.resize(size_t(a.shape(0)));
    for (size_t f = 0; f < out.size(); ++f)
      for (py::ssize_t k = 0; k < a.shape(1); ++k) out[f].push_back(int(p[f * size_t(a.shape(1)) + size_t(k)]));
    return out;
  }
  for (const py::handle face : faces) {
    std::vector<int> polygon;
    for (const py::handle index : face) polygon.push_back(index.cast<int>());
    out.push_back(std::move(polygon));
  }
  return out;
}

std::vector<int> face_list(const py::object& faces) {
  std::vector<int> out;
  if (py::isinstance<py::array>(faces)) {
    const py::array a(faces);
    if (a.dtype().kind() == 'b') {  // a boolean mask over the faces
      const auto mask = faces.cast<py::array_t<bool, py::array::c_style>>();
      for (py::ssize_t i = 0; i < mask.size(); ++i)
        if (mask.data()[i]) out.push_back(int(i));
      return out;
    }
    const Indices indices = faces.cast<Indices>();
    for (py::ssize_t i = 0; i < indices.size(); ++i) out.push_back(int(indices.data()[i]));
    return out;
  }
  for (const py::handle index : faces) out.push_back(index.cast<int>());
  return out;
}

Fix fix_named(const std::string& name) {
  if (const std::optional<Fix> fix = fix_from_name(name)) return *fix;
  throw py::value_error("fix: expected \"all\", \"position\" or \"orientation\", got \"" + name + "\"");
}


// A transform from keyword arguments: a 4x4 matrix, or translate / axis / angle_deg / center
// (the scenario format's transform).
RigidTransform transform_from(const std::optional<Points>& matrix, const std::vector<double>& translate,
                              const std::vector<double>& axis, double angle_deg,
                              const std::optional<std::vector<double>>& center,
                              const Vec3& default_center) {
  if (matrix) {
    if (matrix->ndim() != 2 || matrix->shape(0) != 4 || matrix->shape(1) != 4)
      throw py::value_error("matrix: expected a 4x4 array");
    RigidTransform t;
    const double* m = matrix->data();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) t.rotation(r, c) = m[4 * r + c];
      t.translation[r] = m[4 * r + 3];
    }
    const Mat3 rtr = t.rotation.transpose() * t.rotation;
    if (!((rtr - Mat3::Identity()).norm() < 1e-6) || !(t.rotation.determinant() > 0))
      throw py::value_error("matrix: the upper 3x3 block is not a rotation");
    return t;
  }
  return make_rigid_transform(vec3(translate, "translate"), vec3(axis, "axis"), angle_deg,
                              center ? vec3(*center, "center") : default_center);
}

SolveOptions solve_options(const std::string& method, int max_iterations, double tolerance, bool path,
                           size_t faces) {
  SolverSpec spec;
  spec.max_iterations = max_iterations;
  spec.tolerance = tolerance;
  SolveOptions o = scenario_solve_options(spec, faces, method == "auto" ? "" : method);
  o.path.enabled = path;
  return o;
}

std::string report_text(const SolveReport& r) {
  std::ostringstream s;
  s << "SolveReport(energy=" << r.energy << ", iterations=" << r.iterations
    << ", converged=" << (r.converged ? "True" : "False") << ", seconds=" << r.seconds
    << ", stop_reason='" << r.stop_reason << "')";
  return s.str();
}

// A Deformer with the mesh it was made on (for its face count and bounding box).
struct PyDeformer {
  std::shared_ptr<const Mesh> mesh;
  std::unique_ptr<Deformer> deformer;
};

PrismParameters prisms_from(std::optional<double> height, std::optional<double> half_thickness,
                            double normal_blend, double width, const std::optional<Points>& height_factors,
                            const std::optional<Points>& width_factors) {
  if (height && half_thickness) throw py::value_error("give at most one of height and half_thickness");
  PrismParameters p = PrismParameters::product_default();
  if (height) {
    p.height = *height;
    p.height_unit = HeightUnit::MeanEdgeLength;
  } else if (half_thickness) {
    p.height = *half_thickness;
  }
  p.normal_blend = normal_blend;
  p.width = width;
  auto factors = [](const std::optional<Points>& a) {
    std::vector<double> out;
    if (a) out.assign(a->data(), a->data() + a->size());
    return out;
  };
  p.face_height_factor = factors(height_factors);
  p.face_width_factor = factors(width_factors);
  return p;
}

}  // namespace

PYBIND11_MODULE(primo, m) {
  m.doc() = "PriMo: coupled prisms for intuitive surface modeling (docs/python.md)";
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      error(e.what());
    }
  });

  m.def("set_thread_count", &set_thread_count, py::arg("threads"),
        "Threads the solver may use (0: every core). Results do not depend on it.");
  m.def("thread_count", &thread_count);

  // --- Meshes ------------------------------------------------------------------------------
  py::class_<Mesh, std::shared_ptr<Mesh>>(m, "Mesh", "A polygon mesh (faces keep their sizes).")
      .def(py::init([](const Points& vertices, const py::object& faces) {
             PolygonSoup soup{from_numpy(vertices, "vertices"), faces_from_python(faces)};
             return std::make_shared<Mesh>(mesh_from_soup(soup, "arrays"));
           }),
           py::arg("vertices"), py::arg("faces"),
           "From an (n, 3) array and faces: an (m, k) integer array or a list of index lists.")
      .def_property_readonly("n_vertices", [](const Mesh& mesh) { return mesh.n_vertices(); })
      .def_property_readonly("n_faces", [](const Mesh& mesh) { return mesh.n_faces(); })
      .def_property_readonly("vertices", [](const Mesh& mesh) {
        std::vector<Vec3> points;
        for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
        return to_numpy(std::move(points));
      })
      .def_property_readonly("faces",
                             [](const Mesh& mesh) -> py::object {
                               std::vector<std::vector<int>> faces;
                               size_t k = 0;
                               bool uniform = true;
                               for (auto f : mesh.faces()) {
                                 std::vector<int> polygon;
                                 for (auto v : f.vertices()) polygon.push_back(v.idx());
                                 if (faces.empty()) k = polygon.size();
                                 uniform = uniform && polygon.size() == k;
                                 faces.push_back(std::move(polygon));
                               }
                               if (!uniform) return py::cast(faces);
                               py::array_t<long long> a({py::ssize_t(faces.size()), py::ssize_t(k)});
                               auto w = a.mutable_unchecked<2>();
                               for (size_t f = 0; f < faces.size(); ++f)
                                 for (size_t i = 0; i < k; ++i) w(py::ssize_t(f), py::ssize_t(i)) = faces[f][i];
                               return std::move(a);
                             },
                             "An (m, k) array when every face has k vertices, else a list of lists.")
      .def_property_readonly("bbox_diagonal", [](const Mesh& mesh) { return bounding_box_diagonal(mesh); })
      .def("face_centroids",
           [](const Mesh& mesh) {
             std::vector<Vec3> c;
             for (auto f : mesh.faces()) {
               Vec3 sum = Vec3::Zero();
               int n = 0;
               for (auto v : f.vertices()) sum += mesh.point(v), ++n;
               c.push_back(sum / double(n));
             }
             return to_numpy(std::move(c));
           },
           "Each face's vertex average, an (m, 3) array (what scenario box and sphere selections test).")
      .def("with_vertices",
           [](const Mesh& mesh, const Points& vertices) {
             const std::vector<Vec3> points = from_numpy(vertices, "vertices");
             if (points.size() != mesh.n_vertices())
               throw py::value_error("vertices: expected " + std::to_string(mesh.n_vertices()) + " rows, got " +
                                     std::to_string(points.size()));
             auto out = std::make_shared<Mesh>(mesh);
             for (auto v : out->vertices()) out->set_point(v, points[size_t(v.idx())]);
             return out;
           },
           py::arg("vertices"), "The same faces at new vertex positions (a deformed copy to save).")
      .def("__repr__", [](const Mesh& mesh) {
        return "Mesh(" + std::to_string(mesh.n_vertices()) + " vertices, " + std::to_string(mesh.n_faces()) +
               " faces)";
      });
  m.def("load_mesh", [](const std::string& path) { return std::make_shared<Mesh>(load_mesh(path)); },
        py::arg("path"), "Reads OBJ, OFF, PLY, STL or OM.");
  m.def("save_mesh", [](const Mesh& mesh, const std::string& path) { save_mesh(mesh, path); },
        py::arg("mesh"), py::arg("path"), "Writes by extension, atomically.");

  // --- Constraints -------------------------------------------------------------------------
  py::class_<Handle>(m, "Handle", "A rigid group of faces moved to a target.")
      .def(py::init([](const py::object& faces, const std::string& fix, const std::string& name) {
             Handle h;
             h.faces = face_list(faces);
             h.fix = fix_named(fix);
             h.name = name;
             return h;
           }),
           py::arg("faces"), py::arg("fix") = "all", py::arg("name") = "",
           "faces: indices or a boolean mask; fix: \"all\", \"position\" or \"orientation\".")
      .def_readwrite("name", &Handle::name)
      .def_property_readonly("faces", [](const Handle& h) { return h.faces; })
      .def_property_readonly("fix", [](const Handle& h) { return fix_name(h.fix); });
  py::class_<Force>(m, "Force", "Springs pulling faces by an offset.")
      .def(py::init([](const py::object& faces, double stiffness, const std::vector<double>& offset,
                       const std::string& name) {
             Force f;
             f.faces = face_list(faces);
             f.stiffness = stiffness;
             f.target_offset = vec3(offset, "offset");
             f.name = name;
             return f;
           }),
           py::arg("faces"), py::arg("stiffness") = 1.0, py::arg("offset") = std::vector<double>{0, 0, 0},
           py::arg("name") = "");

  py::class_<SolveReport>(m, "SolveReport")
      .def_readonly("energy", &SolveReport::energy)
      .def_readonly("initial_energy", &SolveReport::initial_energy)
      .def_readonly("iterations", &SolveReport::iterations)
      .def_readonly("converged", &SolveReport::converged)
      .def_readonly("seconds", &SolveReport::seconds)
      .def_readonly("stop_reason", &SolveReport::stop_reason)
      .def_readonly("energies", &SolveReport::energies)
      .def_readonly("path_steps", &SolveReport::path_steps)
      .def("__repr__", &report_text);

  // --- Deformer ----------------------------------------------------------------------------
  py::class_<PyDeformer>(m, "Deformer", "Rigid prisms on the faces, coupled by elastic joints.")
      .def(py::init([](std::shared_ptr<Mesh> mesh, std::vector<Handle> handles, std::vector<Force> forces,
                       std::optional<double> height, std::optional<double> half_thickness,
                       double normal_blend, double width, std::optional<Points> height_factors,
                       std::optional<Points> width_factors) {
             const PrismParameters prisms =
                 prisms_from(height, half_thickness, normal_blend, width, height_factors, width_factors);
             PyDeformer d;
             d.mesh = mesh;
             d.deformer = std::make_unique<Deformer>(*mesh, prisms, std::move(handles), std::move(forces));
             return d;
           }),
           py::arg("mesh"), py::arg("handles") = std::vector<Handle>{}, py::arg("forces") = std::vector<Force>{},
           py::kw_only(), py::arg("height") = py::none(), py::arg("half_thickness") = py::none(),
           py::arg("normal_blend") = 0.0, py::arg("width") = 1.0, py::arg("height_factors") = py::none(),
           py::arg("width_factors") = py::none(),
           "Prisms: half_thickness (fraction of the bounding-box diagonal; default 0.08, the editor's "
           "material) or height (mean edge lengths, the scenario format's); per-face factors optional.")
      .def("set_handle_transform",
           [](PyDeformer& d, int handle, std::optional<Points> matrix, std::vector<double> translate,
              std::vector<double> axis, double angle_deg, std::optional<std::vector<double>> center) {
             if (handle < 0 || handle >= int(d.deformer->handles().size()))
               throw py::index_error("handle " + std::to_string(handle) + ": there are " +
                                     std::to_string(d.deformer->handles().size()));
             const Vec3 centroid =
                 area_weighted_centroid(compute_face_geometry(*d.mesh), d.deformer->handles()[size_t(handle)].faces);
             d.deformer->set_handle_transform(handle,
                                              transform_from(matrix, translate, axis, angle_deg, center, centroid));
           },
           py::arg("handle"), py::kw_only(), py::arg("matrix") = py::none(),
           py::arg("translate") = std::vector<double>{0, 0, 0}, py::arg("axis") = std::vector<double>{0, 0, 1},
           py::arg("angle_deg") = 0.0, py::arg("center") = py::none(),
           "A 4x4 matrix, or a rotation of angle_deg about axis through center (default: the "
           "handle's area-weighted centroid) followed by translate.")
      .def("set_force_offset",
           [](PyDeformer& d, int force, std::vector<double> offset) {
             if (force < 0 || force >= int(d.deformer->forces().size()))
               throw py::index_error("force " + std::to_string(force) + ": there are " +
                                     std::to_string(d.deformer->forces().size()));
             d.deformer->set_force_offset(force, vec3(offset, "offset"));
           },
           py::arg("force"), py::arg("offset"))
      .def("solve",
           [](PyDeformer& d, const std::string& method, int max_iterations, double tolerance, bool path) {
             const SolveOptions o = solve_options(method, max_iterations, tolerance, path, d.mesh->n_faces());
             py::gil_scoped_release free_python;
             return d.deformer->solve(o);
           },
           py::arg("method") = "auto", py::arg("max_iterations") = 100, py::arg("tolerance") = 1e-8,
           py::arg("path") = true,
           "method: \"auto\" (as primo deform), \"global\", \"hierarchical\" or \"local\"; path: follow "
           "large jumps in sub-steps as a drag would.")
      .def("vertices", [](const PyDeformer& d) { return to_numpy(d.deformer->vertex_positions()); },
           "The deformed vertices, an (n, 3) array.")
      .def_property_readonly("energy", [](const PyDeformer& d) { return d.deformer->energy(); })
      .def_property_readonly("n_handles", [](const PyDeformer& d) { return d.deformer->handles().size(); })
      .def_property_readonly("n_forces", [](const PyDeformer& d) { return d.deformer->forces().size(); })
      .def("reset", [](PyDeformer& d) { d.deformer->reset(); }, "Back to the rest pose.");

  // --- Scenarios and sessions --------------------------------------------------------------
  m.def(
      "deform_scenario",
      [](const std::string& path, const std::string& solver, bool one_step) {
        const Scenario scenario = load_scenario(path);
        const Mesh mesh = load_mesh(scenario.mesh_path);
        const ResolvedScenario resolved = resolve_scenario(scenario, mesh);
        Deformer deformer = make_scenario_deformer(mesh, resolved);
        SolveOptions options = scenario_solve_options(resolved.solver, mesh.n_faces(), solver);
        options.path.enabled = !one_step;
        SolveReport report;
        {
          py::gil_scoped_release free_python;
          report = deformer.solve(options);
        }
        return py::make_tuple(to_numpy(deformer.vertex_positions()), report);
      },
      py::arg("path"), py::arg("solver") = "", py::arg("one_step") = false,
      "Solves a scenario file as primo deform does: (vertices, SolveReport).");
  m.def(
      "replay_session",
      [](const std::string& path, const std::string& mesh_path) {
        const Session session = load_session(path);
        const Mesh mesh = load_mesh(mesh_path.empty() ? session.mesh_path : mesh_path);
        ReplayResult result;
        {
          py::gil_scoped_release free_python;
          result = replay_session(session, mesh);
        }
        py::dict out;
        out["vertices"] = to_numpy(std::move(result.positions));
        out["frames"] = result.frames;
        out["converged"] = result.converged;
        out["energy"] = result.energy;
        out["iterations"] = result.iterations;
        return out;
      },
      py::arg("path"), py::arg("mesh") = "",
      "Replays a recorded editor session as primo replay does: a dict with vertices, frames, "
      "converged, energy, iterations.");
}
