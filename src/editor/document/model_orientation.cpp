#include "model_orientation.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "primo/util/error.h"
#include "primo/io/input_files.h"

namespace primo::editor {
namespace fs = std::filesystem;
namespace {

// The signed axis nearest `direction` among the axes `allowed` (by index) lets through.
template <typename Allowed>
SignedAxis nearest_axis(const glm::dvec3& direction, Allowed allowed) {
  SignedAxis best;
  double best_dot = -1.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!allowed(axis)) continue;
    const double d = std::abs(direction[axis]);
    if (d > best_dot) {
      best_dot = d;
      best = {axis, direction[axis] < 0.0 ? -1 : 1};
    }
  }
  return best;
}

}  // namespace

glm::dvec3 axis_vector(const SignedAxis& axis) {
  glm::dvec3 v(0.0);
  v[axis.axis] = double(axis.sign);
  return v;
}

ModelOrientation format_orientation(const std::string& mesh_path) {
  std::string ext = fs::path(mesh_path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".stl") return {{2, 1}, {1, -1}};
  return {};
}

std::string orientation_file_path(const std::string& mesh_path) {
  if (mesh_path.empty()) return {};  // a mesh made in memory
  fs::path p(mesh_path);
  p.replace_extension(".orientation.json");
  return p.string();
}

ModelOrientation mesh_orientation(const std::string& mesh_path) {
  const std::string file = orientation_file_path(mesh_path);
  std::error_code ec;
  if (file.empty() || !fs::exists(file, ec)) return format_orientation(mesh_path);
  // Through read_input_file: a pipe or device under the sidecar's name must not block.
  return parse_model_orientation(read_input_file(file), file);
}

ModelOrientation orientation_from_view(const glm::dvec3& towards_eye, const glm::dvec3& camera_up) {
  ModelOrientation o;
  o.front = nearest_axis(towards_eye, [](int) { return true; });
  o.up = nearest_axis(camera_up, [&](int axis) { return axis != o.front.axis; });
  return o;
}

std::string orientation_label(const ModelOrientation& o) {
  std::string up = signed_axis_name(o.up), front = signed_axis_name(o.front);
  up[1] = char(std::toupper(up[1]));
  front[1] = char(std::toupper(front[1]));
  return "up " + up + ", front " + front;
}

}  // namespace primo::editor
