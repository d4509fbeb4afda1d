// Reading and writing scenario files (docs/scenario-format.md). The reader is strict: every
// problem becomes one Error line "<source>: <json path>: <problem>", so that a typo in a
// scenario never silently changes what gets solved.

#include "primo/scenario/scenario.h"

#include <Eigen/Geometry>
#include <climits>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "primo/util/error.h"
#include "primo/util/utf8.h"
#include "primo/io/input_files.h"
#include "primo/io/json_limits.h"

namespace primo {
namespace {

// ordered_json keeps the file's key order, so "the first unknown key" is the first one a
// reader sees, and written files list keys in the order the format documents them.
using Json = nlohmann::ordered_json;

constexpr const char* kFormat = "primo-scenario/1";

std::string source_label(const std::string& source) {
  return source.empty() ? "(text)" : source;
}

std::string child_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string element_path(const std::string& parent, size_t index) {
  return (parent.empty() ? "(root)" : parent) + "[" + std::to_string(index) + "]";
}

std::string shown_path(const std::string& path) { return path.empty() ? "(root)" : path; }

// 1-based line and column of the 0-based `offset` in `text`.
std::string line_and_column(const std::string& text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1;
  size_t line_start = 0;
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(offset - line_start + 1);
}

// nlohmann's what() starts with "[json.exception.parse_error.101] parse error at line 3,
// column 0: ". Its column is unreliable after a lookahead character is put back, so we keep
// only the description and compute the position from the byte offset ourselves.
std::string parse_error_detail(const std::string& what) {
  std::string detail = what;
  const size_t bracket = detail.find("] ");
  if (detail.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos)
    detail = detail.substr(bracket + 2);
  const size_t column = detail.find("column ");
  if (detail.rfind("parse error", 0) == 0 && column != std::string::npos) {
    const size_t colon = detail.find(": ", column);
    if (colon != std::string::npos) detail = detail.substr(colon + 2);
  }
  return detail;
}

// Parses JSON text, reporting malformed input and duplicate keys with a position. nlohmann
// keeps the last of duplicate keys; the format forbids silently ignored keys, so a duplicate
// (whose first value would be ignored) is an error too.
Json parse_json_text(const std::string& text, const std::string& label) {
  struct Container {
    bool is_array = false;
    std::string path;
    size_t next_index = 0;
    std::string last_key;
    std::set<std::string> keys;
  };
  std::vector<Container> open;
  std::string duplicate_key_path;

  auto current_element_path = [&]() -> std::string {
    if (open.empty()) return "";
    const Container& top = open.back();
    return top.is_array ? element_path(top.path, top.next_index)
                        : child_path(top.path, top.last_key);
  };
  auto element_done = [&]() {
    if (!open.empty() && open.back().is_array) ++open.back().next_index;
  };

  Json::parser_callback_t track = [&](int, nlohmann::detail::parse_event_t event,
                                      Json& parsed) {
    using Event = nlohmann::detail::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start: {
        Container container;
        container.is_array = event == Event::array_start;
        container.path = current_element_path();
        open.push_back(std::move(container));
        break;
      }
      case Event::key: {
        Container& top = open.back();
        top.last_key = parsed.get<std::string>();
        if (!top.keys.insert(top.last_key).second && duplicate_key_path.empty())
          duplicate_key_path = child_path(top.path, top.last_key);
        break;
      }
      case Event::object_end:
      case Event::array_end:
        open.pop_back();
        element_done();
        break;
      case Event::value:
        element_done();
        break;
    }
    return true;
  };

