// A vertex animation as glTF morph targets. The rest mesh is the document save_mesh writes
// (mesh_export_gltf.h), so PriMo's own reader and other tools see the same triangles and face
// sizes; the targets, the times and the weights follow its data in the one buffer.

#include "primo/io/mesh_animation_gltf.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

#include "mesh_export_gltf.h"
#include "primo/util/error.h"
#include "primo/io/output_files.h"

namespace primo {
namespace {

using detail::GltfJson;

std::vector<float> as_floats(const std::vector<Vec3>& points) {
  std::vector<float> out;
  out.reserve(3 * points.size());
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) out.push_back(float(p[k]));
  return out;
}

// The position of every glTF vertex: its mesh vertex's.
std::vector<Vec3> gltf_positions(const std::vector<Vec3>& points, const detail::GltfVertices& vertices) {
  std::vector<Vec3> out;
  out.reserve(vertices.mesh_vertex.size());
  for (const int v : vertices.mesh_vertex) out.push_back(points[size_t(v)]);
  return out;
}

std::vector<Vec3> points_of(const Mesh& mesh) {
  std::vector<Vec3> points;
  points.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
  return points;
}

bool is_binary(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".glb") return true;
  if (ext == ".gltf") return false;
  throw Error(path + ": an animation is written as glTF: use .glb or .gltf");
}

}  // namespace

std::uint64_t mesh_animation_size_bound(const Mesh& rest, std::uint64_t frames,
                                        const std::string& path, const MeshAttributes& attributes) {
  const bool binary = is_binary(path);
  std::uint64_t corners = 0;
  for (auto f : rest.faces()) corners += 3 * (f.valence() - 2);
  std::uint64_t vertices = rest.n_vertices(), extra = 0;
  if (detail::has_gltf_attributes(attributes)) {
    vertices = detail::gltf_vertices(rest, attributes).mesh_vertex.size();
    extra += vertices * (8 * attributes.texcoords.size() + 16 * attributes.colors.size());
    extra += 1024 * (attributes.materials.size() + 1);  // a node, mesh and material each
    // JOINTS_0 and WEIGHTS_0 a vertex; a node (name, matrix) and an inverse bind matrix a joint.
    if (!attributes.skin.empty()) extra += 24 * vertices + 1024;
    for (const SkinJoint& joint : attributes.skin.joints) extra += 64 + 512 + 6 * joint.name.size();
    for (const MeshImage& image : attributes.images) {
      std::error_code error;
      const auto file = std::filesystem::file_size(std::filesystem::path(image.folder) / image.uri, error);
      extra += image.bytes.size() + (error ? 0 : std::uint64_t(file)) + 512 + image.uri.size();
    }
  }
  const std::uint64_t mesh_bytes = 24 * vertices + 4 * corners + 4096 + extra;
  const std::uint64_t weights = 4 * frames * frames;
  const std::uint64_t per_frame = 24 * vertices + 4 + 512;  // data, time, JSON
  const std::uint64_t bytes = mesh_bytes + weights + frames * per_frame;
  return binary ? bytes : bytes / 3 * 4 + 4;
}

void check_animation_output_path(const std::string& path) {
  is_binary(path);
  check_output_path(path);
}

MeshAnimation::MeshAnimation(const Mesh& rest, const MeshAttributes& attributes)
    : rest_(rest), posed_(rest), attributes_(attributes) {
  if (!attributes_.empty()) check_attributes(rest_, attributes_, "the animation's rest mesh");
  auto vertices = std::make_shared<detail::GltfVertices>(detail::gltf_vertices(rest_, attributes_));
  vertices_ = vertices;
  rest_positions_ = as_floats(gltf_positions(points_of(rest_), *vertices_));
  rest_normals_ = as_floats(detail::gltf_vertex_normals(rest_, attributes_, *vertices_));
}

int MeshAnimation::add_view(const std::string& bytes, bool vertex_data) {
  views_.push_back({buffer_.size(), bytes.size(), vertex_data});
  buffer_ += bytes;
  return int(views_.size()) - 1;
}

