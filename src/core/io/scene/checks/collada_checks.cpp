// The COLLADA check (collada_checks.h).
//
// The scan follows what Assimp 5.2.5's COLLADA reader (code/AssetLib/Collada/ColladaParser.cpp
// and ColladaLoader.cpp) reads, in the order it reads it: which element it takes from where,
// the text pugixml hands it, which id a reference finds at the time it is resolved. Where the
// reader would throw an error of its own, the check stays silent and lets Assimp say it.

#include "collada_checks.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <unordered_map>

#include "../../mesh_readers.h"
#include "node_graph_limits.h"
#include "xml_scan.h"
#include "primo/util/error.h"

namespace primo::detail {

// --- COLLADA ------------------------------------------------------------------------------------

namespace {

constexpr uint64_t kNone = std::numeric_limits<uint64_t>::max();

[[noreturn]] void refuse(const std::string& path, const std::string& rule) {
  throw Error(path + ": cannot read: not a COLLADA file PriMo accepts (" + rule + ")");
}

// A whole number as written: optional whitespace and '+', digits (saturating at kNone - 1).
// nullopt for anything else (negative numbers included).
std::optional<uint64_t> whole_number(std::string_view text) {
  size_t i = 0;
  while (i < text.size() && is_xml_space(text[i])) ++i;
  if (i < text.size() && text[i] == '+') ++i;
  const size_t digits = i;
  uint64_t value = 0;
  for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i)
    value = value > (kNone - 10) / 10 ? kNone - 1 : value * 10 + uint64_t(text[i] - '0');
  if (i == digits) return std::nullopt;
  while (i < text.size() && is_xml_space(text[i])) ++i;
  if (i != text.size()) return std::nullopt;
  return value;
}


uint64_t saturating_product(uint64_t a, uint64_t b) {
  const unsigned __int128 p = static_cast<unsigned __int128>(a) * b;
  return p > kNone ? kNone : uint64_t(p);
}

uint64_t saturating_sum(uint64_t a, uint64_t b) { return a > kNone - b ? kNone : a + b; }

// Whitespace-separated tokens of a text that arrives in pieces (Assimp's readers split on
// spaces, tabs and line ends, which is XML's whitespace).
class Tokens {
 public:
  // Calls token(std::string_view) for each complete token.
  template <typename F>
  void feed(std::string_view piece, F token) {
    size_t i = 0;
    while (i < piece.size()) {
      if (is_xml_space(piece[i])) {
        if (!partial_.empty()) {
          token(std::string_view(partial_));
          partial_.clear();
        }
        ++i;
        continue;
      }
      size_t end = i;
      while (end < piece.size() && !is_xml_space(piece[end])) ++end;
      if (end == piece.size()) {  // may continue in the next piece
        partial_.append(piece.substr(i));
        return;
      }
      if (partial_.empty()) {
        token(piece.substr(i, end - i));
      } else {
        partial_.append(piece.substr(i, end - i));
        token(std::string_view(partial_));
        partial_.clear();
      }
      i = end;
    }
  }
  template <typename F>
  void finish(F token) {
    if (!partial_.empty()) token(std::string_view(partial_));
    partial_.clear();
  }

 private:
  std::string partial_;
};

// How many whitespace-separated values a text holds (float arrays: counted, not parsed).
class ValueCounter {
 public:
  void feed(std::string_view piece) {
    for (char c : piece) {
      const bool space = is_xml_space(c);
      if (!space && !in_value_) ++count_;
      in_value_ = !space;
    }
  }
  uint64_t count() const { return count_; }