  check_json_depth(text, label);
  Json root;
  try {
    root = Json::parse(text, track, /*allow_exceptions=*/true, /*ignore_comments=*/false);
  } catch (const Json::parse_error& e) {
    // e.byte is the 1-based position of the last character read.
    const size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    throw Error(label + ": (root): malformed JSON at " + line_and_column(text, offset) + ": " +
                parse_error_detail(e.what()));
  } catch (const Json::exception& e) {
    // Number overflow (e.g. 1e999) comes without a position; find the quoted literal.
    std::string position;
    const std::string what = e.what();
    const size_t open_quote = what.find('\'');
    const size_t close_quote = what.rfind('\'');
    if (open_quote != std::string::npos && close_quote > open_quote) {
      const size_t at = text.find(what.substr(open_quote + 1, close_quote - open_quote - 1));
      if (at != std::string::npos) position = " at " + line_and_column(text, at);
    }
    throw Error(label + ": (root): malformed JSON" + position + ": " +
                parse_error_detail(what));
  }
  if (!duplicate_key_path.empty())
    throw Error(label + ": " + duplicate_key_path + ": duplicate key");
  return root;
}

// Validating accessors. `path` is always the JSON path of the value being read.
class ScenarioReader {
 public:
  explicit ScenarioReader(std::string label) : label_(std::move(label)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw Error(label_ + ": " + shown_path(path) + ": " + problem);
  }

  void expect_object(const Json& value, const std::string& path) const {
    if (!value.is_object()) fail(path, "expected an object");
  }

  void expect_array(const Json& value, const std::string& path) const {
    if (!value.is_array()) fail(path, "expected an array");
  }

  // Rejects keys outside `allowed`, naming the first one in file order.
  void expect_only_keys(const Json& object, const std::string& path,
                        std::initializer_list<const char*> allowed) const {
    for (const auto& item : object.items()) {
      bool known = false;
      for (const char* key : allowed) known = known || item.key() == key;
      if (!known) fail(child_path(path, item.key()), "unknown key");
    }
  }

  const Json& required(const Json& object, const std::string& path, const char* key) const {
    const auto it = object.find(key);
    if (it == object.end()) fail(child_path(path, key), "missing required key");
    return *it;
  }

  const Json* optional(const Json& object, const char* key) const {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  std::string string(const Json& value, const std::string& path) const {
    if (!value.is_string()) fail(path, "expected a string");
    return value.get<std::string>();
  }

  double number(const Json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, "expected a number");
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(path, "expected a finite number");
    // A stiffness, height or translation of 1e308 is finite but overflows the energy: the
    // solve would "converge" at once without solving (docs/scenario-format.md, "Ranges").
    if (std::abs(x) > kMaxScenarioMagnitude)
      fail(path, "must be between -1e15 and 1e15, got " + format_number(x));
    return x;
  }

  double number_at_least(const Json& value, const std::string& path, double lowest) const {
    const double x = number(value, path);
    if (x < lowest) fail(path, "must be >= " + format_number(lowest) + ", got " + format_number(x));
    return x;
  }

  double positive_number(const Json& value, const std::string& path) const {
    const double x = number(value, path);
    if (!(x > 0.0)) fail(path, "must be > 0, got " + format_number(x));
    return x;
  }

  // JSON does not distinguish 10 from 10.0, so an integral float is accepted; 10.5 is not.
  int non_negative_integer(const Json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, "expected a non-negative integer");
    if (value.is_number_unsigned()) {
      const auto u = value.get<std::uint64_t>();
      if (u > std::uint64_t(INT_MAX)) fail(path, "integer too large: " + std::to_string(u));
      return int(u);
    }
    if (value.is_number_integer()) {
      const auto i = value.get<std::int64_t>();
      if (i < 0) fail(path, "must be >= 0, got " + std::to_string(i));
      if (i > INT_MAX) fail(path, "integer too large: " + std::to_string(i));
      return int(i);
    }
    const double x = value.get<double>();
    if (!std::isfinite(x) || std::floor(x) != x)
      fail(path, "expected a non-negative integer, got " + format_number(x));
    if (x < 0) fail(path, "must be >= 0, got " + format_number(x));
    if (x > double(INT_MAX)) fail(path, "integer too large: " + format_number(x));
    return int(x);
  }

