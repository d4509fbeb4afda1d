// Reading and writing session files (docs/sessions.md, "The format"). Reading is strict and
// every error names where it is; writing puts one event per line.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>

#include "primo/util/error.h"
#include "primo/util/utf8.h"
#include "primo/io/input_files.h"
#include "primo/io/json_limits.h"
#include "primo/io/output_files.h"
#include "primo/sessions/session.h"
#include "primo/model/turn.h"

namespace primo {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw Error(where.empty() ? what : where + ": " + what);
}

std::string at(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

void check_object(const json& j, const std::string& path, std::initializer_list<const char*> keys) {
  if (!j.is_object()) fail(path, "expected an object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    for (const char* k : keys) known = known || it.key() == k;
    if (!known) fail(at(path, it.key()), "unknown key");
  }
}

const json& member(const json& j, const std::string& path, const char* key) {
  auto it = j.find(key);
  if (it == j.end()) fail(at(path, key), "missing");
  return *it;
}

double number(const json& j, const std::string& path) {
  if (!j.is_number()) fail(path, "expected a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(path, "expected a finite number");
  if (std::abs(v) > kMaxScenarioMagnitude) fail(path, "must be between -1e15 and 1e15");
  return v;
}

int integer(const json& j, const std::string& path) {
  if (!j.is_number_integer()) fail(path, "expected an integer");
  const auto v = j.get<long long>();
  if (v < -2147483647LL || v > 2147483647LL) fail(path, "integer out of range");
  return int(v);
}

Vec3 vec3(const json& j, const std::string& path) {
  if (!j.is_array() || j.size() != 3) fail(path, "expected an array of 3 numbers");
  return {number(j[0], path + "[0]"), number(j[1], path + "[1]"), number(j[2], path + "[2]")};
}

Eigen::Quaterniond quaternion(const json& j, const std::string& path) {
  if (!j.is_array() || j.size() != 4) fail(path, "expected [w, x, y, z]");
  Eigen::Quaterniond q(number(j[0], path + "[0]"), number(j[1], path + "[1]"),
                       number(j[2], path + "[2]"), number(j[3], path + "[3]"));
  if (std::abs(q.norm() - 1.0) > 1e-6) fail(path, "not a unit quaternion");
  return q;
}

std::vector<int> int_array(const json& j, const std::string& path) {
  if (!j.is_array()) fail(path, "expected an array of integers");
  std::vector<int> out;
  out.reserve(j.size());
  for (size_t i = 0; i < j.size(); ++i)
    out.push_back(integer(j[i], path + "[" + std::to_string(i) + "]"));
  return out;
}

std::vector<double> number_array(const json& j, const std::string& path) {
  if (!j.is_array()) fail(path, "expected an array of numbers");
  std::vector<double> out;
  out.reserve(j.size());
  for (size_t i = 0; i < j.size(); ++i)
    out.push_back(number(j[i], path + "[" + std::to_string(i) + "]"));
  return out;
}

const char* mode_name(SessionHandleMode m) {
  switch (m) {
    case SessionHandleMode::Pose:
      return "pose";
    case SessionHandleMode::Position:
      return "position";
    case SessionHandleMode::Orientation:
      return "orientation";
    case SessionHandleMode::Spring:
      return "spring";
    case SessionHandleMode::Fixed:
      return "fixed";
  }
  return "pose";
}

SessionHandleMode parse_mode(const json& j, const std::string& path) {
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    for (SessionHandleMode m :
         {SessionHandleMode::Pose, SessionHandleMode::Position, SessionHandleMode::Orientation,
          SessionHandleMode::Spring, SessionHandleMode::Fixed})
      if (s == mode_name(m)) return m;
  }
  fail(path, "expected \"pose\", \"position\", \"orientation\", \"spring\" or \"fixed\"");
}

json vec_json(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }
json quat_json(const Eigen::Quaterniond& q) { return json::array({q.w(), q.x(), q.y(), q.z()}); }

// A turn is written only where it is not the rotation's own (beyond half a turn, or turned
// the long way): files without turns read as before, and as written.
bool turn_is_principal(const SessionPose& p) {
  return p.whole_turn() == nearest_turn(p.rotation.toRotationMatrix());
}

json pose_json(const SessionPose& p) {
  json j = {{"translate", vec_json(p.translate)}, {"rotation", quat_json(p.rotation)}};
  if (!turn_is_principal(p)) j["turn"] = vec_json(p.whole_turn());
  return j;
}

// The pose's turn from j["turn"], which must make its rotation. Without one the turn is not
// known (SessionPose::known_turn): a replay continues the turn the handle had, as the
// recording did.
void parse_turn(const json& j, const std::string& path, SessionPose& pose) {
  if (!j.contains("turn")) return;
  pose.turn = vec3(j["turn"], at(path, "turn"));
  if (!turn_makes(pose.turn, pose.rotation.toRotationMatrix()))
    fail(at(path, "turn"), "is not a turn of the rotation beside it (a rotation vector, axis "
                           "times angle in radians, whose rotation is that quaternion)");
}

json handle_json(const SessionHandle& g) {
  json j = {{"name", g.name},           {"mode", mode_name(g.mode)},    {"faces", *g.faces},
            {"stiffness", g.stiffness}, {"center", vec_json(g.center)}, {"color", g.color}};
  j["translate"] = vec_json(g.pose.translate);
  j["rotation"] = quat_json(g.pose.rotation);
  if (!turn_is_principal(g.pose)) j["turn"] = vec_json(g.pose.whole_turn());
  if (g.falloff)
    j["falloff"] = {{"radius", g.falloff->radius},
                    {"faces", g.falloff->faces},
                    {"weights", g.falloff->weights}};
  return j;
}

// The faces' range and whether they are the handle's own need the mesh and the handle:
// apply_event checks them.
std::shared_ptr<const SessionFalloff> parse_falloff(const json& j, const std::string& path) {
  check_object(j, path, {"radius", "faces", "weights"});
  auto f = std::make_shared<SessionFalloff>();
  f->radius = number(member(j, path, "radius"), at(path, "radius"));
  if (f->radius < 0.0) fail(at(path, "radius"), "must not be negative");
  f->faces = int_array(member(j, path, "faces"), at(path, "faces"));
  f->weights = number_array(member(j, path, "weights"), at(path, "weights"));
  if (f->weights.size() != f->faces.size())
    fail(at(path, "weights"), "must have as many entries as faces");
  for (size_t i = 0; i < f->weights.size(); ++i)
    if (!(f->weights[i] > 0.0 && f->weights[i] <= 1.0))
      fail(at(path, "weights") + "[" + std::to_string(i) + "]", "must be in (0, 1]");
  return f;
}

SessionHandle parse_handle(const json& j, const std::string& path) {
  check_object(j, path,
               {"name", "mode", "faces", "stiffness", "center", "color", "translate", "rotation",
                "turn", "falloff"});
  SessionHandle g;
  const json& name = member(j, path, "name");
  if (!name.is_string()) fail(at(path, "name"), "expected a string");
  g.name = name.get<std::string>();
  g.mode = parse_mode(member(j, path, "mode"), at(path, "mode"));
  g.faces = std::make_shared<const std::vector<int>>(
      int_array(member(j, path, "faces"), at(path, "faces")));
  if (j.contains("stiffness")) {
    g.stiffness = number(j["stiffness"], at(path, "stiffness"));
    if (g.stiffness <= 0.0) fail(at(path, "stiffness"), "must be positive");
  }
  g.center = vec3(member(j, path, "center"), at(path, "center"));
  if (j.contains("color")) g.color = integer(j["color"], at(path, "color"));
  if (j.contains("translate")) g.pose.translate = vec3(j["translate"], at(path, "translate"));
  if (j.contains("rotation")) g.pose.rotation = quaternion(j["rotation"], at(path, "rotation"));
  parse_turn(j, path, g.pose);
  if (j.contains("falloff")) g.falloff = parse_falloff(j["falloff"], at(path, "falloff"));
  return g;
}

std::vector<SessionHandle> parse_handles(const json& j, const std::string& path) {
  if (!j.is_array()) fail(path, "expected an array of handles");
  std::vector<SessionHandle> out;
  for (size_t i = 0; i < j.size(); ++i)
    out.push_back(parse_handle(j[i], path + "[" + std::to_string(i) + "]"));
  return out;
}

// The height under the scenario format's key for its unit (docs/scenario-format.md).
const char* height_key(HeightUnit unit) {
  return unit == HeightUnit::Diagonal ? "half_thickness" : "height";
}

json prisms_json(const SessionPrisms& p) {
  return {
      {height_key(p.height_unit), p.height}, {"width", p.width}, {"normal_blend", p.normal_blend}};
}

SessionPrisms parse_prisms(const json& j, const std::string& path) {
  check_object(j, path, {"height", "half_thickness", "width", "normal_blend"});
  SessionPrisms p;
  if (j.contains("height") == j.contains("half_thickness"))
    fail(path, "expected exactly one of \"height\" and \"half_thickness\"");
  p.height_unit = j.contains("height") ? HeightUnit::MeanEdgeLength : HeightUnit::Diagonal;
  const char* key = height_key(p.height_unit);
  p.height = number(member(j, path, key), at(path, key));
  p.width = number(member(j, path, "width"), at(path, "width"));
  p.normal_blend = number(member(j, path, "normal_blend"), at(path, "normal_blend"));
  // The scenario format's ranges, which are also what the editor's sliders can make: height
  // >= 0 (0 a membrane), width > 0, any finite normal_blend (below 0 enhances detail).
  if (p.height < 0.0) fail(at(path, key), "must be >= 0");
  if (p.width <= 0.0) fail(at(path, "width"), "must be positive");
  return p;
}

// Sparse factors: faces whose value is not 1, then the listed ones not yet made into an array
// (a session read and written again without meeting its mesh).
json sparse_factors(const FaceFactors& f, const ListedFactors& listed) {
  json faces = json::array(), values = json::array();
  if (f)
    for (size_t i = 0; i < f->size(); ++i)
      if ((*f)[i] != 1.0) faces.push_back(int(i)), values.push_back((*f)[i]);
  for (size_t i = 0; i < listed.faces.size(); ++i)
    faces.push_back(listed.faces[i]), values.push_back(listed.values[i]);
  return {{"faces", faces}, {"values", values}};
}

void parse_face_values(const json& j, const std::string& path, std::vector<int>& faces,
                       std::vector<double>& values) {
  faces = int_array(member(j, path, "faces"), at(path, "faces"));
  values = number_array(member(j, path, "values"), at(path, "values"));
  if (faces.size() != values.size()) fail(at(path, "values"), "must have as many entries as faces");
  for (size_t i = 0; i < values.size(); ++i)
    if (values[i] <= 0.0) fail(at(path, "values[" + std::to_string(i) + "]"), "must be positive");
}

// The mesh is not known here: the faces stay a list, which initial_state checks against the
// mesh before making it an array (a face of 16,777,215 allocated 134 MB before the check). Far
// beyond any mesh a session may have is an error at once.
ListedFactors listed_factors(std::vector<int> faces, std::vector<double> values,
                             const std::string& path) {
  for (size_t i = 0; i < faces.size(); ++i) {
    const std::string where = path + ".faces[" + std::to_string(i) + "]";
    if (faces[i] < 0) fail(where, "negative face index");
    if (faces[i] >= kMaxSessionFaces)
      fail(where, "face " + std::to_string(faces[i]) +
                      " is beyond the largest mesh a session may have (" +
                      std::to_string(kMaxSessionFaces) + " faces)");
  }
  return {std::move(faces), std::move(values)};
}

const char* layer_name(FactorLayer l) { return l == FactorLayer::Height ? "height" : "width"; }

json event_json(const SessionEvent& e) {
  json j = {{"t", e.t}, {"frame", e.frame}, {"type", event_type_name(e.type)}};
  switch (e.type) {
    case SessionEvent::Type::Handles: {
      json hs = json::array();
      for (const SessionHandle& g : e.handles) hs.push_back(handle_json(g));
      j["handles"] = hs;
      break;
    }
    case SessionEvent::Type::Targets: {
      json ps = json::array();
      for (const SessionTarget& p : e.poses) {
        json pj = pose_json(p.pose);
        pj["handle"] = p.handle;
        ps.push_back(pj);
      }
      j["poses"] = ps;
      break;
    }
    case SessionEvent::Type::Factors:
      j["layer"] = layer_name(e.layer);
      j["faces"] = e.faces;
      j["values"] = e.values;
      break;
    case SessionEvent::Type::Prisms:
      j["prisms"] = prisms_json(e.prisms);
      break;
    case SessionEvent::Type::Undo:
    case SessionEvent::Type::Redo:
      break;
  }
  return j;
}

SessionEvent parse_event(const json& j, SessionEvent::Type type) {
  SessionEvent e;
  e.type = type;
  e.t = number(member(j, "", "t"), "t");
  if (e.t < 0.0) fail("t", "must not be negative");
  e.frame = integer(member(j, "", "frame"), "frame");
  if (e.frame < 0) fail("frame", "must not be negative");
  if (e.frame > kMaxSessionFrame)
    fail("frame", std::to_string(e.frame) + " is beyond the last frame a session may have (" +
                      std::to_string(kMaxSessionFrame) + ", 46 hours at 60 frames a second)");
  switch (type) {
    case SessionEvent::Type::Handles:
      check_object(j, "", {"t", "frame", "type", "handles"});
      e.handles = parse_handles(member(j, "", "handles"), "handles");
      break;
    case SessionEvent::Type::Targets: {
      check_object(j, "", {"t", "frame", "type", "poses"});
      const json& ps = member(j, "", "poses");
      if (!ps.is_array()) fail("poses", "expected an array");
      for (size_t i = 0; i < ps.size(); ++i) {
        const std::string p = "poses[" + std::to_string(i) + "]";
        check_object(ps[i], p, {"handle", "translate", "rotation", "turn"});
        SessionTarget sp;
        sp.handle = integer(member(ps[i], p, "handle"), at(p, "handle"));
        sp.pose.translate = vec3(member(ps[i], p, "translate"), at(p, "translate"));
        sp.pose.rotation = quaternion(member(ps[i], p, "rotation"), at(p, "rotation"));
        parse_turn(ps[i], p, sp.pose);
        e.poses.push_back(sp);
      }
      break;
    }
    case SessionEvent::Type::Factors: {
      check_object(j, "", {"t", "frame", "type", "layer", "faces", "values"});
      const json& l = member(j, "", "layer");
      if (l == "height")
        e.layer = FactorLayer::Height;
      else if (l == "width")
        e.layer = FactorLayer::Width;
      else
        fail("layer", "expected \"height\" or \"width\"");
      parse_face_values(j, "", e.faces, e.values);
      break;
    }
    case SessionEvent::Type::Prisms:
      check_object(j, "", {"t", "frame", "type", "prisms"});
      e.prisms = parse_prisms(member(j, "", "prisms"), "prisms");
      break;
    case SessionEvent::Type::Undo:
    case SessionEvent::Type::Redo:
      check_object(j, "", {"t", "frame", "type"});
      break;
  }
  return e;
}

}  // namespace

