// Scene formats (glTF 2.0, FBX, COLLADA, 3MF) read through Assimp and baked into one polygon
// soup, which mesh_from_soup then validates like any other file.
//
// 1. Assimp reads the file with no post-processing but the validation of its own data
//    structure: no triangulation (polygons stay polygons), no joining or reordering.
// 2. Every mesh of the scene's node tree is taken, each time a node refers to it, with the
//    node's global transform (so the soup is what a viewer shows); a transform that mirrors
//    reverses its faces, which keeps the orientation a viewer's front faces have.
// 3. Exporters split a vertex wherever its UV, normal or material changes (FBX and COLLADA
//    through Assimp even give every face corner its own vertex), which would tear the surface
//    into pieces. Vertices are merged when their transformed positions are bitwise equal, in
//    order of first appearance. Split copies come from the same stored coordinates, so they are
//    exactly equal; distinct vertices are never merged however close. A file written by PriMo
//    (its node has the extras key primo_face_sizes) is not merged: its vertices are the mesh's,
//    unless it was written with attributes (primo_vertex_copies: a vertex per distinct corner).
// 4. glTF holds triangles only. When a node carries PriMo's face sizes and its triangles are
//    exactly the fans PriMo writes, the fans are joined back into the original faces.
// 5. What was joined, merged and left out goes into a one-line note.

#include "mesh_import_assimp.h"

#include <assimp/material.h>
#include <assimp/metadata.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Dense>
#include <algorithm>
#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "checks/collada_checks.h"
#include "checks/fbx_checks.h"
#include "checks/gltf_accessor_checks.h"
#include "checks/gltf_buffer_files.h"
#include "checks/gltf_limits.h"
#include "../mesh_export_gltf.h"
#include "scene_attributes.h"
#include "scene_reader_process.h"
#include "scene_signature.h"
#include "checks/threemf_checks.h"
#include "scene_skin.h"
#include "primo/util/error.h"
#include "primo/io/input_files.h"
#include "primo/io/mesh_import.h"

namespace fs = std::filesystem;

// Debian's Assimp is built with its internal checks (ai_assert) on, and their handler prints to
// stderr and aborts the process: a damaged 3MF file (a zip without its model) would take the
// editor down with it. The library calls this function through its exported symbol, which this
// definition replaces for the whole process (the static core is linked into the executable,
// whose definition wins), so a failed check becomes an exception that the importer catches
// and reports as its error: "cannot read: not a valid 3MF file (Assimp: internal check failed:
// mRootStream != nullptr)". Its handler setter is not exported by Debian's build.
namespace Assimp {
void aiAssertViolation(const char* expression, const char* file, int line);
void aiAssertViolation(const char* expression, const char* /*file*/, int /*line*/) {
  throw std::runtime_error(std::string("internal check failed: ") +
                           (expression ? expression : "?"));
}
}  // namespace Assimp

namespace primo {
namespace detail {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

std::string lowercase_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string format_name(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".gltf" || ext == ".glb") return "glTF";
  if (ext == ".fbx") return "FBX";
  if (ext == ".dae") return "COLLADA";
  if (ext == ".3mf") return "3MF";
  return ext;
}

// A name or message from the file for a one-line message: control bytes become '?', at most
// `limit` bytes (not cutting a UTF-8 character).
std::string printable(const std::string& text, size_t limit) {
  std::string out;
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  if (out.size() > limit) {
    size_t cut = limit;
    while (cut > 0 && (static_cast<unsigned char>(out[cut]) & 0xC0) == 0x80) --cut;
    out = out.substr(0, cut) + "...";
  }
  return out;
}

std::string quoted_name(const aiString& name) {
  if (name.length == 0) return "(unnamed)";
  return "'" + printable(std::string(name.C_Str()), 40) + "'";
}

// Assimp's message, first line only.
std::string assimp_message(const char* message) {
  std::string text = message ? message : "";
  const size_t end = text.find_first_of("\r\n");
  if (end != std::string::npos) text.resize(end);
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return printable(text.empty() ? "no reason given" : text, 200);
}

std::string plural(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

// Bitwise position key; -0 and +0 are the same coordinate.
struct PositionKey {
  uint64_t bits[3];
  bool operator==(const PositionKey& other) const {
    return bits[0] == other.bits[0] && bits[1] == other.bits[1] && bits[2] == other.bits[2];
  }
};

PositionKey key_of(const Vec3& p) {
  PositionKey key;
  for (int k = 0; k < 3; ++k) {
    const double value = p[k] == 0.0 ? 0.0 : p[k];
    std::memcpy(&key.bits[k], &value, sizeof value);
  }
  return key;
}

struct PositionHash {
  size_t operator()(const PositionKey& key) const {
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (uint64_t b : key.bits) h = (h ^ b) * 0x100000001B3ull + (h >> 29);
    return size_t(h);
  }
};

// "4x2928 3x10" -> {4 x 2928, 3 x 10}; nothing when the text is not of that form.
std::vector<std::pair<int, long long>> parse_face_sizes(const std::string& text) {
  std::vector<std::pair<int, long long>> runs;
  size_t i = 0;
  const auto number = [&](long long& value) {
    const size_t begin = i;
    value = 0;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) &&
           value < (1LL << 40))
      value = value * 10 + (text[i++] - '0');
    return i > begin && value < (1LL << 40);
  };
  while (i < text.size()) {
    long long size, count;
    if (!number(size) || i >= text.size() || text[i++] != 'x' || !number(count)) return {};
    if (size < 3 || size > INT_MAX || count < 1) return {};
    runs.emplace_back(int(size), count);
    if (i < text.size() && text[i++] != ' ') return {};
  }
  return runs;
}

