// The 3MF check (threemf_checks.h), following Assimp 5.2.5's 3MF reader: D3MFOpcPackage.cpp and
// ZipArchiveIOSystem.cpp (which entries it opens and how it names them), XmlSerializer.cpp
// (what it reads from the model, in which order, with which number parser). Where Assimp would
// throw an error of its own, the check stays silent and lets Assimp say it.

#include "threemf_checks.h"

#include <unzip.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

#include "xml_scan.h"
#include "../../mesh_readers.h"
#include "node_graph_limits.h"
#include "primo/util/error.h"

namespace primo::detail {
namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& rule) {
  throw Error(path + ": cannot read: not a 3MF file PriMo accepts (" + rule + ")");
}



// An int as written: optional whitespace, sign and digits, within int's range; nullopt for
// anything else (Assimp's atoi would read "2x" as 2, "x" as 0 and "9999999999" as anything).
std::optional<int> int_value(std::string_view text) {
  size_t i = 0;
  while (i < text.size() && is_xml_space(text[i])) ++i;
  bool negative = false;
  if (i < text.size() && (text[i] == '-' || text[i] == '+')) negative = text[i++] == '-';
  const size_t digits = i;
  long long value = 0;
  for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
    value = value * 10 + (text[i] - '0');
    if (value > (long long)INT_MAX + 1) return std::nullopt;
  }
  if (i == digits) return std::nullopt;
  while (i < text.size() && is_xml_space(text[i])) ++i;
  if (i != text.size()) return std::nullopt;
  if (negative) value = -value;
  if (value > INT_MAX || value < INT_MIN) return std::nullopt;
  return int(value);
}

// Whether strtof reads all of `text` (but surrounding whitespace) as a number, as Assimp reads
// coordinates and transforms ("" and "1x" would be 0 and 1 without a word).
bool is_number(std::string_view text) {
  // The common case without strtof: digits, a point, digits.
  size_t i = 0;
  if (i < text.size() && text[i] == '-') ++i;
  const size_t start = i;
  while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
  bool digits = i > start;
  if (i < text.size() && text[i] == '.') {
    const size_t fraction = ++i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    digits = digits || i > fraction;
  }
  if (digits && i == text.size()) return true;
  // Anything else as strtof reads it (exponents, "inf", surrounding whitespace).
  while (!text.empty() && is_xml_space(text.back())) text.remove_suffix(1);
  if (text.empty() || text.size() > 200) return false;
  char buffer[256];
  std::memcpy(buffer, text.data(), text.size());
  buffer[text.size()] = '\0';
  char* end = nullptr;
  std::strtof(buffer, &end);
  return end != buffer && *end == '\0';
}

// --- The zip, in memory, through minizip ------------------------------------------------------

struct MemoryFile {
  std::string_view bytes;
  uint64_t at = 0;
};

voidpf zip_open(voidpf opaque, const void*, int) { return opaque; }
uLong zip_read(voidpf, voidpf stream, void* buffer, uLong size) {
  MemoryFile& file = *static_cast<MemoryFile*>(stream);
  const uint64_t n =
      std::min<uint64_t>(size, file.bytes.size() - std::min<uint64_t>(file.at, file.bytes.size()));
  std::memcpy(buffer, file.bytes.data() + file.at, size_t(n));
  file.at += n;
  return uLong(n);
}
uLong zip_write(voidpf, voidpf, const void*, uLong) { return 0; }
ZPOS64_T zip_tell(voidpf, voidpf stream) { return static_cast<MemoryFile*>(stream)->at; }
long zip_seek(voidpf, voidpf stream, ZPOS64_T offset, int origin) {
  MemoryFile& file = *static_cast<MemoryFile*>(stream);
  uint64_t base = 0;
  if (origin == ZLIB_FILEFUNC_SEEK_CUR)
    base = file.at;
  else if (origin == ZLIB_FILEFUNC_SEEK_END)
    base = file.bytes.size();
  else if (origin != ZLIB_FILEFUNC_SEEK_SET)
    return -1;
  if (offset > file.bytes.size() || base + offset > file.bytes.size()) return -1;
  file.at = base + offset;
  return 0;
}
int zip_close(voidpf, voidpf) { return 0; }
int zip_error(voidpf, voidpf) { return 0; }