 private:
  uint64_t count_ = 0;
  bool in_value_ = false;
};

// An index as Assimp's strtol10 would read it, or why it cannot be one. Assimp reads a sign
// and digits and stops: a negative index is read as 0, and anything else (a '.', a letter) is
// read as 0 without moving on, so the reader pushes zeros until memory runs out.
struct Index {
  uint64_t value = 0;
  bool negative = false, whole = true;
};
Index read_index(std::string_view token) {
  Index index;
  size_t i = 0;
  if (i < token.size() && (token[i] == '-' || token[i] == '+')) index.negative = token[i++] == '-';
  if (i == token.size()) index.whole = false;
  for (; i < token.size(); ++i) {
    if (token[i] < '0' || token[i] > '9') {
      index.whole = false;
      break;
    }
    index.value =
        index.value > (kNone - 10) / 10 ? kNone - 1 : index.value * 10 + uint64_t(token[i] - '0');
  }
  if (index.negative && index.value == 0) index.negative = false;  // "-0" is 0
  return index;
}

enum class Semantic {
  kInvalid,
  kPosition,
  kTexcoord,
  kNormal,
  kColor,
  kVertex,
  kBitangent,
  kTangent
};

Semantic semantic_of(std::string_view s) {
  if (s == "POSITION") return Semantic::kPosition;
  if (s == "TEXCOORD") return Semantic::kTexcoord;
  if (s == "NORMAL") return Semantic::kNormal;
  if (s == "COLOR") return Semantic::kColor;
  if (s == "VERTEX") return Semantic::kVertex;
  if (s == "BINORMAL" || s == "TEXBINORMAL") return Semantic::kBitangent;
  if (s == "TANGENT" || s == "TEXTANGENT") return Semantic::kTangent;
  return Semantic::kInvalid;
}

struct Array {
  bool numbers = true;  // float_array; IDREF_array and Name_array hold names
  uint64_t count = 0;
  int line = 0;
};

struct Accessor {
  std::string source;  // the <source> it belongs to
  std::string array;   // its source="#..." without '#', or "" when Assimp refuses the reference
  uint64_t count = 0, offset = 0, stride = 1;
  uint64_t params = 0, typed_size = 0;  // typed_size: float4x4 counts 16, other types 1
  int line = 0;
};

struct Input {
  Semantic semantic = Semantic::kInvalid;
  std::string source;  // without '#'
  uint64_t offset = 0;
  int line = 0;
};

struct Mesh {
  std::string id;
  std::string vertices_id;
  std::vector<Input> per_vertex;
  uint64_t largest_vertex_index = 0;
  bool any_vertex_index = false;
};

enum class PrimitiveType {
  kLines,
  kLineStrips,
  kPolygons,
  kPolylist,
  kTriangles,
  kTrifans,
  kTristrips
};

struct Primitive {
  PrimitiveType type = PrimitiveType::kTriangles;
  std::string name;
  uint64_t count = 0;
  std::vector<Input> inputs;
  std::vector<uint64_t> vcount;
  bool vcount_read = false;
  bool inputs_used = false;  // its inputs are in used_inputs_
  int line = 0;
};

struct Node {
  std::string id, name;
  std::vector<int> children;
  std::vector<std::pair<std::string, int>> instances;   // url as written, line
  std::vector<std::pair<std::string, int>> geometries;  // url without '#', line
  int line = 0;
};

struct Controller {
  bool skin = true;
  std::string mesh;          // what Assimp looks the mesh up by
  std::string joint_source;  // <joints><input semantic="JOINT" source="#...">
  int64_t weights = 0;       // <vertex_weights count>
  int64_t joint_offset = 0, weight_offset = 1;
  bool has_weight_inputs = false;
  bool vcount_read = false;
  uint64_t pairs = 0;  // the sum of <vcount>
  uint64_t largest_joint = 0;
  bool any_joint = false;
  int line = 0;
};

enum class Kind : uint8_t {
  kOther,
  kCollada,
  kLibraryGeometries,
  kGeometry,
  kSkipped,
  kMesh,
  kSource,
  kTechnique,
  kAccessor,
  kArray,
  kVertices,
  kPrimitive,
  kVcount,
  kP,
  kLibraryNodes,
  kLibraryScenes,
  kNode,
  kScene,
  kLibraryControllers,
  kController,
  kJoints,
  kWeights,
  kWeightsVcount,
  kWeightsV,
};

struct Frame {
  Kind kind = Kind::kOther;
  int index = -1;      // into the vector its kind names
  int saved = -1;      // the innermost index of its kind before it opened
  bool taken = false;  // a <technique_common>'s first <accessor> was read
};

class ColladaScan : public XmlScan {
 public:
  explicit ColladaScan(std::string_view bytes) : bytes_(bytes.size()) {}

  void open(std::string_view name, const std::vector<XmlAttribute>& attributes) override;
  void text(std::string_view piece) override;
  void close() override;
  // The checks that need the whole file: accessors, inputs, the node graph, skins.
  void finish();

 private:
  std::optional<std::string_view> attribute(const std::vector<XmlAttribute>& attributes,
                                            std::string_view name) const {
    for (const XmlAttribute& a : attributes)
      if (a.name == name) return a.value;
    return std::nullopt;
  }
  // The whole number `name` holds, `fallback` when it is absent; refuses anything else.
  uint64_t number(const std::vector<XmlAttribute>& attributes, std::string_view element,
                  std::string_view name, uint64_t fallback) {
    const auto text = attribute(attributes, name);
    if (!text) return fallback;
    const auto value = whole_number(*text);
    if (!value) {
      stop("<" + std::string(element) + "> at line " + std::to_string(line) + " has " +
           std::string(name) + "=" + quoted(*text) + ", which is no whole number");
      return fallback;
    }
    return *value;
  }
  void stop(const std::string& rule) {
    if (refusal.empty()) refusal = rule;
  }
  const Accessor* accessor_of(const std::string& source) const {
    const auto it = accessors_.find(source);
    return it == accessors_.end() ? nullptr : &accessor_list_[it->second];
  }
  const Array* array_of(const std::string& id) const {
    const auto it = arrays_.find(id);
    return it == arrays_.end() ? nullptr : &it->second;
  }
  Input read_input(const std::vector<XmlAttribute>& attributes, std::string_view element);
  void open_p();
  void index_token(std::string_view token);
  void vcount_token(std::string_view token);
  void weights_token(std::string_view token, bool v);
  void close_p();
  std::string node_name(int n) const;
  int resolve_instance(const std::string& url, int root);
  void check_node_graph(int root);
  void check_skin(const Controller& controller, const std::string& id, int line);