// The fans PriMo writes (v0 vk vk+1 for each face, in face order) joined back into faces, or
// nothing when the triangles are not exactly those fans.
bool join_fans(const std::vector<std::pair<int, long long>>& runs,
               std::vector<std::vector<int>>& faces) {
  long long expected = 0;
  for (const auto& [size, count] : runs) expected += (size - 2) * count;
  if (expected != (long long)faces.size()) return false;
  for (const auto& face : faces)
    if (face.size() != 3) return false;
  std::vector<std::vector<int>> joined;
  size_t t = 0;
  for (const auto& [size, count] : runs)
    for (long long c = 0; c < count; ++c) {
      std::vector<int> face = faces[t];
      for (int k = 1; k < size - 2; ++k) {
        const std::vector<int>& next = faces[t + size_t(k)];
        if (next[0] != face[0] || next[1] != face.back()) return false;
        face.push_back(next[2]);
      }
      t += size_t(size - 2);
      joined.push_back(std::move(face));
    }
  faces = std::move(joined);
  return true;
}

struct Instance {
  std::string node_name;  // quoted
  size_t first_face = 0;
  size_t n_faces = 0;
};

class SceneBaker {
 public:
  SceneBaker(const aiScene& scene, const std::string& path)
      : scene_(scene), path_(path), attributes_(scene, path), skin_(scene, path) {}

  SceneSoup bake() {
    if (!scene_.mRootNode) fail(path_, "cannot read: the " + format_name(path_) + " scene has no nodes");
    visit_nodes();
    if (instances_.empty()) {
      std::string what = "empty mesh: the scene holds no mesh";
      if (scene_.mNumMeshes > 0) what += " in its node tree (" + plural(scene_.mNumMeshes, "mesh", "meshes") + " outside it)";
      fail(path_, what);
    }
    SceneSoup out;
    soup_.attributes = attributes_.finish(dropped_);
    soup_.attributes.skin = skin_.finish(soup_.points.size(), skin_said_);
    out.note = note();
    if (instances_.size() > 1) out.parts = parts();
    out.soup = std::move(soup_);
    return out;
  }