class Zip {
 public:
  explicit Zip(std::string_view bytes) : file_{bytes, 0} {
    zlib_filefunc64_def functions;
    std::memset(&functions, 0, sizeof functions);
    functions.zopen64_file = zip_open;
    functions.zread_file = zip_read;
    functions.zwrite_file = zip_write;
    functions.ztell64_file = zip_tell;
    functions.zseek64_file = zip_seek;
    functions.zclose_file = zip_close;
    functions.zerror_file = zip_error;
    functions.opaque = &file_;
    handle_ = unzOpen2_64("memory", &functions);
  }
  ~Zip() {
    if (handle_) unzClose(handle_);
  }
  Zip(const Zip&) = delete;
  Zip& operator=(const Zip&) = delete;
  unzFile handle() const { return handle_; }

 private:
  MemoryFile file_;
  unzFile handle_ = nullptr;
};

// Assimp's ZipArchiveIOSystem::SimplifyFilename: backslashes become slashes, leading dots and
// slashes go, "a/../" folds.
std::string simplified(std::string name) {
  std::replace(name.begin(), name.end(), '\\', '/');
  const size_t first = name.find_first_not_of("./");
  if (first != 0) name.erase(0, first);
  const std::string relative = "/../";
  for (size_t at = name.find(relative); at != std::string::npos; at = name.find(relative)) {
    const size_t previous = at == 0 ? std::string::npos : name.rfind('/', at - 1);
    if (previous == std::string::npos || previous == at)
      name.erase(0, at + relative.size());
    else
      name.erase(previous, at + relative.size() - 1 - previous);
  }
  return name;
}

struct Entry {
  unz64_file_pos position{};
  uint64_t size = 0;  // declared, uncompressed
};

// The entries Assimp's archive maps: by simplified name, the first of a name, none empty and
// none whose name is longer than 256 bytes. Refuses entries that would inflate too far.
std::map<std::string, Entry> entries_of(unzFile zip, const std::string& path) {
  std::map<std::string, Entry> entries;
  uint64_t total = 0;
  if (unzGoToFirstFile(zip) != UNZ_OK) return entries;
  std::vector<char> name(65536);
  do {
    unz_file_info64 info;
    if (unzGetCurrentFileInfo64(zip, &info, name.data(), uLong(name.size()), nullptr, 0, nullptr,
                                0) != UNZ_OK)
      break;
    const std::string entry_name(name.data(), std::min<size_t>(info.size_filename, name.size()));
    const uint64_t allowed = std::min(
        kMax3mfEntryBytes,
        std::max<uint64_t>(uint64_t(1) << 20, info.compressed_size * kMax3mfInflationRatio));
    if (info.uncompressed_size > allowed)
      refuse(path, "its entry " + quoted(entry_name) + " would inflate from " +
                       std::to_string(info.compressed_size) + " to " +
                       std::to_string(info.uncompressed_size) + " bytes, more than " +
                       (allowed == kMax3mfEntryBytes
                            ? "an entry may (1 GiB)"
                            : std::to_string(kMax3mfInflationRatio) + " times its size"));
    total += info.uncompressed_size;
    if (total > kMax3mfZipBytes)
      refuse(path, "its entries would inflate to more than 2 GiB together");
    if (info.uncompressed_size != 0 && info.size_filename <= 256) {
      Entry entry;
      entry.size = info.uncompressed_size;
      unzGetFilePos64(zip, &entry.position);
      entries.emplace(simplified(entry_name), entry);
    }
  } while (unzGoToNextFile(zip) == UNZ_OK);
  return entries;
}

// Scans the entry's bytes, as many as it declares (what Assimp reads), with scan_xml.
std::string scan_entry(unzFile zip, const Entry& entry, const std::string& name, XmlScan& scan,
                       const std::string& path) {
  unz64_file_pos position = entry.position;
  if (unzGoToFilePos64(zip, &position) != UNZ_OK || unzOpenCurrentFile(zip) != UNZ_OK)
    refuse(path, "its entry " + quoted(name) + " cannot be inflated");
  uint64_t read = 0;
  bool damaged = false;
  const std::string rule = scan_xml(
      [&](char* buffer, int length) {
        const uint64_t wanted = std::min<uint64_t>(uint64_t(length), entry.size - read);
        if (wanted == 0) return 0;
        const int n = unzReadCurrentFile(zip, buffer, unsigned(wanted));
        if (n < 0) {
          damaged = true;
          return 0;
        }
        read += uint64_t(n);
        return n;
      },
      scan);
  const int closed = unzCloseCurrentFile(zip);
  if (damaged || (rule.empty() && (read != entry.size || closed == UNZ_CRCERROR)))
    refuse(path, "its entry " + quoted(name) + " is damaged (it does not inflate to the " +
                     std::to_string(entry.size) + " bytes it declares with their checksum)");
  return rule;
}