  Vec3 vec3(const Json& value, const std::string& path) const {
    if (!value.is_array() || value.size() != 3) fail(path, "expected an array of 3 numbers");
    Vec3 v;
    for (size_t k = 0; k < 3; ++k) v[int(k)] = number(value[k], element_path(path, k));
    return v;
  }

  std::vector<int> index_list(const Json& value, const std::string& path) const {
    expect_array(value, path);
    std::vector<int> indices;
    indices.reserve(value.size());
    for (size_t k = 0; k < value.size(); ++k)
      indices.push_back(non_negative_integer(value[k], element_path(path, k)));
    return indices;
  }

  Selection selection(const Json& value, const std::string& path) const {
    expect_object(value, path);
    expect_only_keys(value, path, {"faces", "vertices", "box", "sphere", "all"});
    if (value.size() != 1) {
      std::string present;
      for (const auto& item : value.items())
        present += (present.empty() ? "" : ", ") + std::string("'") + item.key() + "'";
      fail(path, "expected exactly one of faces, vertices, box, sphere, all" +
                     (present.empty() ? std::string(", got none") : ", got " + present));
    }
    const std::string kind = value.begin().key();
    const Json& body = value.begin().value();
    Selection s;
    const std::string body_path = child_path(path, kind);
    if (kind == "faces") {
      s.kind = Selection::Kind::Faces;
      s.indices = index_list(body, body_path);
    } else if (kind == "vertices") {
      s.kind = Selection::Kind::Vertices;
      s.indices = index_list(body, body_path);
    } else if (kind == "box") {
      s.kind = Selection::Kind::Box;
      expect_object(body, body_path);
      expect_only_keys(body, body_path, {"min", "max"});
      s.min = vec3(required(body, body_path, "min"), child_path(body_path, "min"));
      s.max = vec3(required(body, body_path, "max"), child_path(body_path, "max"));
      for (int k = 0; k < 3; ++k) {
        if (s.min[k] > s.max[k])
          fail(body_path, std::string("min > max in ") + "xyz"[k] + " (" +
                              format_number(s.min[k]) + " > " + format_number(s.max[k]) + ")");
      }
    } else if (kind == "sphere") {
      s.kind = Selection::Kind::Sphere;
      expect_object(body, body_path);
      expect_only_keys(body, body_path, {"center", "radius"});
      s.center = vec3(required(body, body_path, "center"), child_path(body_path, "center"));
      s.radius = number_at_least(required(body, body_path, "radius"),
                                 child_path(body_path, "radius"), 0.0);
    } else {
      s.kind = Selection::Kind::All;
      if (!body.is_boolean() || !body.get<bool>()) fail(body_path, "expected true");
    }
    return s;
  }

  static std::string format_number(double x) {
    std::ostringstream out;
    out.precision(17);
    out << x;
    return out.str();
  }

 private:
  std::string label_;
};

void read_prisms(const ScenarioReader& in, const Json& value, PrismParameters& prisms) {
  const std::string path = "prisms";
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"height", "half_thickness", "normal_blend", "width"});
  const Json* height = in.optional(value, "height");
  const Json* half_thickness = in.optional(value, "half_thickness");
  if (height && half_thickness)
    in.fail("prisms", "sets both height and half_thickness; give one (half_thickness is the "
                      "resolution-independent form)");
  if (height) {
    prisms.height = in.number_at_least(*height, "prisms.height", 0.0);  // 0: a flat membrane
    prisms.height_unit = HeightUnit::MeanEdgeLength;
  }
  if (half_thickness) {
    prisms.height = in.number_at_least(*half_thickness, "prisms.half_thickness", 0.0);
    prisms.height_unit = HeightUnit::Diagonal;
  }
  if (const Json* v = in.optional(value, "normal_blend"))
    prisms.normal_blend = in.number(*v, "prisms.normal_blend");
  if (const Json* v = in.optional(value, "width"))
    prisms.width = in.positive_number(*v, "prisms.width");
}