Session parse_session(const std::string& text, const std::string& source) {
  const std::string src = source.empty() ? "session" : source;
  // Where the parser is, so that a file cut off mid-timeline names the event it broke in.
  std::string top_key;
  int event_index = -1;
  std::string event_type;
  bool type_next = false;
  auto where_event = [&](int i, const std::string& type) {
    return "events[" + std::to_string(i) + "]" + (type.empty() ? "" : " (" + type + ")");
  };
  check_json_depth(text, src);
  json root;
  try {
    root = json::parse(text, [&](int depth, json::parse_event_t ev, json& parsed) {
      if (ev == json::parse_event_t::key && depth == 1) top_key = parsed.get<std::string>();
      if (top_key == "events" && depth == 2 && ev == json::parse_event_t::object_start)
        ++event_index, event_type.clear();
      if (top_key == "events" && depth == 3) {
        if (ev == json::parse_event_t::key)
          type_next = parsed == "type";
        else if (ev == json::parse_event_t::value && type_next && parsed.is_string())
          event_type = parsed.get<std::string>(), type_next = false;
      }
      return true;
    });
  } catch (const json::parse_error& e) {
    // Line and column of the byte where parsing failed.
    size_t line = 1, col = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i)
      if (text[i] == '\n')
        ++line, col = 1;
      else
        ++col;
    const bool truncated = e.byte >= text.size();
    std::string where =
        top_key == "events" && event_index >= 0 ? where_event(event_index, event_type) + ": " : "";
    throw Error(src + ": " + where +
                (truncated ? "the file ends early (truncated?)" : "malformed JSON") + " at line " +
                std::to_string(line) + ", column " + std::to_string(col));
  } catch (const json::exception& e) {
    // A number too large for a double (1e999) is json's out_of_range.406, without a position.
    std::string what = e.what();
    if (const size_t b = what.find("] ");
        what.rfind("[json.exception.", 0) == 0 && b != std::string::npos)
      what = what.substr(b + 2);
    std::string where =
        top_key == "events" && event_index >= 0 ? where_event(event_index, event_type) + ": " : "";
    throw Error(src + ": " + where + "malformed JSON: " + what);
  }

  Session s;
  s.source = source;
  try {
    check_object(root, "", {"format", "mesh", "solver", "initial", "events"});
    const json& format = member(root, "", "format");
    if (format != kSessionFormat)
      fail("format", std::string("expected \"") + kSessionFormat + "\"");
    const json& mesh = member(root, "", "mesh");
    if (!mesh.is_string() || mesh.get<std::string>().empty()) fail("mesh", "expected a file path");
    s.mesh = mesh.get<std::string>();
    fs::path mp(s.mesh);
    s.mesh_path = mp.is_absolute() || source.empty()
                      ? s.mesh
                      : (fs::path(source).parent_path() / mp).lexically_normal().string();
    if (root.contains("solver")) {
      const json& sj = root["solver"];
      check_object(sj, "solver", {"max_iterations", "tolerance", "method"});
      if (sj.contains("max_iterations")) {
        s.solver.max_iterations = integer(sj["max_iterations"], "solver.max_iterations");
        if (s.solver.max_iterations < 1) fail("solver.max_iterations", "must be at least 1");
      }
      if (sj.contains("tolerance")) {
        s.solver.tolerance = number(sj["tolerance"], "solver.tolerance");
        if (s.solver.tolerance < 0.0) fail("solver.tolerance", "must not be negative");
      }
      if (sj.contains("method")) {
        const json& m = sj["method"];
        if (m == "default")
          s.solver.method = SolverMethod::Default;
        else if (m == "global")
          s.solver.method = SolverMethod::Global;
        else if (m == "local")
          s.solver.method = SolverMethod::Local;
        else if (m == "hierarchical")
          s.solver.method = SolverMethod::Hierarchical;
        else
          fail("solver.method", "expected \"default\", \"global\", \"local\" or \"hierarchical\"");
      }
    }
    const json& init = member(root, "", "initial");
    check_object(init, "initial", {"prisms", "handles", "height_factors", "width_factors"});
    s.initial.prisms = parse_prisms(member(init, "initial", "prisms"), "initial.prisms");
    s.initial.handles = parse_handles(member(init, "initial", "handles"), "initial.handles");
    for (const char* layer : {"height_factors", "width_factors"}) {
      if (!init.contains(layer)) continue;
      const std::string p = std::string("initial.") + layer;
      check_object(init[layer], p, {"faces", "values"});
      std::vector<int> faces;
      std::vector<double> values;
      parse_face_values(init[layer], p, faces, values);
      (layer[0] == 'h' ? s.initial.listed_height : s.initial.listed_width) =
          listed_factors(std::move(faces), std::move(values), p);
    }
  } catch (const Error& e) {
    throw Error(src + ": " + e.what());
  }

  const json* events = nullptr;
  try {
    events = &member(root, "", "events");
    if (!events->is_array()) fail("events", "expected an array");
  } catch (const Error& e) {
    throw Error(src + ": " + e.what());
  }
  double last_t = 0.0;
  int last_frame = 0;
  for (size_t i = 0; i < events->size(); ++i) {
    const json& ej = (*events)[i];
    std::string type;
    if (ej.is_object() && ej.contains("type") && ej["type"].is_string())
      type = ej["type"].get<std::string>();
    const std::string where = src + ": " + where_event(int(i), type) + ": ";
    if (!ej.is_object()) throw Error(where + "expected an object");
    if (type.empty()) throw Error(where + "type: missing or not a string");
    SessionEvent::Type t{};
    bool known = false;
    for (auto candidate :
         {SessionEvent::Type::Handles, SessionEvent::Type::Targets, SessionEvent::Type::Factors,
          SessionEvent::Type::Prisms, SessionEvent::Type::Undo, SessionEvent::Type::Redo})
      if (type == event_type_name(candidate)) t = candidate, known = true;
    if (!known)
      throw Error(where +
                  "type: unknown event type (expected handles, targets, factors, prisms, "
                  "undo or redo)");
    try {
      SessionEvent e = parse_event(ej, t);
      if (e.t < last_t) fail("t", "goes back in time");
      if (e.frame < last_frame) fail("frame", "goes back");
      last_t = e.t, last_frame = e.frame;
      s.events.push_back(std::move(e));
    } catch (const Error& e) {
      throw Error(where + e.what());
    }
  }
  return s;
}