// _rels/.rels: the first relationship of the start-part type names the model (Assimp's
// OpcPackageRelationshipReader).
class RelationshipScan : public XmlScan {
 public:
  void open(std::string_view name, const std::vector<XmlAttribute>& attributes) override {
    ++depth_;
    if (depth_ == 1) in_relationships_ = name == "Relationships";
    if (depth_ != 2 || !in_relationships_ || name != "Relationship" || found_) return;
    std::string_view id, type, target;
    for (const XmlAttribute& a : attributes) {
      if (a.name == "Id") id = a.value;
      if (a.name == "Type") type = a.value;
      if (a.name == "Target") target = a.value;
    }
    if (id.empty() || type.empty() || target.empty()) return;
    if (type == "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel") {
      found_ = true;
      target_ = std::string(target);
    }
  }
  void text(std::string_view) override {}
  void close() override { --depth_; }
  bool found() const { return found_; }
  const std::string& target() const { return target_; }

 private:
  int depth_ = 0;
  bool in_relationships_ = false, found_ = false;
  std::string target_;
};

// --- The model -----------------------------------------------------------------------------------

enum class Resource { kObject, kBaseMaterials, kTextureGroup };

struct Object {
  int id = 0;
  std::vector<std::pair<int, int>> components;  // object id, line
  int line = 0;
};

enum class Kind : uint8_t {
  kOther,
  kSkipped,
  kModel,
  kResources,
  kObject,
  kMesh,
  kVertices,
  kTriangles,
  kComponents,
  kBuild,
  kBaseMaterials,
  kTextureGroup,
};

class ModelScan : public XmlScan {
 public:
  void open(std::string_view name, const std::vector<XmlAttribute>& attributes) override;
  void text(std::string_view) override {}
  void close() override;
  void finish();

 private:
  struct Frame {
    Kind kind = Kind::kOther;
  };
  struct Mesh {
    int vertices = 0;
    bool vertices_open = false, vertices_read = false, triangles_read = false;
    bool textured = false;  // Assimp's texture coordinates of this mesh are made
  };
  struct Pending {  // a resource read, entered into the dictionary when it closes (as Assimp)
    int id = 0;
    Resource type = Resource::kObject;
    int size = 0;  // bases or texture coordinates
    int object = -1;
    int line = 0;
  };
  struct Known {
    Resource type;
    int size;
    int object;
    int line;
  };

  std::optional<std::string_view> attribute(const std::vector<XmlAttribute>& attributes,
                                            std::string_view name) const {
    for (const XmlAttribute& a : attributes)
      if (a.name == name) return a.value;
    return std::nullopt;
  }
  void stop(const std::string& rule) {
    if (refusal.empty()) refusal = rule;
  }
  // The id `name` holds (nullopt when absent); refuses one that is no number.
  std::optional<int> id(const std::vector<XmlAttribute>& attributes, std::string_view element,
                        std::string_view name) {
    const auto text = attribute(attributes, name);
    if (!text) return std::nullopt;
    const auto value = int_value(*text);
    if (!value) {
      stop("<" + std::string(element) + "> at line " + std::to_string(line) + " has " +
           std::string(name) + "=" + quoted(*text) + ", which is no whole number");
      return std::nullopt;
    }
    return value;
  }
  void check_transform(const std::vector<XmlAttribute>& attributes, std::string_view element);
  void check_path(const std::vector<XmlAttribute>& attributes, std::string_view element);
  void vertex(const std::vector<XmlAttribute>& attributes);
  void triangle(const std::vector<XmlAttribute>& attributes);
  const Known* known(int id) const {
    const auto it = dictionary_.find(id);
    return it == dictionary_.end() ? nullptr : &it->second;
  }