 private:
  void visit_nodes() {
    std::vector<bool> used(scene_.mNumMeshes, false);
    std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack;
    stack.emplace_back(scene_.mRootNode, to_eigen(scene_.mRootNode->mTransformation));
    size_t visited = 0;
    while (!stack.empty()) {
      const auto [node, transform] = stack.back();
      stack.pop_back();
      if (++visited > (1u << 24)) fail(path_, "cannot read: the scene has too many nodes");
      for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        const unsigned index = node->mMeshes[i];
        if (index >= scene_.mNumMeshes || !scene_.mMeshes[index])
          fail(path_, "cannot read: node " + quoted_name(node->mName) + " refers to mesh " +
                          std::to_string(index) + ", but the scene has " +
                          plural(scene_.mNumMeshes, "mesh", "meshes"));
        used[index] = true;
        add_mesh(*node, *scene_.mMeshes[index], transform);
      }
      for (unsigned c = node->mNumChildren; c-- > 0;)
        if (const aiNode* child = node->mChildren[c])
          stack.emplace_back(child, transform * to_eigen(child->mTransformation));
    }
    unused_meshes_ = size_t(std::count(used.begin(), used.end(), false));
  }

  void add_mesh(const aiNode& node, const aiMesh& mesh, const Eigen::Matrix4d& transform) {
    aiString face_sizes, copies;
    const bool primo_file =
        node.mMetaData && node.mMetaData->Get(std::string(kFaceSizesKey), face_sizes);
    // A file PriMo wrote with attributes has a vertex per distinct corner: merged by position.
    const bool keep_vertices =
        primo_file && !node.mMetaData->Get(std::string(kVertexCopiesKey), copies);
    if (!mesh.mVertices && mesh.mNumVertices > 0)
      fail(path_, "cannot read: mesh " + quoted_name(mesh.mName) + " has no vertex positions");
    if (soup_.points.size() + mesh.mNumVertices > size_t(INT_MAX))
      fail(path_, "cannot read: more than " + std::to_string(INT_MAX) + " vertices");

    // Positions, transformed, merged by position unless PriMo wrote them.
    std::vector<int> index_of(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& a = mesh.mVertices[v];
      const Eigen::Vector4d h = transform * Eigen::Vector4d(a.x, a.y, a.z, 1.0);
      const Vec3 p = h[3] == 1.0 ? Vec3(h.head<3>()) : Vec3(h.head<3>() / h[3]);
      ++input_vertices_;
      if (keep_vertices) {
        index_of[v] = int(soup_.points.size());
        soup_.points.push_back(p);
        continue;
      }
      const auto [it, inserted] = merged_.emplace(key_of(p), int(soup_.points.size()));
      if (inserted) soup_.points.push_back(p);
      index_of[v] = it->second;
    }
    skin_.add_mesh(node, mesh, transform, index_of);

    // Faces: points and lines are counted and left out.
    std::vector<std::vector<int>> faces;
    faces.reserve(mesh.mNumFaces);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices == 1) ++points_;
      if (face.mNumIndices == 2) ++lines_;
      if (face.mNumIndices < 3) continue;
      if (!face.mIndices) fail(path_, "cannot read: mesh " + quoted_name(mesh.mName) + " face " + std::to_string(f) + " has no indices");
      std::vector<int> polygon(face.mNumIndices);
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices)
          fail(path_, "cannot read: mesh " + quoted_name(mesh.mName) + " face " + std::to_string(f) +
                          ": vertex index " + std::to_string(face.mIndices[k]) +
                          " is out of range (the mesh has " + std::to_string(mesh.mNumVertices) +
                          " vertices)");
        polygon[k] = int(face.mIndices[k]);
      }
      faces.push_back(std::move(polygon));
    }
    if (primo_file) {
      const auto runs = parse_face_sizes(face_sizes.C_Str());
      if (runs.empty() || !join_fans(runs, faces)) face_sizes_mismatch_ = true;
    } else if (!faces.empty()) {
      any_foreign_faces_ = true;
    }

    // A mirroring transform turns the faces inside out; reversing them keeps the side a viewer
    // shows as the front.
    const bool mirrored = transform.topLeftCorner<3, 3>().determinant() < 0;
    Instance instance{quoted_name(node.mName), soup_.faces.size(), faces.size()};
    std::vector<int> distinct;
    std::vector<unsigned> ai_corners;
    for (auto& face : faces) {
      ai_corners.assign(face.begin(), face.end());
      for (int& index : face) index = index_of[size_t(index)];
      // A face with fewer than 3 distinct corners once copies are merged has no area: exporters
      // leave such collapsed triangles behind, and they are dropped (and counted) here.
      distinct = face;
      std::sort(distinct.begin(), distinct.end());
      if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() < 3) {
        ++collapsed_faces_;
        --instance.n_faces;
        continue;
      }
      if (mirrored) {
        std::reverse(face.begin() + 1, face.end());
        std::reverse(ai_corners.begin() + 1, ai_corners.end());
      }
      attributes_.add_face(mesh, ai_corners, face);
      soup_.faces.push_back(std::move(face));
    }
    instances_.push_back(instance);

    // What the soup leaves out of this mesh.
    morph_targets_ += mesh.mNumAnimMeshes;
  }

  std::string note() const {
    std::vector<std::string> said;
    if (instances_.size() > 1) {
      std::string joined = std::to_string(instances_.size()) + " meshes joined into one:";
      for (size_t i = 0; i < instances_.size() && i < 4; ++i)
        joined += std::string(i ? ", " : " ") + instances_[i].node_name + " (" +
                  plural(instances_[i].n_faces, "face", "faces") + ")";
      if (instances_.size() > 4) joined += " and " + std::to_string(instances_.size() - 4) + " more";
      said.push_back(joined);
    }
    const size_t merged = input_vertices_ - soup_.points.size();
    if (merged > 0)
      said.push_back("merged " + plural(merged, "vertex copy", "vertex copies") +
                     " split for UVs or normals (" + std::to_string(input_vertices_) + " -> " +
                     std::to_string(soup_.points.size()) + " vertices)");
    if (collapsed_faces_)
      said.push_back("dropped " + plural(collapsed_faces_, "face", "faces") +
                     " whose corners coincide (no area)");
    if (face_sizes_mismatch_)
      said.push_back(std::string("the triangles do not match the file's ") + kFaceSizesKey +
                     ": faces kept as triangles");
    const std::string format = format_name(path_);
    if (any_foreign_faces_ && format == "glTF")
      said.push_back("glTF stores triangles only, so the faces are triangles");
    said.insert(said.end(), skin_said_.begin(), skin_said_.end());

    // UVs, normals, colours and materials are kept (SceneAttributeCollector), and the skin
    // (SceneSkinCollector).
    std::vector<std::string> ignored = dropped_;
    if (morph_targets_) ignored.push_back(plural(morph_targets_, "morph target", "morph targets"));
    if (scene_.mNumAnimations)
      ignored.push_back(plural(scene_.mNumAnimations, "animation", "animations"));
    if (scene_.mNumCameras) ignored.push_back(plural(scene_.mNumCameras, "camera", "cameras"));
    if (scene_.mNumLights) ignored.push_back(plural(scene_.mNumLights, "light", "lights"));
    if (points_) ignored.push_back(plural(points_, "point", "points"));
    if (lines_) ignored.push_back(plural(lines_, "line segment", "line segments"));
    if (unused_meshes_)
      ignored.push_back(plural(unused_meshes_, "mesh", "meshes") + " outside the node tree");

    if (said.empty() && ignored.empty()) return "";
    std::string out = path_ + ": ";
    for (size_t i = 0; i < said.size(); ++i) out += (i ? "; " : "") + said[i];
    if (!ignored.empty()) {
      out += said.empty() ? "ignored: " : "; ignored: ";
      for (size_t i = 0; i < ignored.size(); ++i) out += (i ? ", " : "") + ignored[i];
    }
    return out;
  }

  std::string parts() const {
    std::string out = "the file's " + std::to_string(instances_.size()) + " meshes were joined:";
    for (size_t i = 0; i < instances_.size() && i < 6; ++i) {
      const Instance& in = instances_[i];
      out += std::string(i ? ", " : " ") + "faces " + std::to_string(in.first_face) + "-" +
             std::to_string(in.first_face + in.n_faces - (in.n_faces ? 1 : 0)) + " " + in.node_name;
    }
    if (instances_.size() > 6) out += ", ...";
    return out;
  }

  const aiScene& scene_;
  const std::string& path_;
  PolygonSoup soup_;
  std::unordered_map<PositionKey, int, PositionHash> merged_;
  std::vector<Instance> instances_;
  size_t input_vertices_ = 0;
  size_t points_ = 0, lines_ = 0, unused_meshes_ = 0, morph_targets_ = 0, collapsed_faces_ = 0;
  SceneAttributeCollector attributes_;
  std::vector<std::string> dropped_;  // attributes that could not be kept
  bool any_foreign_faces_ = false;  // faces of meshes PriMo did not write
  bool face_sizes_mismatch_ = false;
  SceneSkinCollector skin_;
  std::vector<std::string> skin_said_;  // what the skin kept and changed
};