std::string optional_name(const ScenarioReader& in, const Json& object,
                          const std::string& path) {
  const Json* v = in.optional(object, "name");
  return v ? in.string(*v, child_path(path, "name")) : std::string();
}

RegionSpec read_region(const ScenarioReader& in, const Json& value, const std::string& path) {
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"name", "select", "height", "width"});
  RegionSpec region;
  region.where = path;
  region.name = optional_name(in, value, path);
  region.select = in.selection(in.required(value, path, "select"), child_path(path, "select"));
  if (const Json* v = in.optional(value, "height"))
    region.height = in.number_at_least(*v, child_path(path, "height"), 0.0);
  if (const Json* v = in.optional(value, "width"))
    region.width = in.positive_number(*v, child_path(path, "width"));
  return region;
}

Fix read_fix(const ScenarioReader& in, const Json& value, const std::string& path) {
  const std::string fix = in.string(value, path);
  if (const std::optional<Fix> f = fix_from_name(fix)) return *f;
  in.fail(path, "expected \"all\", \"position\" or \"orientation\", got \"" + fix + "\"");
}

TransformSpec read_transform(const ScenarioReader& in, const Json& value,
                             const std::string& path) {
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"translate", "axis", "angle_deg", "center"});
  TransformSpec t;
  if (const Json* v = in.optional(value, "translate"))
    t.translate = in.vec3(*v, child_path(path, "translate"));
  const Json* axis = in.optional(value, "axis");
  if (axis) t.axis = in.vec3(*axis, child_path(path, "axis"));
  if (const Json* v = in.optional(value, "angle_deg"))
    t.angle_deg = in.number(*v, child_path(path, "angle_deg"));
  if (const Json* v = in.optional(value, "center"))
    t.center = in.vec3(*v, child_path(path, "center"));
  if (t.angle_deg != 0.0) {
    if (!axis) in.fail(child_path(path, "axis"), "required when angle_deg is not 0");
    if (!(t.axis.norm() > 0.0))
      in.fail(child_path(path, "axis"), "must be non-zero when angle_deg is not 0");
  }
  return t;
}

HandleSpec read_handle(const ScenarioReader& in, const Json& value, const std::string& path) {
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"name", "select", "fix", "transform"});
  HandleSpec handle;
  handle.where = path;
  handle.name = optional_name(in, value, path);
  handle.select = in.selection(in.required(value, path, "select"), child_path(path, "select"));
  handle.fix = read_fix(in, in.required(value, path, "fix"), child_path(path, "fix"));
  if (const Json* v = in.optional(value, "transform"))
    handle.transform = read_transform(in, *v, child_path(path, "transform"));
  return handle;
}

ForceSpec read_force(const ScenarioReader& in, const Json& value, const std::string& path) {
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"name", "select", "target_offset", "stiffness"});
  ForceSpec force;
  force.where = path;
  force.name = optional_name(in, value, path);
  force.select = in.selection(in.required(value, path, "select"), child_path(path, "select"));
  force.target_offset = in.vec3(in.required(value, path, "target_offset"),
                                child_path(path, "target_offset"));
  force.stiffness = in.number_at_least(in.required(value, path, "stiffness"),
                                       child_path(path, "stiffness"), 0.0);
  return force;
}

void read_solver(const ScenarioReader& in, const Json& value, SolverSpec& solver) {
  const std::string path = "solver";
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"max_iterations", "tolerance", "method"});
  if (const Json* v = in.optional(value, "max_iterations"))
    solver.max_iterations = in.non_negative_integer(*v, "solver.max_iterations");
  if (const Json* v = in.optional(value, "tolerance"))
    solver.tolerance = in.number_at_least(*v, "solver.tolerance", 0.0);
  if (const Json* v = in.optional(value, "method")) {
    const std::string method = in.string(*v, "solver.method");
    if (method == "global")
      solver.method = SolverMethod::Global;
    else if (method == "local")
      solver.method = SolverMethod::Local;
    else if (method == "hierarchical")
      solver.method = SolverMethod::Hierarchical;
    else
      in.fail("solver.method",
              "expected \"global\", \"local\" or \"hierarchical\", got \"" + method + "\"");
  }
}