int MeshAnimation::add_accessor(const std::vector<float>& values, int components, bool bounds) {
  const size_t count = values.size() / size_t(components);
  Accessor a;
  a.count = count;
  a.components = components;
  std::vector<uint32_t> moved;
  for (size_t i = 0; i < count; ++i)
    for (int k = 0; k < components; ++k)
      if (values[i * size_t(components) + size_t(k)] != 0.0f) {
        moved.push_back(uint32_t(i));
        break;
      }
  // Nothing moved: glTF's accessor of zeros (no data at all) fails in Assimp 5.2 ("data is
  // null"), so the zeros are a sparse accessor substituting a zero for element 0.
  if (moved.empty()) moved.push_back(0);
  if (bounds) {
    // The bounds of every element, the zeros a sparse accessor leaves included.
    a.min.assign(size_t(components), moved.size() < count ? 0.0f : std::numeric_limits<float>::infinity());
    a.max.assign(size_t(components), moved.size() < count ? 0.0f : -std::numeric_limits<float>::infinity());
    for (uint32_t i : moved)
      for (int k = 0; k < components; ++k) {
        const float x = values[size_t(i) * size_t(components) + size_t(k)];
        a.min[size_t(k)] = std::min(a.min[size_t(k)], x);
        a.max[size_t(k)] = std::max(a.max[size_t(k)], x);
      }
  }
  if (3 * moved.size() < count) {
    std::vector<float> moved_values;
    moved_values.reserve(moved.size() * size_t(components));
    for (uint32_t i : moved)
      for (int k = 0; k < components; ++k)
        moved_values.push_back(values[size_t(i) * size_t(components) + size_t(k)]);
    std::string bytes;
    detail::append_raw(bytes, moved);
    a.sparse_count = moved.size();
    a.sparse_indices = add_view(bytes, false);
    bytes.clear();
    detail::append_raw(bytes, moved_values);
    a.sparse_values = add_view(bytes, false);
  } else {
    std::string bytes;
    detail::append_raw(bytes, values);
    a.view = add_view(bytes, true);
  }
  accessors_.push_back(std::move(a));
  return int(accessors_.size()) - 1;
}

void MeshAnimation::add_frame(double seconds, const std::vector<Vec3>& positions,
                              const std::string& name) {
  const std::string where = "animation frame " + std::to_string(times_.size()) + " (" + name + ")";
  if (positions.size() != rest_.n_vertices())
    throw Error(where + ": " + std::to_string(positions.size()) + " positions for a mesh of " +
                std::to_string(rest_.n_vertices()) + " vertices");
  if (!std::isfinite(seconds) || seconds < 0.0 || float(seconds) > std::numeric_limits<float>::max())
    throw Error(where + ": time " + std::to_string(seconds) + " s is not a finite time from 0");
  if (!times_.empty() && seconds < last_seconds_)
    throw Error(where + ": time " + std::to_string(seconds) + " s goes back (the previous frame is at " +
                std::to_string(last_seconds_) + " s)");
  const std::vector<float> frame = as_floats(positions);
  for (size_t i = 0; i < frame.size(); ++i)
    if (!std::isfinite(frame[i]))
      throw Error(where + ": vertex " + std::to_string(i / 3) + " has a coordinate that float32 "
                  "cannot hold (" + std::to_string(positions[i / 3][int(i % 3)]) + ")");
  const std::vector<float> copies = as_floats(gltf_positions(positions, *vertices_));
  std::vector<float> delta(copies.size());
  for (size_t i = 0; i < copies.size(); ++i) delta[i] = copies[i] - rest_positions_[i];
  for (auto v : posed_.vertices()) posed_.set_point(v, positions[size_t(v.idx())]);
  const std::vector<float> normals =
      as_floats(detail::gltf_vertex_normals(posed_, attributes_, *vertices_));
  std::vector<float> normal_delta(normals.size());
  for (size_t i = 0; i < normals.size(); ++i) normal_delta[i] = normals[i] - rest_normals_[i];

  Target t;
  t.position = add_accessor(delta, 3, true);  // glTF requires a POSITION target's bounds
  t.normal = add_accessor(normal_delta, 3, false);
  targets_.push_back(t);
  float time = float(seconds);
  if (!times_.empty() && time <= times_.back())
    time = std::nextafter(times_.back(), std::numeric_limits<float>::infinity());
  times_.push_back(time);
  last_seconds_ = seconds;
  names_.push_back(name);
}