  std::vector<Frame> frames_;
  bool resources_seen_ = false, build_seen_ = false;
  std::vector<Object> objects_;
  std::unordered_map<int, Known> dictionary_;
  Pending pending_;
  bool pending_open_ = false;
  std::optional<int> object_pid_, object_pindex_;
  Mesh mesh_;
  std::vector<std::pair<std::optional<int>, int>> items_;  // build items: object id, line
};

void ModelScan::check_transform(const std::vector<XmlAttribute>& attributes,
                                std::string_view element) {
  const auto transform = attribute(attributes, "transform");
  if (!transform) return;
  // Assimp splits at spaces only and reads 12 numbers, whether there are 12 or not.
  int numbers = 0;
  bool all_numbers = true;
  size_t at = 0;
  const std::string_view text = *transform;
  while (at <= text.size()) {
    size_t end = text.find(' ', at);
    if (end == std::string_view::npos) end = text.size();
    if (end > at) {
      ++numbers;
      all_numbers = all_numbers && is_number(text.substr(at, end - at));
    }
    at = end + 1;
  }
  if (numbers != 12 || !all_numbers)
    stop("the transform of the <" + std::string(element) + "> at line " + std::to_string(line) +
         " is not 12 numbers: " + quoted(text));
}

void ModelScan::check_path(const std::vector<XmlAttribute>& attributes, std::string_view element) {
  for (const XmlAttribute& a : attributes)
    if (a.local == "path" &&
        a.uri == "http://schemas.microsoft.com/3dmanufacturing/production/2015/06")
      stop("the <" + std::string(element) + "> at line " + std::to_string(line) +
           " refers to an object of the model part " + quoted(a.value) +
           ", which Assimp does not read (it would take an object of this part instead)");
}

void ModelScan::vertex(const std::vector<XmlAttribute>& attributes) {
  ++mesh_.vertices;
  for (const char* axis : {"x", "y", "z"}) {
    const auto value = attribute(attributes, axis);
    if (!value || !is_number(*value)) {
      stop("the <vertex> at line " + std::to_string(line) + " has " +
           (value ? std::string(axis) + "=" + quoted(*value) + ", which is no number"
                  : "no " + std::string(axis) + " (Assimp would read 0)"));
      return;
    }
  }
}

void ModelScan::triangle(const std::vector<XmlAttribute>& attributes) {
  const auto where = [&] { return "the <triangle> at line " + std::to_string(line); };
  if (!mesh_.vertices_read) {
    stop(where() + " comes before its mesh's <vertices>");
    return;
  }
  const char* names[3] = {"v1", "v2", "v3"};
  for (int k = 0; k < 3; ++k) {
    const auto text = attribute(attributes, names[k]);
    if (!text) {
      stop(where() + " has no " + names[k] + " (Assimp would read vertex 0)");
      return;
    }
    const auto value = int_value(*text);
    if (!value || *value < 0 || *value >= mesh_.vertices) {
      stop(where() + " has " + names[k] + "=" + quoted(*text) + ", but its mesh has " +
           std::to_string(mesh_.vertices) + " vertices");
      return;
    }
  }
  // Properties: Assimp indexes the base materials or texture coordinates with p1 (p2, p3)
  // when pid names them at this point of the file.
  const auto pid = id(attributes, "triangle", "pid");
  const auto p1 = id(attributes, "triangle", "p1");
  if (!refusal.empty() || !pid || !p1) return;
  const Known* group = known(*pid);
  if (!group) return;
  if (group->type == Resource::kBaseMaterials && (*p1 < 0 || *p1 >= group->size)) {
    stop(where() + " has p1=" + std::to_string(*p1) + ", but base materials " +
         std::to_string(*pid) + " has " + std::to_string(group->size));
    return;
  }
  if (group->type == Resource::kTextureGroup && !mesh_.textured) {
    // The first textured triangle of a mesh: Assimp reads p1, p2, p3 (-1 when absent).
    mesh_.textured = true;
    for (const char* p : {"p1", "p2", "p3"}) {
      const int index = id(attributes, "triangle", p).value_or(-1);
      if (!refusal.empty()) return;
      if (index < 0 || index >= group->size) {
        stop(where() + " has " + p + "=" + std::to_string(index) + ", but texture group " +
             std::to_string(*pid) + " has " + std::to_string(group->size) + " coordinates" +
             (index == -1 ? " (Assimp reads a missing one as -1)" : ""));
        return;
      }
    }
  }
}