// [w, x, y, z, tx, ty, tz] per face: a unit quaternion (checked to 1e-6, then normalized, so
// values rounded by another writer still load) and a translation.
SolvedStateSpec read_solved_state(const ScenarioReader& in, const Json& value) {
  const std::string path = "solved_state";
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"face_motions"});
  const std::string list_path = child_path(path, "face_motions");
  const Json& list = in.required(value, path, "face_motions");
  in.expect_array(list, list_path);
  SolvedStateSpec state;
  state.face_motions.reserve(list.size());
  for (size_t f = 0; f < list.size(); ++f) {
    const std::string at = element_path(list_path, f);
    const Json& m = list[f];
    if (!m.is_array() || m.size() != 7)
      in.fail(at, "expected [w, x, y, z, tx, ty, tz]: a unit quaternion and a translation");
    double v[7];
    for (size_t k = 0; k < 7; ++k) v[k] = in.number(m[k], element_path(at, k));
    Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
    if (std::abs(q.norm() - 1.0) > 1e-6)
      in.fail(at, "not a unit quaternion (norm " + ScenarioReader::format_number(q.norm()) + ")");
    q.normalize();
    RigidTransform t;
    t.rotation = q.toRotationMatrix();
    t.translation = Vec3(v[4], v[5], v[6]);
    state.face_motions.push_back(t);
  }
  return state;
}

MirrorPairSpec read_mirror_pair(const ScenarioReader& in, const Json& value,
                                const std::string& path, size_t n_handles, size_t n_forces) {
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"handles", "forces", "axis"});
  const Json* handles = in.optional(value, "handles");
  const Json* forces = in.optional(value, "forces");
  if ((handles != nullptr) == (forces != nullptr))
    in.fail(path, "expected exactly one of 'handles' and 'forces'");
  MirrorPairSpec pair;
  pair.forces = forces != nullptr;
  const char* key = pair.forces ? "forces" : "handles";
  const std::string at = child_path(path, key);
  const std::vector<int> indices = in.index_list(pair.forces ? *forces : *handles, at);
  if (indices.size() != 2) in.fail(at, "expected two indices");
  const size_t n = pair.forces ? n_forces : n_handles;
  for (size_t k = 0; k < 2; ++k)
    if (size_t(indices[k]) >= n)
      in.fail(element_path(at, k), "no " + std::string(pair.forces ? "force " : "handle ") +
                                       std::to_string(indices[k]) + " (there are " +
                                       std::to_string(n) + ")");
  if (indices[0] == indices[1]) in.fail(at, "a handle cannot be its own mirror twin");
  pair.first = indices[0], pair.second = indices[1];
  const std::string axis = in.string(in.required(value, path, "axis"), child_path(path, "axis"));
  if (axis != "x" && axis != "y" && axis != "z")
    in.fail(child_path(path, "axis"), "expected \"x\", \"y\" or \"z\", got \"" + axis + "\"");
  pair.axis = axis[0] - 'x';
  return pair;
}

SignedAxis read_signed_axis(const ScenarioReader& in, const Json& value, const std::string& path) {
  const std::string name = in.string(value, path);
  for (int axis = 0; axis < 3; ++axis)
    for (const int sign : {1, -1})
      if (name == signed_axis_name({axis, sign})) return {axis, sign};
  in.fail(path, "expected \"+x\", \"-x\", \"+y\", \"-y\", \"+z\" or \"-z\", got \"" + name + "\"");
}

