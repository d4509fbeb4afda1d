// The `primo` Python module: meshes, deformers, scenarios and sessions for NumPy users, as
// libigl's and CGAL's bindings offer them. A thin layer over the core (docs/python.md): every
// call is a core call, every primo::Error becomes primo.Error with the same message, and the
// arrays the solver makes are handed to NumPy without copying.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <sstream>
#include <string>
#include <vector>

#include "primo/solve/deformer.h"
#include "primo/util/error.h"
#include "primo/mesh/geometry.h"
#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "primo/io/output_files.h"
#include "primo/util/parallel.h"
#include "primo/scenario/scenario.h"
#include "primo/scenario/scenario_deformer.h"
#include "primo/scenario/scenario_solve.h"
#include "primo/sessions/session.h"
#include "primo/sessions/session_replay.h"

namespace py = pybind11;
using namespace primo;

namespace {

// A mesh read from a file keeps the attributes it was read with (UVs, normals, colours,
// materials), so that save_mesh writes a posed copy with them as `primo deform` does. Python
// sees it as a primo.Mesh: pybind11 hands out the registered base class.
struct MeshWithAttributes : Mesh {
  MeshWithAttributes(Mesh mesh, MeshAttributes attributes)
      : Mesh(std::move(mesh)), attributes(std::move(attributes)) {}
  MeshAttributes attributes;
};

// The attributes `mesh` was read with, null for a mesh made from arrays.
const MeshAttributes* attributes_of(const Mesh& mesh) {
  const auto* read = dynamic_cast<const MeshWithAttributes*>(&mesh);
  return read ? &read->attributes : nullptr;
}

// A file's mesh with its attributes.
std::shared_ptr<Mesh> mesh_with_attributes(const std::string& path) {
  LoadedMesh loaded = load_mesh_noted(path);
  return std::make_shared<MeshWithAttributes>(std::move(loaded.mesh), std::move(loaded.attributes));
}

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Indices = py::array_t<long long, py::array::c_style | py::array::forcecast>;

// Work on the solver's threads holds this shared; a change of their number holds it alone, so
// that it waits for running solves (TBB's arena must not be replaced under them).
std::shared_mutex g_thread_pool;

// The C++ object behind `self` or an argument. `Type.__new__(Type)` makes an instance whose
// __init__ never ran, and pybind11 would hand its methods uninitialised memory.
template <class T>
T& initialized(py::handle object, const char* type_name) {
  if (!py::isinstance<T>(object))
    throw py::type_error(std::string("expected a primo.") + type_name + ", got " +
                         std::string(py::str(py::type::handle_of(object).attr("__name__"))));
  auto* instance = reinterpret_cast<py::detail::instance*>(object.ptr());
  py::detail::value_and_holder v = instance->get_value_and_holder(py::detail::get_type_info(typeid(T)));
  if (!v || !v.holder_constructed())
    throw py::type_error(std::string("primo.") + type_name + ".__init__ was not called");
  return *v.template value_ptr<T>();
}

double finite_number(double x, const std::string& what) {
  if (!std::isfinite(x)) throw py::value_error(what + ": expected a finite number");
  return x;
}

double number_at_least(double x, double least, const std::string& what) {
  if (!(std::isfinite(x) && x >= least)) {
    char bound[32];
    std::snprintf(bound, sizeof bound, "%g", least);
    throw py::value_error(what + ": expected a finite number of at least " + bound);
  }
  return x;
}

double positive_number(double x, const std::string& what) {
  if (!(std::isfinite(x) && x > 0)) throw py::value_error(what + ": expected a finite number above 0");
  return x;
}

// An index as the scenario format reads one: an integer in [0, 2^31 - 1], never a float or a
// bool, never wrapped.
int index_value(long long value, const std::string& what) {
  if (value < 0 || value > std::numeric_limits<int>::max())
    throw py::index_error(what + ": index " + std::to_string(value) + " is out of range");
  return int(value);
}

int index_from(py::handle item, const std::string& what) {
  if (PyBool_Check(item.ptr()) || !PyLong_Check(item.ptr()))
    throw py::type_error(what + ": expected integer indices, got " +
                         std::string(py::str(py::type::handle_of(item).attr("__name__"))));
  int overflow = 0;
  const long long value = PyLong_AsLongLongAndOverflow(item.ptr(), &overflow);
  if (overflow != 0) throw py::index_error(what + ": index " + std::string(py::str(item)) + " is out of range");
  return index_value(value, what);
}

// An integer NumPy array's entries (floats are refused rather than truncated).
Indices integer_array(const py::array& a, const std::string& what) {
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::type_error(what + ": expected an integer array, got dtype " + std::string(py::str(a.dtype())));
  if (kind == 'u' && a.dtype().itemsize() >= 8) {  // above 2^63 would wrap in long long
    const auto u = a.cast<py::array_t<unsigned long long, py::array::c_style | py::array::forcecast>>();
    for (py::ssize_t i = 0; i < u.size(); ++i)
      if (u.data()[i] > (unsigned long long)std::numeric_limits<int>::max())
        throw py::index_error(what + ": index " + std::to_string(u.data()[i]) + " is out of range");
  }
  return a.cast<Indices>();
}

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
  for (size_t i = 0; i < points.size(); ++i) {
    points[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    if (!points[i].allFinite())
      throw py::value_error(what + ": row " + std::to_string(i) + " is not finite");
  }
  return points;
}

Vec3 vec3(const std::vector<double>& v, const std::string& what) {
  if (v.size() != 3) throw py::value_error(what + ": expected three numbers");
  const Vec3 out(v[0], v[1], v[2]);
  if (!out.allFinite()) throw py::value_error(what + ": expected finite numbers");
  return out;
}

// Faces as an (m, k) integer array (all faces k-gons) or any sequence of index sequences
// (polygons of any size).
std::vector<std::vector<int>> faces_from_python(const py::object& faces) {
  std::vector<std::vector<int>> out;
  if (py::isinstance<py::array>(faces) && py::array(faces).ndim() == 2) {
    const Indices a = integer_array(py::array(faces), "faces");
    const long long* p = a.data();
    out.resize(size_t(a.shape(0)));
    for (size_t f = 0; f < out.size(); ++f)
      for (py::ssize_t k = 0; k < a.shape(1); ++k)
        out[f].push_back(index_value(p[f * size_t(a.shape(1)) + size_t(k)], "faces"));
    return out;
  }
  for (const py::handle face : faces) {
    std::vector<int> polygon;
    for (const py::handle index : face) polygon.push_back(index_from(index, "faces"));
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
    const Indices indices = integer_array(a, "faces");
    for (py::ssize_t i = 0; i < indices.size(); ++i) out.push_back(index_value(indices.data()[i], "faces"));
    return out;
  }
  for (const py::handle index : faces) out.push_back(index_from(index, "faces"));
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
    for (int i = 0; i < 16; ++i)
      if (!std::isfinite(m[i])) throw py::value_error("matrix: expected finite numbers");
    if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0)
      throw py::value_error("matrix: the bottom row must be 0 0 0 1 (a rigid motion)");
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) t.rotation(r, c) = m[4 * r + c];
      t.translation[r] = m[4 * r + 3];
    }
    const Mat3 rtr = t.rotation.transpose() * t.rotation;
    if (!((rtr - Mat3::Identity()).norm() < 1e-6) || !(t.rotation.determinant() > 0))
      throw py::value_error("matrix: the upper 3x3 block is not a rotation");
    return t;
  }
  return make_rigid_transform(vec3(translate, "translate"), vec3(axis, "axis"),
                              finite_number(angle_deg, "angle_deg"),
                              center ? vec3(*center, "center") : default_center);
}