void ModelScan::open(std::string_view name, const std::vector<XmlAttribute>& attributes) {
  const Kind parent = frames_.empty() ? Kind::kOther : frames_.back().kind;
  Frame frame;
  if (parent == Kind::kSkipped || (frames_.empty() && name != "model")) {
    frame.kind = Kind::kSkipped;
  } else if (frames_.empty()) {
    frame.kind = Kind::kModel;
  } else if (parent == Kind::kModel) {
    // Assimp reads the first <resources> and the first <build>.
    if (name == "resources") frame.kind = resources_seen_ ? Kind::kSkipped : Kind::kResources;
    if (name == "build") frame.kind = build_seen_ ? Kind::kSkipped : Kind::kBuild;
    resources_seen_ = resources_seen_ || name == "resources";
    build_seen_ = build_seen_ || name == "build";
  } else if (parent == Kind::kResources) {
    std::optional<int> resource;
    if (name == "object" || name == "basematerials" || name == "m:texture2dgroup") {
      resource = id(attributes, name, "id");
      if (!resource) {
        frame.kind = Kind::kSkipped;  // Assimp reads no resource without an id
        frames_.push_back(frame);
        return;
      }
      pending_ = Pending{*resource, Resource::kObject, 0, -1, line};
      pending_open_ = true;
    }
    if (name == "object") {
      frame.kind = Kind::kObject;
      pending_.object = int(objects_.size());
      objects_.push_back(Object{*resource, {}, line});
      object_pid_ = id(attributes, name, "pid");
      object_pindex_ = id(attributes, name, "pindex");
    } else if (name == "basematerials") {
      frame.kind = Kind::kBaseMaterials;
      pending_.type = Resource::kBaseMaterials;
    } else if (name == "m:texture2dgroup") {
      frame.kind = Kind::kTextureGroup;
      pending_.type = Resource::kTextureGroup;
    }
  } else if (parent == Kind::kObject) {
    if (name == "mesh") {
      frame.kind = Kind::kMesh;
      mesh_ = Mesh{};
      // Assimp takes the mesh's material from the object's pid and pindex.
      const Known* materials = object_pid_ ? known(*object_pid_) : nullptr;
      if (materials && object_pindex_ && materials->type == Resource::kBaseMaterials &&
          (*object_pindex_ < 0 || *object_pindex_ >= materials->size))
        stop("object " + std::to_string(pending_.id) +
             " has pindex=" + std::to_string(*object_pindex_) + ", but base materials " +
             std::to_string(*object_pid_) + " has " + std::to_string(materials->size));
    } else if (name == "components") {
      frame.kind = Kind::kComponents;
    }
  } else if (parent == Kind::kComponents && name == "component") {
    check_transform(attributes, name);
    check_path(attributes, name);
    if (const auto object = id(attributes, name, "objectid"))
      objects_[size_t(pending_.object)].components.emplace_back(*object, line);
    else
      stop("the <component> at line " + std::to_string(line) +
           " names no object; Assimp would leave it out");
  } else if (parent == Kind::kMesh) {
    if (name == "vertices") {
      if (mesh_.vertices_read || mesh_.vertices_open)
        stop("the mesh of object " + std::to_string(pending_.id) +
             " has a second <vertices> at line " + std::to_string(line) +
             "; Assimp would keep only the last");
      frame.kind = Kind::kVertices;
      mesh_.vertices_open = true;
    } else if (name == "triangles") {
      if (mesh_.triangles_read)
        stop("the mesh of object " + std::to_string(pending_.id) +
             " has a second <triangles> at line " + std::to_string(line) +
             "; Assimp would keep only the last");
      frame.kind = Kind::kTriangles;
      mesh_.triangles_read = true;
    }
  } else if (parent == Kind::kVertices && name == "vertex") {
    vertex(attributes);
  } else if (parent == Kind::kTriangles && name == "triangle") {
    triangle(attributes);
  } else if (parent == Kind::kBaseMaterials && name == "base") {
    ++pending_.size;
  } else if (parent == Kind::kTextureGroup && name == "m:tex2coord") {
    ++pending_.size;
  } else if (parent == Kind::kBuild && name == "item") {
    check_transform(attributes, name);
    check_path(attributes, name);
    items_.emplace_back(id(attributes, name, "objectid"), line);
  }
  frames_.push_back(frame);
}