ModelOrientation read_orientation(const ScenarioReader& in, const Json& value,
                                  const std::string& path) {
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"up", "front"});
  ModelOrientation o;
  o.up = read_signed_axis(in, in.required(value, path, "up"), child_path(path, "up"));
  o.front = read_signed_axis(in, in.required(value, path, "front"), child_path(path, "front"));
  if (o.up.axis == o.front.axis)
    in.fail(child_path(path, "front"), "must be perpendicular to up (" + signed_axis_name(o.up) +
                                           "), got " + signed_axis_name(o.front));
  return o;
}

EditorSpec read_editor(const ScenarioReader& in, const Json& value, size_t n_handles,
                       size_t n_forces) {
  const std::string path = "editor";
  in.expect_object(value, path);
  in.expect_only_keys(value, path, {"fixed_regions", "mirror_pairs", "orientation"});
  EditorSpec editor;
  if (const Json* v = in.optional(value, "fixed_regions")) {
    const std::string at = child_path(path, "fixed_regions");
    editor.fixed_regions = in.index_list(*v, at);
    for (size_t k = 0; k < editor.fixed_regions.size(); ++k)
      if (size_t(editor.fixed_regions[k]) >= n_handles)
        in.fail(element_path(at, k), "no handle " + std::to_string(editor.fixed_regions[k]) +
                                         " (there are " + std::to_string(n_handles) + ")");
  }
  if (const Json* v = in.optional(value, "mirror_pairs")) {
    const std::string at = child_path(path, "mirror_pairs");
    in.expect_array(*v, at);
    std::vector<char> paired_handle(n_handles, 0), paired_force(n_forces, 0);
    for (size_t k = 0; k < v->size(); ++k) {
      const MirrorPairSpec pair =
          read_mirror_pair(in, (*v)[k], element_path(at, k), n_handles, n_forces);
      std::vector<char>& paired = pair.forces ? paired_force : paired_handle;
      for (const int i : {pair.first, pair.second}) {
        if (paired[size_t(i)])
          in.fail(element_path(at, k), std::string(pair.forces ? "force " : "handle ") +
                                           std::to_string(i) + " is in two mirror pairs");
        paired[size_t(i)] = 1;
      }
      editor.mirror_pairs.push_back(pair);
    }
  }
  if (const Json* v = in.optional(value, "orientation"))
    editor.orientation = read_orientation(in, *v, child_path(path, "orientation"));
  return editor;
}

template <typename Spec, typename ReadOne>
std::vector<Spec> read_list(const ScenarioReader& in, const Json& root, const char* key,
                            ReadOne read_one) {
  std::vector<Spec> specs;
  const Json* list = in.optional(root, key);
  if (!list) return specs;
  in.expect_array(*list, key);
  for (size_t i = 0; i < list->size(); ++i)
    specs.push_back(read_one(in, (*list)[i], element_path(key, i)));
  return specs;
}

std::string resolve_mesh_path(const std::string& mesh, const std::string& source) {
  namespace fs = std::filesystem;
  const fs::path mesh_path(mesh);
  if (mesh_path.is_absolute() || source.empty()) return mesh_path.string();
  return (fs::path(source).parent_path() / mesh_path).string();
}

// --- writing ---------------------------------------------------------------------------

// A non-finite number would be written as null and fail to load again; refuse it here.
double finite(double x, const std::string& path) {
  if (!std::isfinite(x))
    throw Error("scenario_to_json: " + path + ": cannot write a non-finite number");
  return x;
}

Json vec3_json(const Vec3& v, const std::string& path) {
  return Json::array({finite(v.x(), path), finite(v.y(), path), finite(v.z(), path)});
}

Json selection_json(const Selection& s, const std::string& path) {
  Json out = Json::object();
  switch (s.kind) {
    case Selection::Kind::Faces:
      out["faces"] = s.indices;
      break;
    case Selection::Kind::Vertices:
      out["vertices"] = s.indices;
      break;
    case Selection::Kind::Box:
      out["box"] = Json{{"min", vec3_json(s.min, path + ".box.min")},
                        {"max", vec3_json(s.max, path + ".box.max")}};
      break;
    case Selection::Kind::Sphere:
      out["sphere"] = Json{{"center", vec3_json(s.center, path + ".sphere.center")},
                           {"radius", finite(s.radius, path + ".sphere.radius")}};
      break;
    case Selection::Kind::All:
      out["all"] = true;
      break;
  }
  return out;
}

}  // namespace