  const size_t bytes_;
  std::vector<Frame> frames_;
  // The innermost open element of each kind (an index into its vector), -1 outside.
  int mesh_ = -1, source_ = -1, primitive_ = -1, controller_ = -1, accessor_ = -1;
  std::string array_id_;  // the array whose values are being counted
  ValueCounter values_;
  Tokens tokens_;

  std::unordered_map<std::string, Array> arrays_;
  std::vector<std::string> source_ids_;
  std::unordered_map<std::string, int> source_lines_;
  std::vector<Accessor> accessor_list_;                // in the file's order
  std::unordered_map<std::string, size_t> accessors_;  // by the id of their <source>
  std::vector<Mesh> meshes_;
  std::unordered_map<std::string, int> mesh_library_;  // the first <geometry> of an id
  std::vector<Primitive> primitives_;
  std::vector<Input> used_inputs_;  // inputs a <p> reads through

  // The <p> being read.
  struct Slot {
    uint64_t offset = 0;     // of the inputs it bounds
    uint64_t bound = kNone;  // indices must stay below
    std::string source;      // whose count the bound is
  };
  std::vector<Slot> slots_;  // one per offset that has an input with a known accessor
  uint64_t p_offsets_ = 1, p_indices_ = 0, p_vertex_slot_ = kNone;
  bool p_active_ = false;
  int p_line_ = 0;

  std::vector<Node> nodes_;
  std::unordered_map<std::string, int> node_library_;  // library nodes and visual scenes
  int root_ = -1;
  bool scene_read_ = false;
  std::unordered_map<std::string, int> scene_tree_;  // names and ids of the scene's tree
  bool scene_tree_built_ = false;