void ModelScan::close() {
  if (frames_.empty()) return;
  const Kind kind = frames_.back().kind;
  frames_.pop_back();
  if (kind == Kind::kVertices) {
    mesh_.vertices_open = false;
    mesh_.vertices_read = true;
  }
  if ((kind == Kind::kObject || kind == Kind::kBaseMaterials || kind == Kind::kTextureGroup) &&
      pending_open_) {
    pending_open_ = false;
    const auto [it, inserted] = dictionary_.emplace(
        pending_.id, Known{pending_.type, pending_.size, pending_.object, pending_.line});
    if (!inserted)
      stop("two resources have the id " + std::to_string(pending_.id) + " (lines " +
           std::to_string(it->second.line) + " and " + std::to_string(pending_.line) +
           "); Assimp would keep the first and lose the meshes of the other");
  }
}

void ModelScan::finish() {
  if (!refusal.empty()) return;
  // Components and build items must name objects: Assimp leaves the others out.
  const size_t n = objects_.size();
  std::vector<std::vector<size_t>> edges(n);
  auto object_index = [&](int object_id) -> int {
    const Known* k = known(object_id);
    return k && k->type == Resource::kObject ? k->object : -1;
  };
  for (size_t o = 0; o < n; ++o)
    for (const auto& [component, line_of] : objects_[o].components) {
      const int target = object_index(component);
      if (target < 0) {
        stop("a component of object " + std::to_string(objects_[o].id) + " (line " +
             std::to_string(line_of) + ") names object " + std::to_string(component) +
             ", which the file does not have; Assimp would leave it out");
        return;
      }
      edges[o].push_back(size_t(target));
    }
  std::vector<size_t> roots;
  for (const auto& [item, line_of] : items_) {
    const int target = item ? object_index(*item) : -1;
    if (target < 0) {
      stop("the build item at line " + std::to_string(line_of) +
           (item ? " names object " + std::to_string(*item) + ", which the file does not have"
                 : " names no object") +
           "; Assimp would leave it out");
      return;
    }
    roots.push_back(size_t(target));
  }
  // Cycles, depth and instances: the objects, and the build (the last node) whose children
  // are the items' objects.
  edges.push_back(roots);
  const std::string problem = node_graph_problem(edges, [&](size_t k) {
    return k == n ? std::string("the build") : "object " + std::to_string(objects_[k].id);
  });
  if (!problem.empty()) stop(problem);
}

}  // namespace

void check_3mf(std::string_view bytes, const std::string& path) {
  Zip zip(bytes);
  if (!zip.handle()) return;  // no zip minizip reads: Assimp's minizip refuses it, and says so
  const std::map<std::string, Entry> entries = entries_of(zip.handle(), path);
  // The model part is the one _rels/.rels names as the start part (D3MFOpcPackage).
  const auto rels = entries.find("_rels/.rels");
  if (rels == entries.end()) refuse(path, "it has no _rels/.rels to name its model part");
  RelationshipScan relationships;
  if (const std::string rule =
          scan_entry(zip.handle(), rels->second, rels->first, relationships, path);
      !rule.empty())
    refuse(path, "_rels/.rels: " + rule);
  if (!relationships.found()) refuse(path, "its _rels/.rels names no model part");
  std::string model = relationships.target();
  for (int k = 0; k < 2 && !model.empty() && model[0] == '/'; ++k) model.erase(0, 1);
  const auto part = entries.find(simplified(model));
  if (part == entries.end())
    refuse(path, "its model part " + quoted(relationships.target()) + " is missing");
  ModelScan scan;
  if (const std::string rule = scan_entry(zip.handle(), part->second, part->first, scan, path);
      !rule.empty())
    refuse(path, rule);
  scan.finish();
  if (!scan.refusal.empty()) refuse(path, scan.refusal);
}

}  // namespace primo::detail