Scenario parse_scenario(const std::string& json_text, const std::string& source) {
  const std::string label = source_label(source);
  const Json root = parse_json_text(json_text, label);
  const ScenarioReader in(label);

  in.expect_object(root, "");
  in.expect_only_keys(root, "",
                      {"format", "mesh", "prisms", "regions", "handles", "forces", "solver",
                       "solved_state", "editor"});

  const std::string format = in.string(in.required(root, "", "format"), "format");
  if (format != kFormat)
    in.fail("format", "expected \"" + std::string(kFormat) + "\", got \"" + format + "\"");

  Scenario scenario;
  scenario.source = source;
  scenario.mesh = in.string(in.required(root, "", "mesh"), "mesh");
  if (scenario.mesh.empty()) in.fail("mesh", "must not be empty");
  scenario.mesh_path = resolve_mesh_path(scenario.mesh, source);

  if (const Json* v = in.optional(root, "prisms")) read_prisms(in, *v, scenario.prisms);
  scenario.regions = read_list<RegionSpec>(in, root, "regions", read_region);
  scenario.handles = read_list<HandleSpec>(in, root, "handles", read_handle);
  scenario.forces = read_list<ForceSpec>(in, root, "forces", read_force);
  if (const Json* v = in.optional(root, "solver")) read_solver(in, *v, scenario.solver);
  if (const Json* v = in.optional(root, "solved_state"))
    scenario.solved_state = read_solved_state(in, *v);
  if (const Json* v = in.optional(root, "editor"))
    scenario.editor = read_editor(in, *v, scenario.handles.size(), scenario.forces.size());
  return scenario;
}

ModelOrientation parse_model_orientation(const std::string& json_text, const std::string& source) {
  const std::string label = source_label(source);
  return read_orientation(ScenarioReader(label), parse_json_text(json_text, label), "");
}

std::string signed_axis_name(const SignedAxis& axis) {
  return std::string(axis.sign < 0 ? "-" : "+") + char('x' + axis.axis);
}

Scenario load_scenario(const std::string& path) {
  return parse_scenario(read_input_file(path), path);
}