// Leaves `importer` only the readers of the format `path`'s extension names (glTF has two,
// for its versions 1 and 2): bytes they decline are refused, not passed on to whichever of
// Assimp's other readers claims them (scene_signature.h).
void keep_only_readers_of(Assimp::Importer& importer, const std::string& path) {
  const std::string ext = lowercase_extension(path).substr(1);
  std::vector<Assimp::BaseImporter*> others;
  for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
    Assimp::BaseImporter* reader = importer.GetImporter(i);
    std::set<std::string> extensions;
    reader->GetExtensionList(extensions);
    if (extensions.count(ext) == 0) others.push_back(reader);
  }
  // Unregistering hands a reader back to its caller.
  for (Assimp::BaseImporter* reader : others)
    if (importer.UnregisterLoader(reader) == aiReturn_SUCCESS) delete reader;
}

// The first bytes of the file at `path` (after check_input_file).
std::string file_head(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kSignatureBytes, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(std::max<std::streamsize>(in.gcount(), 0)));
  return head;
}

// What a glTF asks of Assimp (its node tree) and of the file system (its buffer files), from
// one parse of its JSON.
// `bytes` are the whole asset; its buffer files are read from its folder when `files_beside`.
void check_gltf_before_assimp(std::string_view bytes, const std::string& path, bool files_beside) {
  const nlohmann::json outline = gltf_outline(bytes, path);
  check_gltf_node_tree(outline, path);
  check_gltf_buffer_files(outline, path);
  const auto folder = files_beside ? std::optional<std::string>(fs::path(path).parent_path().string())
                                   : std::nullopt;
  check_gltf_accessors(outline, gltf_buffer_bytes(outline, bytes, folder), path);
}