SolveOptions solve_options(const std::string& method, int max_iterations, double tolerance, bool path,
                           size_t faces) {
  if (method != "auto" && method != "global" && method != "hierarchical" && method != "local")
    throw py::value_error("method: expected \"auto\", \"global\", \"hierarchical\" or \"local\", got \"" +
                          method + "\"");
  if (max_iterations < 0) throw py::value_error("max_iterations: expected at least 0");
  number_at_least(tolerance, 0.0, "tolerance");
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
  // One call at a time: a Deformer is not thread-safe, and Python threads may share one.
  std::unique_ptr<std::mutex> busy = std::make_unique<std::mutex>();
};

// Runs `work` on the deformer behind `self` without the GIL, once the calls of other threads
// on it (and any change of the thread count) have ended.
template <class Work>
auto with_deformer(py::handle self, Work&& work) {
  PyDeformer& d = initialized<PyDeformer>(self, "Deformer");
  py::gil_scoped_release free_python;
  std::shared_lock<std::shared_mutex> pool(g_thread_pool);
  std::lock_guard<std::mutex> lock(*d.busy);
  return work(d);
}

PrismParameters prisms_from(std::optional<double> height, std::optional<double> half_thickness,
                            double normal_blend, double width, const std::optional<Points>& height_factors,
                            const std::optional<Points>& width_factors) {
  if (height && half_thickness) throw py::value_error("give at most one of height and half_thickness");
  PrismParameters p = PrismParameters::product_default();
  if (height) {
    p.height = number_at_least(*height, 0.0, "height");
    p.height_unit = HeightUnit::MeanEdgeLength;
  } else if (half_thickness) {
    p.height = number_at_least(*half_thickness, 0.0, "half_thickness");
  }
  p.normal_blend = finite_number(normal_blend, "normal_blend");
  p.width = positive_number(width, "width");
  // As the scenario format's regions: heights at least 0, widths above 0.
  auto factors = [](const std::optional<Points>& a, bool zero_allowed, const std::string& what) {
    std::vector<double> out;
    if (a) out.assign(a->data(), a->data() + a->size());
    for (double x : out)
      if (zero_allowed) number_at_least(x, 0.0, what); else positive_number(x, what);
    return out;
  };
  p.face_height_factor = factors(height_factors, true, "height_factors");
  p.face_width_factor = factors(width_factors, false, "width_factors");
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

  m.def(
      "set_thread_count",
      [](int threads) {
        if (threads < 0) throw py::value_error("threads: expected 0 (every core) or more");
        py::gil_scoped_release free_python;
        std::unique_lock<std::shared_mutex> pool(g_thread_pool);  // after running solves
        set_thread_count(threads);
      },
      py::arg("threads"),
      "Threads the solver may use (0: every core). Results do not depend on it; a change waits "
      "for running solves.");
  m.def("thread_count", &thread_count);

  // --- Meshes ------------------------------------------------------------------------------
  py::class_<Mesh, std::shared_ptr<Mesh>>(m, "Mesh", "A polygon mesh (faces keep their sizes).")
      .def(py::init([](const Points& vertices, const py::object& faces) {
             PolygonSoup soup{from_numpy(vertices, "vertices"), faces_from_python(faces)};
             return std::make_shared<Mesh>(mesh_from_soup(soup, "arrays"));
           }),
           py::arg("vertices"), py::arg("faces"),
           "From an (n, 3) array and faces: an (m, k) integer array or a list of index lists.")
      .def_property_readonly("n_vertices", [](py::handle mesh_object) {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh"); return mesh.n_vertices(); })
      .def_property_readonly("n_faces", [](py::handle mesh_object) {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh"); return mesh.n_faces(); })
      .def_property_readonly("vertices", [](py::handle mesh_object) {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh");
        std::vector<Vec3> points;
        for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
        return to_numpy(std::move(points));
      })
      .def_property_readonly("faces",
                             [](py::handle mesh_object) -> py::object {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh");
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
      .def_property_readonly("bbox_diagonal", [](py::handle mesh_object) {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh"); return bounding_box_diagonal(mesh); })
      .def("face_centroids",
           [](py::handle mesh_object) {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh");
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
           [](py::handle mesh_object, const Points& vertices) {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh");
             const std::vector<Vec3> points = from_numpy(vertices, "vertices");
             if (points.size() != mesh.n_vertices())
               throw py::value_error("vertices: expected " + std::to_string(mesh.n_vertices()) + " rows, got " +
                                     std::to_string(points.size()));
             std::shared_ptr<Mesh> out;
             if (const MeshAttributes* attributes = attributes_of(mesh))
               out = std::make_shared<MeshWithAttributes>(mesh, *attributes);
             else
               out = std::make_shared<Mesh>(mesh);
             for (auto v : out->vertices()) out->set_point(v, points[size_t(v.idx())]);
             return out;
           },
           py::arg("vertices"),
           "The same faces, and the attributes the mesh was read with, at new vertex positions "
           "(a deformed copy to save).")
      .def("__repr__", [](py::handle mesh_object) {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh");
        return "Mesh(" + std::to_string(mesh.n_vertices()) + " vertices, " + std::to_string(mesh.n_faces()) +
               " faces)";
      });
  m.def("load_mesh",
        &mesh_with_attributes, py::arg("path"),
        "Reads OBJ, OFF, PLY, STL, OM, glTF, FBX, COLLADA or 3MF, with its UVs, normals, colours and "
        "materials.");
  m.def("save_mesh", [](py::handle mesh_object, const std::string& path) {
        const Mesh& mesh = initialized<Mesh>(mesh_object, "Mesh");
        if (const MeshAttributes* attributes = attributes_of(mesh))
          save_mesh(mesh, *attributes, path);
        else
          save_mesh(mesh, path); },
        py::arg("mesh"), py::arg("path"),
        "Writes by extension, atomically, with the attributes the mesh was read with.");

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
      .def_property(
          "name", [](py::handle self) { return initialized<Handle>(self, "Handle").name; },
          [](py::handle self, const std::string& name) { initialized<Handle>(self, "Handle").name = name; })
      .def_property_readonly("faces", [](py::handle self) {
        const Handle& h = initialized<Handle>(self, "Handle"); return h.faces; })
      .def_property_readonly("fix", [](py::handle self) {
        const Handle& h = initialized<Handle>(self, "Handle"); return fix_name(h.fix); });
  py::class_<Force>(m, "Force", "Springs pulling faces by an offset.")
      .def(py::init([](const py::object& faces, double stiffness, const std::vector<double>& offset,
                       const std::string& name) {
             Force f;
             f.faces = face_list(faces);
             f.stiffness = number_at_least(stiffness, 0.0, "stiffness");
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
  py::class_<PyDeformer>(m, "Deformer",
                         "Rigid prisms on the faces, coupled by elastic joints. Safe to share across "
                         "threads: calls on one Deformer run one at a time.")
      .def(py::init([](py::handle mesh_object, const py::sequence& handle_objects,
                       const py::sequence& force_objects, std::optional<double> height,
                       std::optional<double> half_thickness, double normal_blend, double width,
                       std::optional<Points> height_factors, std::optional<Points> width_factors) {
             initialized<Mesh>(mesh_object, "Mesh");
             std::vector<Handle> handles;
             for (const py::handle h : handle_objects) handles.push_back(initialized<Handle>(h, "Handle"));
             std::vector<Force> forces;
             for (const py::handle f : force_objects) forces.push_back(initialized<Force>(f, "Force"));
             const PrismParameters prisms =
                 prisms_from(height, half_thickness, normal_blend, width, height_factors, width_factors);
             PyDeformer d;
             d.mesh = mesh_object.cast<std::shared_ptr<Mesh>>();
             py::gil_scoped_release free_python;
             std::shared_lock<std::shared_mutex> pool(g_thread_pool);
             d.deformer = std::make_unique<Deformer>(*d.mesh, prisms, std::move(handles), std::move(forces));
             return d;
           }),
           py::arg("mesh"), py::arg("handles") = py::list(), py::arg("forces") = py::list(),
           py::kw_only(), py::arg("height") = py::none(), py::arg("half_thickness") = py::none(),
           py::arg("normal_blend") = 0.0, py::arg("width") = 1.0, py::arg("height_factors") = py::none(),
           py::arg("width_factors") = py::none(),
           "Prisms: half_thickness (fraction of the bounding-box diagonal; default 0.08, the editor's "
           "material) or height (mean edge lengths, the scenario format's); per-face factors optional.")
      .def("set_handle_transform",
           [](py::handle self, int handle, std::optional<Points> matrix, std::vector<double> translate,
              std::vector<double> axis, double angle_deg, std::optional<std::vector<double>> center) {
             with_deformer(self, [&](PyDeformer& d) {
               if (handle < 0 || handle >= int(d.deformer->handles().size()))
                 throw py::index_error("handle " + std::to_string(handle) + ": there are " +
                                       std::to_string(d.deformer->handles().size()));
               const Vec3 centroid = area_weighted_centroid(compute_face_geometry(*d.mesh),
                                                            d.deformer->handles()[size_t(handle)].faces);
               d.deformer->set_handle_transform(
                   handle, transform_from(matrix, translate, axis, angle_deg, center, centroid));
             });
           },
           py::arg("handle"), py::kw_only(), py::arg("matrix") = py::none(),
           py::arg("translate") = std::vector<double>{0, 0, 0}, py::arg("axis") = std::vector<double>{0, 0, 1},
           py::arg("angle_deg") = 0.0, py::arg("center") = py::none(),
           "A 4x4 matrix, or a rotation of angle_deg about axis through center (default: the "
           "handle's area-weighted centroid) followed by translate.")
      .def("set_force_offset",
           [](py::handle self, int force, std::vector<double> offset) {
             with_deformer(self, [&](PyDeformer& d) {
               if (force < 0 || force >= int(d.deformer->forces().size()))
                 throw py::index_error("force " + std::to_string(force) + ": there are " +
                                       std::to_string(d.deformer->forces().size()));
               d.deformer->set_force_offset(force, vec3(offset, "offset"));
             });
           },
           py::arg("force"), py::arg("offset"))
      .def("solve",
           [](py::handle self, const std::string& method, int max_iterations, double tolerance, bool path) {
             return with_deformer(self, [&](PyDeformer& d) {
               const SolveOptions o = solve_options(method, max_iterations, tolerance, path, d.mesh->n_faces());
               return d.deformer->solve(o);
             });
           },
           py::arg("method") = "auto", py::arg("max_iterations") = 100, py::arg("tolerance") = 1e-8,
           py::arg("path") = true,
           "method: \"auto\" (as primo deform), \"global\", \"hierarchical\" or \"local\"; path: follow "
           "large jumps in sub-steps as a drag would. Another thread's solve on the same Deformer "
           "waits for this one.")
      .def("vertices",
           [](py::handle self) {
             return to_numpy(with_deformer(self, [](PyDeformer& d) { return d.deformer->vertex_positions(); }));
           },
           "The deformed vertices, an (n, 3) array.")
      .def_property_readonly("energy",
                             [](py::handle self) {
                               return with_deformer(self, [](PyDeformer& d) { return d.deformer->energy(); });
                             })
      .def_property_readonly("n_handles",
                             [](py::handle self) {
                               return initialized<PyDeformer>(self, "Deformer").deformer->handles().size();
                             })
      .def_property_readonly("n_forces",
                             [](py::handle self) {
                               return initialized<PyDeformer>(self, "Deformer").deformer->forces().size();
                             })
      .def("reset", [](py::handle self) { with_deformer(self, [](PyDeformer& d) { d.deformer->reset(); }); },
           "Back to the rest pose.");

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
          std::shared_lock<std::shared_mutex> pool(g_thread_pool);
          report = deformer.solve(options);
        }
        return py::make_tuple(to_numpy(deformer.vertex_positions()), report);
      },
      py::arg("path"), py::arg("solver") = "", py::arg("one_step") = false,
      "Solves a scenario file as primo deform does: (vertices, SolveReport).");
  m.def(
      "load_scenario",
      [](const std::string& path) {
        const Scenario scenario = load_scenario(path);
        const std::shared_ptr<Mesh> mesh = mesh_with_attributes(scenario.mesh_path);
        const ResolvedScenario resolved = resolve_scenario(scenario, *mesh);
        // What the file says, every key written out, as a plain dict; and what its selections
        // and regions come to on the mesh, so that a caller never re-implements either.
        py::dict out;
        out["scenario"] = py::module_::import("json").attr("loads")(scenario_to_json(scenario));
        out["mesh_path"] = scenario.mesh_path;
        out["mesh"] = mesh;
        py::list handle_faces;
        for (const Handle& h : resolved.handles) handle_faces.append(h.faces);
        out["handle_faces"] = handle_faces;
        const auto factors = [&](const std::vector<double>& f) {
          return f.empty() ? std::vector<double>(size_t(mesh->n_faces()), 1.0) : f;
        };
        out["height_factors"] = factors(resolved.prisms.face_height_factor);
        out["width_factors"] = factors(resolved.prisms.face_width_factor);
        return out;
      },
      py::arg("path"),
      "Reads and checks a scenario file as primo deform does: a dict with scenario (the file's "
      "keys, all written out), mesh_path, mesh, handle_faces (each handle's faces) and "
      "height_factors and width_factors (per face, from the regions).");
  m.def(
      "save_scenario",
      [](const py::dict& scenario, const std::string& path) {
        const std::string text = py::str(py::module_::import("json").attr("dumps")(scenario));
        // Checked as a file with this name would be, so that what primo deform refuses is
        // never written; the mesh is resolved against the file's folder, as when it is read.
        const Scenario parsed = parse_scenario(text, path);
        write_text_atomically(path, scenario_to_json(parsed));
      },
      py::arg("scenario"), py::arg("path"),
      "Checks a scenario given as a dict with the reader of primo deform and writes it, "
      "atomically; a scenario the reader refuses raises primo.Error and writes nothing.");
  m.def(
      "replay_session",
      [](const std::string& path, const std::string& mesh_path) {
        const Session session = load_session(path);
        const Mesh mesh = load_mesh(mesh_path.empty() ? session.mesh_path : mesh_path);
        ReplayResult result;
        {
          py::gil_scoped_release free_python;
          std::shared_lock<std::shared_mutex> pool(g_thread_pool);
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