std::string scenario_to_json(const Scenario& scenario) {
  Json root = Json::object();
  root["format"] = kFormat;
  // A JSON string holds text: a file name of other bytes cannot be written as the format
  // stands (a rename is the way out; the autosave refers to such a mesh through a link).
  if (!is_valid_utf8(scenario.mesh))
    throw Error("cannot write the scenario: the mesh's file name \"" +
                escape_invalid_utf8(scenario.mesh) +
                "\" is not UTF-8 (%XX marks each such byte), and a scenario's JSON holds only "
                "text; rename the mesh file");
  root["mesh"] = scenario.mesh;
  const PrismParameters& prisms = scenario.prisms;
  const bool diagonal = prisms.height_unit == HeightUnit::Diagonal;
  const char* height_key = diagonal ? "half_thickness" : "height";
  root["prisms"] = Json{{height_key, finite(prisms.height, std::string("prisms.") + height_key)},
                        {"normal_blend", finite(prisms.normal_blend, "prisms.normal_blend")},
                        {"width", finite(prisms.width, "prisms.width")}};

  root["regions"] = Json::array();
  for (size_t i = 0; i < scenario.regions.size(); ++i) {
    const RegionSpec& r = scenario.regions[i];
    const std::string path = element_path("regions", i);
    Json region = Json::object();
    if (!r.name.empty()) region["name"] = r.name;
    region["select"] = selection_json(r.select, path + ".select");
    if (r.height) region["height"] = finite(*r.height, path + ".height");
    if (r.width) region["width"] = finite(*r.width, path + ".width");
    root["regions"].push_back(std::move(region));
  }

  root["handles"] = Json::array();
  for (size_t i = 0; i < scenario.handles.size(); ++i) {
    const HandleSpec& h = scenario.handles[i];
    const std::string path = element_path("handles", i);
    Json handle = Json::object();
    if (!h.name.empty()) handle["name"] = h.name;
    handle["select"] = selection_json(h.select, path + ".select");
    handle["fix"] = fix_name(h.fix);
    Json transform = Json::object();
    transform["translate"] = vec3_json(h.transform.translate, path + ".transform.translate");
    transform["axis"] = vec3_json(h.transform.axis, path + ".transform.axis");
    transform["angle_deg"] = finite(h.transform.angle_deg, path + ".transform.angle_deg");
    if (h.transform.center)
      transform["center"] = vec3_json(*h.transform.center, path + ".transform.center");
    handle["transform"] = std::move(transform);
    root["handles"].push_back(std::move(handle));
  }

  root["forces"] = Json::array();
  for (size_t i = 0; i < scenario.forces.size(); ++i) {
    const ForceSpec& f = scenario.forces[i];
    const std::string path = element_path("forces", i);
    Json force = Json::object();
    if (!f.name.empty()) force["name"] = f.name;
    force["select"] = selection_json(f.select, path + ".select");
    force["target_offset"] = vec3_json(f.target_offset, path + ".target_offset");
    force["stiffness"] = finite(f.stiffness, path + ".stiffness");
    root["forces"].push_back(std::move(force));
  }

  Json solver = Json::object();
  solver["max_iterations"] = scenario.solver.max_iterations;
  solver["tolerance"] = finite(scenario.solver.tolerance, "solver.tolerance");
  // "Default" (the best available method) is expressed by leaving the key out.
  if (scenario.solver.method == SolverMethod::Global) solver["method"] = "global";
  if (scenario.solver.method == SolverMethod::Local) solver["method"] = "local";
  if (scenario.solver.method == SolverMethod::Hierarchical) solver["method"] = "hierarchical";
  root["solver"] = std::move(solver);

  if (scenario.solved_state) {
    Json motions = Json::array();
    const auto& list = scenario.solved_state->face_motions;
    for (size_t f = 0; f < list.size(); ++f) {
      const std::string path = "solved_state.face_motions[" + std::to_string(f) + "]";
      const Eigen::Quaterniond q(list[f].rotation);
      const Vec3& t = list[f].translation;
      motions.push_back(Json{finite(q.w(), path), finite(q.x(), path), finite(q.y(), path),
                             finite(q.z(), path), finite(t.x(), path), finite(t.y(), path),
                             finite(t.z(), path)});
    }
    root["solved_state"] = Json{{"face_motions", std::move(motions)}};
  }
  if (scenario.editor) {
    Json editor = Json::object();
    if (!scenario.editor->fixed_regions.empty())
      editor["fixed_regions"] = scenario.editor->fixed_regions;
    if (!scenario.editor->mirror_pairs.empty()) {
      Json pairs = Json::array();
      for (const MirrorPairSpec& p : scenario.editor->mirror_pairs)
        pairs.push_back(Json{{p.forces ? "forces" : "handles", {p.first, p.second}},
                             {"axis", std::string(1, char('x' + p.axis))}});
      editor["mirror_pairs"] = std::move(pairs);
    }
    if (const auto& o = scenario.editor->orientation)
      editor["orientation"] = Json{{"up", signed_axis_name(o->up)},
                                   {"front", signed_axis_name(o->front)}};
    root["editor"] = std::move(editor);
  }

  // Names typed in the editor are UTF-8; anything else is refused here, not half written.
  try {
    return root.dump(2) + "\n";
  } catch (const Json::type_error& e) {
    throw Error(std::string("cannot write the scenario: a name in it is not UTF-8 text (") +
                e.what() + ")");
  }
}

}  // namespace primo