// Assimp logs only through its DefaultLogger, which PriMo never creates: nothing is printed.
// Its importers throw internally and return no scene; the catches are for what escapes them.
template <typename Read>
SceneSoup read_in_this_process(const std::string& path, Read read) {
  try {
    Assimp::Importer importer;
    keep_only_readers_of(importer, path);
    const aiScene* scene = read(importer, aiProcess_ValidateDataStructure);
    if (!scene) {
      const std::string message = assimp_message(importer.GetErrorString());
      if (message.find("bad_alloc") != std::string::npos) throw std::bad_alloc();
      fail(path, "cannot read: not a valid " + format_name(path) + " file (Assimp: " + message + ")");
    }
    return SceneBaker(*scene, path).bake();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;  // read_in_child_process names the limit
  } catch (const std::exception& e) {
    fail(path, "cannot read: not a valid " + format_name(path) + " file (Assimp: " +
                   assimp_message(e.what()) + ")");
  }
}

// Assimp runs in a child process (scene_reader_process.h), with `limits` or those for
// `input_bytes`.
template <typename Read>
SceneSoup read_with_assimp(const std::string& path, size_t input_bytes,
                           const ReaderProcessLimits* limits, Read read) {
  return read_in_child_process(path, format_name(path),
                               limits ? *limits : reader_process_limits(input_bytes),
                               [&] { return read_in_this_process(path, read); });
}

}  // namespace

SceneSoup read_scene_file(const std::string& path, const ReaderProcessLimits* limits) {
  // Assimp opens the file itself (a .gltf also its buffers): it must not meet a pipe or a device.
  check_input_file(path);
  const std::string head = file_head(path);
  if (head.empty()) fail(path, "cannot read: the file is empty");
  check_scene_signature(head, path);
  const std::string ext = lowercase_extension(path);
  if (ext == ".dae") check_collada(read_input_file(path), path);
  if (ext == ".3mf") check_3mf(read_input_file(path), path);
  if (ext == ".gltf" || ext == ".glb")
    check_gltf_before_assimp(read_input_file(path), path, true);
  if (ext == ".fbx") check_fbx_before_assimp(read_input_file(path), path);
  std::error_code error;
  const auto file_bytes = fs::file_size(path, error);
  const size_t input_bytes = error ? 0 : size_t(file_bytes);
  return read_with_assimp(path, input_bytes, limits, [&](Assimp::Importer& importer, unsigned flags) {
    return importer.ReadFile(path, flags);
  });
}

SceneSoup read_scene_bytes(std::string_view bytes, const std::string& path,
                           const ReaderProcessLimits* limits) {
  if (bytes.empty()) fail(path, "cannot read: the file is empty");
  check_scene_signature(bytes.substr(0, kSignatureBytes), path);
  const std::string ext = lowercase_extension(path);
  if (ext == ".dae") check_collada(bytes, path);
  if (ext == ".3mf") check_3mf(bytes, path);
  if (ext == ".gltf" || ext == ".glb") check_gltf_before_assimp(bytes, path, false);
  if (ext == ".fbx") check_fbx_before_assimp(bytes, path);
  const std::string hint = ext.substr(1);
  return read_with_assimp(path, bytes.size(), limits, [&](Assimp::Importer& importer, unsigned flags) {
    return importer.ReadFileFromMemory(bytes.data(), bytes.size(), flags, hint.c_str());
  });
}

Mesh mesh_from_scene_soup(const SceneSoup& scene, const std::string& path) {
  if (scene.parts.empty()) return mesh_from_soup(scene.soup, path);
  try {
    return mesh_from_soup(scene.soup, path);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + " (" + scene.parts + ")");
  }
}

}  // namespace detail

bool is_scene_file(const std::string& path) {
  const std::string ext = detail::lowercase_extension(path);
  return ext == ".gltf" || ext == ".glb" || ext == ".fbx" || ext == ".dae" || ext == ".3mf";
}

LoadedMesh load_mesh_noted(const std::string& path) {
  if (!is_scene_file(path)) return detail::load_polygon_file(path);
  detail::SceneSoup scene = detail::read_scene_file(path);
  LoadedMesh loaded{detail::mesh_from_scene_soup(scene, path), scene.note,
                    std::move(scene.soup.attributes)};
  check_attributes(loaded.mesh, loaded.attributes, path + ": cannot read");
  return loaded;
}

}  // namespace primo