  std::vector<Controller> controllers_;
  std::unordered_map<std::string, int> controller_library_;
  uint64_t weights_tokens_ = 0;
};

Input ColladaScan::read_input(const std::vector<XmlAttribute>& attributes,
                              std::string_view element) {
  Input input;
  input.line = line;
  input.semantic = semantic_of(attribute(attributes, "semantic").value_or(""));
  const std::string_view source = attribute(attributes, "source").value_or("");
  // Assimp refuses a source that does not begin with '#' itself.
  if (source.empty() || source[0] != '#')
    input.semantic = Semantic::kInvalid;
  else
    input.source = std::string(source.substr(1));
  input.offset = number(attributes, element, "offset", 0);
  return input;
}

void ColladaScan::open(std::string_view name, const std::vector<XmlAttribute>& attributes) {
  // Assimp reserves memory for a count before reading the values: none may exceed the file.
  if (const auto count = attribute(attributes, "count")) {
    if (const auto n = whole_number(*count); n && *n > bytes_)
      stop("a count of " +
           (*n > bytes_ * 10 ? "more than " + std::to_string(bytes_) : std::to_string(*n)) +
           " values is larger than the file");
  }
  const Kind parent = frames_.empty() ? Kind::kOther : frames_.back().kind;
  Frame frame;
  if (parent == Kind::kSkipped || (frames_.empty() && name != "COLLADA")) {
    frame.kind = Kind::kSkipped;  // Assimp reads nothing here
    frames_.push_back(frame);
    return;
  }
  if (frames_.empty()) {
    frame.kind = Kind::kCollada;
  } else if (parent == Kind::kCollada) {
    if (name == "library_geometries")
      frame.kind = Kind::kLibraryGeometries;
    else if (name == "library_visual_scenes")
      frame.kind = Kind::kLibraryScenes;
    else if (name == "library_nodes")
      frame.kind = Kind::kLibraryNodes;
    else if (name == "library_controllers")
      frame.kind = Kind::kLibraryControllers;
    else if (name == "scene")
      frame.kind = Kind::kScene;
  } else if (parent == Kind::kLibraryGeometries && name == "geometry") {
    // Assimp reads the first geometry of an id and skips the others unread.
    const std::string id(attribute(attributes, "id").value_or(""));
    if (mesh_library_.count(id)) {
      frame.kind = Kind::kSkipped;
    } else {
      frame.kind = Kind::kGeometry;
      frame.index = int(meshes_.size());
      mesh_library_[id] = frame.index;
      meshes_.push_back(Mesh{id, "", {}, 0, false});
    }
  } else if (parent == Kind::kGeometry && name == "mesh") {
    frame.kind = Kind::kMesh;
    frame.index = frames_.back().index;
    frame.saved = mesh_;
    mesh_ = frame.index;
  } else if (parent == Kind::kLibraryNodes && name == "node") {
    frame.kind = Kind::kNode;
    frame.index = int(nodes_.size());
    nodes_.push_back(Node{std::string(attribute(attributes, "id").value_or("")),
                          std::string(attribute(attributes, "name").value_or("")),
                          {},
                          {},
                          {},
                          line});
    node_library_[nodes_.back().id] = frame.index;
  } else if (parent == Kind::kLibraryScenes && name == "visual_scene") {
    frame.kind = Kind::kNode;
    frame.index = int(nodes_.size());
    nodes_.push_back(Node{std::string(attribute(attributes, "id").value_or("")),
                          std::string(attribute(attributes, "name").value_or("Scene")),
                          {},
                          {},
                          {},
                          line});
    node_library_[nodes_.back().id] = frame.index;
  } else if (parent == Kind::kNode) {
    Node& owner = nodes_[size_t(frames_.back().index)];
    if (name == "node") {
      frame.kind = Kind::kNode;
      frame.index = int(nodes_.size());
      owner.children.push_back(frame.index);
      nodes_.push_back(Node{std::string(attribute(attributes, "id").value_or("")),
                            std::string(attribute(attributes, "name").value_or("")),
                            {},
                            {},
                            {},
                            line});
    } else if (name == "instance_node") {
      if (const auto url = attribute(attributes, "url"))
        owner.instances.emplace_back(std::string(*url), line);
    } else if (name == "instance_geometry" || name == "instance_controller") {
      const std::string_view url = attribute(attributes, "url").value_or("");
      if (!url.empty() && url[0] == '#')  // else Assimp refuses the file itself
        owner.geometries.emplace_back(std::string(url.substr(1)), line);
    }
  } else if (parent == Kind::kScene && name == "instance_visual_scene") {
    // Assimp takes the scene its library holds under that id at this point of the file.
    const std::string_view url = attribute(attributes, "url").value_or("");
    if (!scene_read_ && !url.empty() && url[0] == '#') {
      const auto it = node_library_.find(std::string(url.substr(1)));
      if (it != node_library_.end()) root_ = it->second;
    } else {
      root_ = -1;  // a second scene or a bad reference: Assimp refuses the file itself
    }
    scene_read_ = true;
  } else if (parent == Kind::kLibraryControllers && name == "controller") {
    if (const auto id = attribute(attributes, "id")) {
      frame.kind = Kind::kController;
      frame.index = int(controllers_.size());
      frame.saved = controller_;
      controller_ = frame.index;
      controllers_.push_back(Controller{});
      controllers_.back().line = line;
      controller_library_[std::string(*id)] = frame.index;
    }
  }

  // Inside a mesh (at any depth, as Assimp walks it): vertices, primitives and their parts.
  if (frame.kind == Kind::kOther && mesh_ >= 0) {
    Mesh& mesh = meshes_[size_t(mesh_)];
    static const std::map<std::string_view, PrimitiveType> kPrimitives = {
        {"lines", PrimitiveType::kLines},         {"linestrips", PrimitiveType::kLineStrips},
        {"polygons", PrimitiveType::kPolygons},   {"polylist", PrimitiveType::kPolylist},
        {"triangles", PrimitiveType::kTriangles}, {"trifans", PrimitiveType::kTrifans},
        {"tristrips", PrimitiveType::kTristrips}};
    if (name == "vertices") {
      frame.kind = Kind::kVertices;
      if (const auto id = attribute(attributes, "id")) mesh.vertices_id = std::string(*id);
    } else if (parent == Kind::kVertices && name == "input") {
      const Input input = read_input(attributes, name);
      if (input.semantic != Semantic::kInvalid) mesh.per_vertex.push_back(input);
    } else if (const auto type = kPrimitives.find(name); type != kPrimitives.end()) {
      frame.kind = Kind::kPrimitive;
      frame.index = int(primitives_.size());
      frame.saved = primitive_;
      primitive_ = frame.index;
      Primitive primitive;
      primitive.type = type->second;
      primitive.name = std::string(name);
      primitive.count = number(attributes, name, "count", 0);
      primitive.line = line;
      primitives_.push_back(std::move(primitive));
    } else if (primitive_ >= 0 && name == "input") {
      const Input input = read_input(attributes, name);
      if (input.semantic != Semantic::kInvalid)
        primitives_[size_t(primitive_)].inputs.push_back(input);
    } else if (primitive_ >= 0 && name == "vcount") {
      frame.kind = Kind::kVcount;
      primitives_[size_t(primitive_)].vcount.clear();
      primitives_[size_t(primitive_)].vcount_read = true;
    } else if (primitive_ >= 0 && name == "p") {
      frame.kind = Kind::kP;
    }
  }

  // Inside a controller (at any depth, as Assimp walks it).
  if (frame.kind == Kind::kOther && controller_ >= 0) {
    Controller& controller = controllers_[size_t(controller_)];
    if (name == "skin") {
      controller.skin = true;
      const std::string source(attribute(attributes, "source").value_or(""));
      if (!source.empty()) controller.mesh = source.substr(1);
    } else if (name == "morph") {
      controller.skin = false;
      controller.mesh = std::string(attribute(attributes, "source").value_or(""));
    } else if (name == "joints") {
      frame.kind = Kind::kJoints;
    } else if (parent == Kind::kJoints && name == "input") {
      const std::string_view source = attribute(attributes, "source").value_or("");
      if (attribute(attributes, "semantic").value_or("") == "JOINT" && !source.empty() &&
          source[0] == '#')
        controller.joint_source = std::string(source.substr(1));
    } else if (name == "vertex_weights") {
      frame.kind = Kind::kWeights;
      controller.weights =
          int64_t(std::min<uint64_t>(number(attributes, name, "count", 0), bytes_));
    } else if (parent == Kind::kWeights && name == "input") {
      const std::string_view semantic = attribute(attributes, "semantic").value_or("");
      const int64_t value =
          int64_t(std::min<uint64_t>(number(attributes, name, "offset", 0), bytes_));
      if (semantic == "JOINT") controller.joint_offset = value;
      if (semantic == "WEIGHT") controller.weight_offset = value;
      controller.has_weight_inputs = true;
    } else if (parent == Kind::kWeights && name == "vcount" && controller.weights > 0) {
      frame.kind = Kind::kWeightsVcount;
      controller.vcount_read = true;
      controller.pairs = 0;
      weights_tokens_ = 0;
    } else if (parent == Kind::kWeights && name == "v" && controller.weights > 0) {
      frame.kind = Kind::kWeightsV;
      weights_tokens_ = 0;
    }
  }

  // Sources, accessors and arrays, wherever Assimp may read them.
  if (frame.kind == Kind::kOther) {
    if (name == "source") {
      frame.kind = Kind::kSource;
      frame.index = int(source_ids_.size());
      frame.saved = source_;
      source_ = frame.index;
      const std::string id(attribute(attributes, "id").value_or(""));
      if (!id.empty() && !source_lines_.emplace(id, line).second)
        stop("two <source>s have the id '" + id + "' (lines " + std::to_string(source_lines_[id]) +
             " and " + std::to_string(line) + "); Assimp would read one through the other");
      source_ids_.push_back(id);
    } else if (name == "technique_common" && source_ >= 0) {
      frame.kind = Kind::kTechnique;
    } else if (parent == Kind::kTechnique && name == "accessor" && !frames_.back().taken) {
      frames_.back().taken = true;
      frame.kind = Kind::kAccessor;
      frame.saved = accessor_;
      Accessor accessor;
      accessor.source = source_ids_[size_t(source_)];
      const std::string_view array = attribute(attributes, "source").value_or("");
      if (!array.empty() && array[0] == '#')
        accessor.array = std::string(array.substr(1));
      else
        accessor.array.clear();
      // Assimp reads count as a signed int: "-1" became 2^64 - 1 and disabled its index check.
      accessor.count = number(attributes, name, "count", 0);
      accessor.offset = number(attributes, name, "offset", 0);
      accessor.stride = number(attributes, name, "stride", 1);
      accessor.line = line;
      accessor_ = int(accessor_list_.size());
      accessors_[accessor.source] = accessor_list_.size();
      accessor_list_.push_back(accessor);
    } else if (accessor_ >= 0 && name == "param") {
      Accessor& accessor = accessor_list_[size_t(accessor_)];
      ++accessor.params;
      if (const auto type = attribute(attributes, "type"))
        accessor.typed_size += *type == "float4x4" ? 16 : 1;
    } else if (name == "float_array" || name == "IDREF_array" || name == "Name_array") {
      frame.kind = Kind::kArray;
      const std::string id(attribute(attributes, "id").value_or(""));
      Array array;
      array.numbers = name == "float_array";
      array.count = number(attributes, name, "count", 0);
      array.line = line;
      if (!id.empty() && arrays_.count(id))
        stop("two arrays have the id '" + id + "' (lines " + std::to_string(arrays_[id].line) +
             " and " + std::to_string(line) + "); Assimp would read one through the other");
      arrays_[id] = array;
      array_id_ = id;
      values_ = ValueCounter();
    }
  }
  if (frame.kind == Kind::kVcount || frame.kind == Kind::kP || frame.kind == Kind::kWeightsVcount ||
      frame.kind == Kind::kWeightsV)
    tokens_ = Tokens();
  if (frame.kind == Kind::kP) open_p();
  frames_.push_back(frame);
}

void ColladaScan::open_p() {
  Primitive& primitive = primitives_[size_t(primitive_)];
  p_active_ = primitive.count > 0;  // Assimp reads no indices for a count of 0
  p_indices_ = 0;
  p_line_ = line;
  if (!p_active_) return;
  const Mesh& mesh = meshes_[size_t(mesh_)];
  if (primitive.type == PrimitiveType::kPolylist &&
      (!primitive.vcount_read || primitive.vcount.size() < primitive.count))
    stop("the <polylist> at line " + std::to_string(primitive.line) + " has no <vcount> of its " +
         std::to_string(primitive.count) +
         " polygons before its <p>; Assimp reads the sizes from beyond its list");
  // Indices per corner: one more than the largest input offset.
  p_offsets_ = 1;
  p_vertex_slot_ = kNone;
  for (const Input& input : primitive.inputs) {
    p_offsets_ = std::max(p_offsets_, saturating_sum(input.offset, 1));
    if (input.semantic == Semantic::kVertex) p_vertex_slot_ = input.offset;
  }
  // The bound of each slot: the counts of the accessors its inputs read, as Assimp resolves
  // them now (a source that comes later is an error Assimp reports).
  slots_.clear();
  auto bound = [&](uint64_t offset, const std::string& source) {
    const Accessor* accessor = accessor_of(source);
    if (!accessor) return;
    auto slot = std::find_if(slots_.begin(), slots_.end(),
                             [&](const Slot& s) { return s.offset == offset; });
    if (slot == slots_.end()) slot = slots_.insert(slots_.end(), Slot{offset, kNone, ""});
    if (accessor->count < slot->bound) *slot = Slot{offset, accessor->count, source};
  };
  for (const Input& input : primitive.inputs) {
    if (input.semantic == Semantic::kVertex) {
      for (const Input& per_vertex : mesh.per_vertex) bound(input.offset, per_vertex.source);
    } else {
      bound(input.offset, input.source);
    }
  }
}

void ColladaScan::index_token(std::string_view token) {
  const Index index = read_index(token);
  const uint64_t slot = p_indices_ % p_offsets_;
  ++p_indices_;
  if (!index.whole) {
    stop("the <p> at line " + std::to_string(p_line_) + " holds " + quoted(token) +
         " where an index belongs; Assimp would read it as 0 again and again without end");
    return;
  }
  if (index.negative) {
    stop("the <p> at line " + std::to_string(p_line_) + " holds the negative index " +
         std::string(token) + ", which Assimp reads as 0");
    return;
  }
  for (const Slot& bound : slots_) {
    if (bound.offset != slot || index.value < bound.bound) continue;
    stop("the <p> at line " + std::to_string(p_line_) + " holds the index " +
         std::to_string(index.value) + ", beyond the " + std::to_string(bound.bound) +
         " values of source '" + bound.source + "'");
    return;
  }
  if (slot == p_vertex_slot_) {
    Mesh& mesh = meshes_[size_t(mesh_)];
    mesh.largest_vertex_index = std::max(mesh.largest_vertex_index, index.value);
    mesh.any_vertex_index = true;
  }
}

void ColladaScan::close_p() {
  if (!p_active_) return;
  const Primitive& primitive = primitives_[size_t(primitive_)];
  const Mesh& mesh = meshes_[size_t(mesh_)];
  const std::string where =
      "the <" + primitive.name + "> at line " + std::to_string(primitive.line);
  // What Assimp reserves and expects: count x corners x indices per corner.
  uint64_t corners = 0;
  if (primitive.type == PrimitiveType::kTriangles) corners = saturating_product(primitive.count, 3);
  if (primitive.type == PrimitiveType::kLines) corners = saturating_product(primitive.count, 2);
  if (primitive.type == PrimitiveType::kPolylist)
    for (size_t k = 0; k < primitive.count && k < primitive.vcount.size(); ++k)
      corners = saturating_sum(corners, primitive.vcount[k]);
  const uint64_t expected = saturating_product(corners, p_offsets_);
  if (expected > bytes_) {
    stop(where + " declares " + (expected == kNone ? "more than 2^64" : std::to_string(expected)) +
         " indices, more than the file's size");
    return;
  }
  if ((primitive.type == PrimitiveType::kTriangles || primitive.type == PrimitiveType::kPolylist) &&
      p_indices_ != expected) {
    stop(where + " declares " + std::to_string(corners) + " corners of " +
         std::to_string(p_offsets_) + (p_offsets_ == 1 ? " index" : " indices") + " each (" +
         std::to_string(expected) + "), but its <p> holds " + std::to_string(p_indices_));
    return;
  }
  if (p_indices_ == 0) return;
  if (p_vertex_slot_ == kNone) {
    stop(where + " has no VERTEX input; Assimp would read the index before its list");
    return;
  }
  // Assimp takes one position per POSITION input and corner: with none or two, the corners
  // and the positions of the mesh no longer match.
  int positions = 0;
  for (const Input& input : mesh.per_vertex) positions += input.semantic == Semantic::kPosition;
  for (const Input& input : primitive.inputs) positions += input.semantic == Semantic::kPosition;
  if (positions != 1) {
    stop(where + " has " + std::to_string(positions) +
         " POSITION inputs (through <vertices> and its own); it needs exactly one");
    return;
  }
  if (primitive.inputs_used) return;
  primitives_[size_t(primitive_)].inputs_used = true;
  for (const Input& input : mesh.per_vertex) used_inputs_.push_back(input);
  for (const Input& input : primitive.inputs)
    if (input.semantic != Semantic::kVertex) used_inputs_.push_back(input);
}

void ColladaScan::text(std::string_view piece) {
  if (frames_.empty() || !refusal.empty()) return;
  switch (frames_.back().kind) {
    case Kind::kArray:
      values_.feed(piece);
      break;
    case Kind::kVcount:
      tokens_.feed(piece, [&](std::string_view token) { vcount_token(token); });
      break;
    case Kind::kP:
      if (p_active_) tokens_.feed(piece, [&](std::string_view token) { index_token(token); });
      break;
    case Kind::kWeightsVcount:
    case Kind::kWeightsV: {
      const bool v = frames_.back().kind == Kind::kWeightsV;
      tokens_.feed(piece, [&](std::string_view token) { weights_token(token, v); });
      break;
    }
    default:
      break;
  }
}

void ColladaScan::vcount_token(std::string_view token) {
  Primitive& primitive = primitives_[size_t(primitive_)];
  const Index value = read_index(token);
  if (!value.whole || value.negative)
    stop("the <vcount> of the <" + primitive.name + "> at line " + std::to_string(primitive.line) +
         " holds " + quoted(token) + ", which is no polygon size");
  else if (primitive.vcount.size() < primitive.count)  // Assimp reads `count` sizes
    primitive.vcount.push_back(value.value);
}

// A number of a skin's <vcount> (weights per vertex) or <v> (joint, weight pairs).
void ColladaScan::weights_token(std::string_view token, bool v) {
  Controller& controller = controllers_[size_t(controller_)];
  const Index value = read_index(token);
  const uint64_t k = weights_tokens_++;
  if (!v) {
    if (k >= uint64_t(controller.weights)) return;  // Assimp reads `count` sizes
    if (!value.whole || value.negative)
      stop("the <vcount> of the skin at line " + std::to_string(controller.line) + " holds " +
           quoted(token) + ", which is no number of weights");
    else
      controller.pairs = saturating_sum(controller.pairs, value.value);
    return;
  }
  if (k % 2 != 0 || k / 2 >= controller.pairs) return;  // joint indices come first
  if (!value.whole || value.negative) {
    stop("the <v> of the skin at line " + std::to_string(controller.line) + " holds " +
         quoted(token) + " where a joint index belongs");
    return;
  }
  controller.largest_joint = std::max(controller.largest_joint, value.value);
  controller.any_joint = true;
}

void ColladaScan::close() {
  if (frames_.empty()) return;
  const Frame frame = frames_.back();
  frames_.pop_back();
  switch (frame.kind) {
    case Kind::kMesh:
      mesh_ = frame.saved;
      break;
    case Kind::kSource:
      source_ = frame.saved;
      break;
    case Kind::kAccessor:
      accessor_ = frame.saved;
      break;
    case Kind::kPrimitive:
      primitive_ = frame.saved;
      break;
    case Kind::kController:
      controller_ = frame.saved;
      break;
    case Kind::kArray: {
      const Array& array = arrays_[array_id_];
      if (values_.count() < array.count)
        stop("the array " +
             (array_id_.empty() ? "at line " + std::to_string(array.line) : "'" + array_id_ + "'") +
             " declares " + std::to_string(array.count) + " values but holds " +
             std::to_string(values_.count()));
      break;
    }
    case Kind::kVcount:
      tokens_.finish([&](std::string_view token) { vcount_token(token); });
      break;
    case Kind::kP:
      if (p_active_) tokens_.finish([&](std::string_view token) { index_token(token); });
      if (refusal.empty()) close_p();
      p_active_ = false;
      break;
    case Kind::kWeightsVcount:
    case Kind::kWeightsV:
      tokens_.finish(
          [&](std::string_view token) { weights_token(token, frame.kind == Kind::kWeightsV); });
      break;
    default:
      break;
  }
}

std::string ColladaScan::node_name(int n) const {
  const Node& node = nodes_[size_t(n)];
  if (!node.id.empty()) return "'" + node.id + "'";
  if (!node.name.empty()) return "'" + node.name + "'";
  return "at line " + std::to_string(node.line);
}

// The node an <instance_node url> names as Assimp finds it: the library of nodes and visual
// scenes by id, else the first node of the scene's tree (children, not instances, in document
// order) whose name or id it is; -1 when none. Assimp leaves an instance it cannot find out
// without a word.
int ColladaScan::resolve_instance(const std::string& url, int root) {
  if (url.empty() || url[0] != '#') return -1;  // another file: Assimp does not read it
  const std::string key = url.substr(1);
  if (const auto it = node_library_.find(key); it != node_library_.end()) return it->second;
  if (!scene_tree_built_) {
    scene_tree_built_ = true;
    std::vector<int> stack = {root};
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      scene_tree_.emplace(nodes_[size_t(n)].name, n);  // the first in document order stays
      scene_tree_.emplace(nodes_[size_t(n)].id, n);
      const auto& children = nodes_[size_t(n)].children;
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
    }
  }
  const auto it = scene_tree_.find(key);
  return it == scene_tree_.end() ? -1 : it->second;
}