std::string MeshAnimation::file_bytes(const std::string& path) const {
  const bool binary = is_binary(path);
  if (times_.empty()) throw Error(path + ": cannot save an animation without frames");
  detail::GltfDocument doc = detail::gltf_document(
      rest_, attributes_, binary, std::filesystem::path(path).stem().string(), path);
  GltfJson& json = doc.json;
  const size_t first_view = json["bufferViews"].size(), first_accessor = json["accessors"].size();
  doc.buffer.append((4 - doc.buffer.size() % 4) % 4, '\0');  // after images of any length
  const size_t offset = doc.buffer.size();
  doc.buffer += buffer_;
  for (const View& v : views_) {
    GltfJson view = {{"buffer", 0}, {"byteOffset", offset + v.offset}, {"byteLength", v.length}};
    if (v.vertex_data) view["target"] = detail::kArrayBuffer;
    json["bufferViews"].push_back(view);
  }
  const auto add_json_accessor = [&](const Accessor& a) {
    GltfJson accessor;
    if (a.view >= 0) accessor["bufferView"] = first_view + size_t(a.view);
    accessor["componentType"] = detail::kFloat;
    accessor["count"] = a.count;
    accessor["type"] = a.components == 3 ? "VEC3" : "SCALAR";
    if (!a.min.empty()) accessor["min"] = a.min, accessor["max"] = a.max;
    if (a.sparse_count > 0)
      accessor["sparse"] = {
          {"count", a.sparse_count},
          {"indices", {{"bufferView", first_view + size_t(a.sparse_indices)},
                       {"componentType", detail::kUnsignedInt}}},
          {"values", {{"bufferView", first_view + size_t(a.sparse_values)}}}};
    json["accessors"].push_back(accessor);
  };
  for (const Accessor& a : accessors_) add_json_accessor(a);

  // The key times, and the weights at each: frame i's target at 1, the others at 0. Dense:
  // readers make the zeros of a sparse accessor anyway (frames x frames floats), and PriMo's
  // glTF checks refuse zeros that no data of the file bounds.
  const size_t n = times_.size();
  const auto append_view = [&](const std::string& bytes) {
    json["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", doc.buffer.size()}, {"byteLength", bytes.size()}});
    doc.buffer += bytes;
    return json["bufferViews"].size() - 1;
  };
  std::string bytes;
  detail::append_raw(bytes, times_);
  json["accessors"].push_back({{"bufferView", append_view(bytes)},
                               {"componentType", detail::kFloat},
                               {"count", n},
                               {"type", "SCALAR"},
                               {"min", {times_.front()}},
                               {"max", {times_.back()}}});
  const size_t times_accessor = json["accessors"].size() - 1;
  std::vector<float> weights(n * n, 0.0f);
  for (size_t i = 0; i < n; ++i) weights[i * n + i] = 1.0f;
  bytes.clear();
  detail::append_raw(bytes, weights);
  json["accessors"].push_back({{"bufferView", append_view(bytes)},
                               {"componentType", detail::kFloat},
                               {"count", n * n},
                               {"type", "SCALAR"}});

  // Every mesh (one per material) morphs by the same targets, its node's weights driven by the
  // one sampler.
  GltfJson targets = GltfJson::array();
  for (const Target& t : targets_)
    targets.push_back({{"POSITION", first_accessor + size_t(t.position)},
                       {"NORMAL", first_accessor + size_t(t.normal)}});
  for (GltfJson& mesh : json["meshes"]) {
    for (GltfJson& primitive : mesh["primitives"]) primitive["targets"] = targets;
    mesh["weights"] = std::vector<float>(n, 0.0f);
    mesh["extras"] = {{"targetNames", names_}};  // what Blender names its shape keys
  }
  GltfJson channels = GltfJson::array();
  for (size_t node = 0; node < json["nodes"].size(); ++node)
    if (json["nodes"][node].contains("mesh"))
      channels.push_back({{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}});
  json["animations"] = GltfJson::array(
      {{{"name", "frames"},
        {"channels", channels},
        {"samplers", {{{"input", times_accessor},
                       {"output", json["accessors"].size() - 1},
                       {"interpolation", "LINEAR"}}}}}});
  return detail::gltf_file_bytes(std::move(doc), binary, path);
}

}  // namespace primo