Session load_session(const std::string& path) { return parse_session(read_input_file(path), path); }

std::string session_to_json(const Session& s, const std::string& session_path) {
  std::string mesh = s.mesh_path.empty() ? s.mesh : s.mesh_path;
  if (!session_path.empty() && !mesh.empty()) {
    std::error_code ec;
    const fs::path folder =
        fs::absolute(fs::path(session_path), ec).lexically_normal().parent_path();
    const fs::path rel =
        fs::absolute(fs::path(mesh), ec).lexically_normal().lexically_relative(folder);
    if (!ec && !rel.empty()) mesh = rel.generic_string();
  }
  const char* method = "default";
  switch (s.solver.method) {
    case SolverMethod::Global:
      method = "global";
      break;
    case SolverMethod::Local:
      method = "local";
      break;
    case SolverMethod::Hierarchical:
      method = "hierarchical";
      break;
    case SolverMethod::Default:
      break;
  }
  json handles = json::array();
  for (const SessionHandle& g : s.initial.handles) handles.push_back(handle_json(g));
  const json initial = {
      {"prisms", prisms_json(s.initial.prisms)},
      {"handles", handles},
      {"height_factors", sparse_factors(s.initial.height_factor, s.initial.listed_height)},
      {"width_factors", sparse_factors(s.initial.width_factor, s.initial.listed_width)}};
  const json solver = {{"max_iterations", s.solver.max_iterations},
                       {"tolerance", s.solver.tolerance},
                       {"method", method}};
  // A JSON string holds text: a file name of other bytes cannot be written.
  if (!is_valid_utf8(mesh))
    throw Error("cannot write the session: the mesh's file name \"" + escape_invalid_utf8(mesh) +
                "\" is not UTF-8 (%XX marks each such byte), and a session's JSON holds only "
                "text; rename the mesh file");
  // One event per line: diffable, and a truncated file still shows where it ends.
  try {
    std::string out = "{\n  \"format\": \"" + std::string(kSessionFormat) + "\",\n";
    out += "  \"mesh\": " + json(mesh).dump() + ",\n";
    out += "  \"solver\": " + solver.dump() + ",\n";
    out += "  \"initial\": " + initial.dump() + ",\n";
    out += "  \"events\": [";
    for (size_t i = 0; i < s.events.size(); ++i)
      out += (i ? ",\n    " : "\n    ") + event_json(s.events[i]).dump();
    out += s.events.empty() ? "]\n}\n" : "\n  ]\n}\n";
    return out;
  } catch (const json::type_error& e) {
    throw Error(std::string("cannot write the session: a name in it is not UTF-8 text (") +
                e.what() + ")");
  }
}

void save_session(const Session& session, const std::string& path) {
  write_text_atomically(path, session_to_json(session, path));
}

}  // namespace primo