void ColladaScan::check_node_graph(int root) {
  // The nodes Assimp builds from the scene: its child nodes and resolved instances, breadth
  // first; reached[k] is graph node k.
  std::vector<int> graph_index(nodes_.size(), -1);
  std::vector<int> reached = {root};
  graph_index[size_t(root)] = 0;
  std::vector<std::vector<size_t>> children;
  for (size_t k = 0; k < reached.size(); ++k) {
    const int v = reached[k];
    std::vector<int> targets = nodes_[size_t(v)].children;
    for (const auto& [url, line_of] : nodes_[size_t(v)].instances) {
      const int target = resolve_instance(url, root);
      if (target < 0) {
        stop("node " + node_name(v) + " instances " + quoted(url) + " at line " +
             std::to_string(line_of) +
             ", which names no node of this file; Assimp would leave it out");
        return;
      }
      targets.push_back(target);
    }
    std::vector<size_t> list;
    for (const int t : targets) {
      if (graph_index[size_t(t)] < 0) {
        graph_index[size_t(t)] = int(reached.size());
        reached.push_back(t);
      }
      list.push_back(size_t(graph_index[size_t(t)]));
    }
    children.push_back(std::move(list));
  }
  const std::string problem =
      node_graph_problem(children, [&](size_t k) { return "node " + node_name(reached[k]); });
  if (!problem.empty()) {
    stop(problem);
    return;
  }
  // Each geometry or controller a node of the scene instances must exist: Assimp skips the
  // ones it cannot find without a word, and its skin code indexes with the file's numbers.
  for (const int v : reached) {
    for (const auto& [id, line_of] : nodes_[size_t(v)].geometries) {
      if (mesh_library_.count(id)) continue;
      const auto controller = controller_library_.find(id);
      if (controller != controller_library_.end() &&
          mesh_library_.count(controllers_[size_t(controller->second)].mesh)) {
        check_skin(controllers_[size_t(controller->second)], id, line_of);
        if (!refusal.empty()) return;
        continue;
      }
      stop("node " + node_name(v) + " instances '#" + id + "' at line " + std::to_string(line_of) +
           ", which names no geometry of this file; Assimp would leave it out");
      return;
    }
  }
}

void ColladaScan::check_skin(const Controller& controller, const std::string& id, int line_of) {
  if (!controller.skin || !controller.has_weight_inputs || controller.joint_offset != 0 ||
      controller.weight_offset != 1 || controller.weights < 0)
    return;  // Assimp refuses these itself
  const Mesh& mesh = meshes_[size_t(mesh_library_.at(controller.mesh))];
  // Assimp looks each corner's vertex up in the weights' list: it must be there.
  if (mesh.any_vertex_index && mesh.largest_vertex_index >= uint64_t(controller.weights)) {
    stop("skin '" + id + "' (instanced at line " + std::to_string(line_of) + ") weighs " +
         std::to_string(controller.weights) + " vertices, but its mesh '" + mesh.id +
         "' uses vertex " + std::to_string(mesh.largest_vertex_index));
    return;
  }
  // ... and writes each weight into the list of its joint.
  const Accessor* names = accessor_of(controller.joint_source);
  const Array* joints = names ? array_of(names->array) : nullptr;
  if (joints && controller.any_joint && controller.largest_joint >= joints->count)
    stop("skin '" + id + "' weighs vertices by joint " + std::to_string(controller.largest_joint) +
         ", but it has " + std::to_string(joints->count) + " joints");
}

void ColladaScan::finish() {
  if (!refusal.empty()) return;
  // Accessors: Assimp reads value offset + index * stride + param of the array it names,
  // trusting that every one of them is there.
  for (const Accessor& accessor : accessor_list_) {
    if (accessor.array.empty()) continue;  // Assimp refuses the reference itself
    const std::string name = "the accessor of source '" + accessor.source + "' (line " +
                             std::to_string(accessor.line) + ")";
    const uint64_t width = std::max(accessor.params, accessor.typed_size);
    if (accessor.stride < width) {
      stop(name + " has a stride of " + std::to_string(accessor.stride) + ", smaller than its " +
           std::to_string(width) + " values per element");
      return;
    }
    const Array* array = array_of(accessor.array);
    if (!array || accessor.count == 0) continue;
    const uint64_t last = saturating_sum(
        saturating_sum(accessor.offset, saturating_product(accessor.count - 1, accessor.stride)),
        std::max<uint64_t>(width, 1));
    if (last > array->count) {
      stop(name + " reads " + (last == kNone ? "beyond 2^64" : std::to_string(last)) +
           " values (offset " + std::to_string(accessor.offset) + ", " +
           std::to_string(accessor.count) + " elements of stride " +
           std::to_string(accessor.stride) + "), but its array '" + accessor.array + "' has " +
           std::to_string(array->count));
      return;
    }
  }
  // Inputs a mesh reads: numbers (Assimp reads the values of a name array from an empty list),
  // and at most 4 per color (Assimp writes each into a color of 4).
  for (const Input& input : used_inputs_) {
    const Accessor* accessor = accessor_of(input.source);
    const Array* array = accessor ? array_of(accessor->array) : nullptr;
    if (!array) continue;  // Assimp reports what it cannot find
    if (!array->numbers) {
      stop("the input at line " + std::to_string(input.line) + " reads source '" + input.source +
           "', whose array holds names, not numbers");
      return;
    }
    if (input.semantic == Semantic::kColor && accessor->typed_size > 4) {
      stop("the COLOR input at line " + std::to_string(input.line) + " reads source '" +
           input.source + "', whose colors have " + std::to_string(accessor->typed_size) +
           " values (at most 4)");
      return;
    }
  }
  if (root_ >= 0) check_node_graph(root_);
}

}  // namespace

void check_collada(std::string_view bytes, const std::string& path) {
  ColladaScan scan(bytes);
  size_t at = 0;
  const std::string rule = scan_xml(
      [&](char* buffer, int length) {
        const size_t n = std::min(bytes.size() - at, size_t(length));
        std::memcpy(buffer, bytes.data() + at, n);
        at += n;
        return int(n);
      },
      scan);
  if (!rule.empty()) refuse(path, rule);
  scan.finish();
  if (!scan.refusal.empty()) refuse(path, scan.refusal);
}

}  // namespace primo::detail
