#pragma once
// What a 3MF file may ask of Assimp 5.2's reader (code/AssetLib/3MF: D3MFOpcPackage reads the
// zip, XmlSerializer the model), checked on its bytes before Assimp reads it (docs/mesh-io.md,
// "Scene formats"). Assimp inflates each zip entry it opens into memory of the size the entry
// declares, follows <component> references without a cycle check (an object that is its own
// component overflowed its stack), and reads triangles, property indices and transforms as the
// file gives them: a triangle without v3 became one with vertex 0, and one naming a vertex the
// object lacks was dropped without a word. Each such structure is refused in one line naming
// the rule.

#include <cstdint>
#include <string>
#include <string_view>

namespace primo::detail {

// An entry of the zip may inflate to at most this many times its compressed size (and 1 MiB
// whatever its size)...
constexpr uint64_t kMax3mfInflationRatio = 1000;
// ... to at most this many bytes, and all entries together to at most kMax3mfZipBytes.
constexpr uint64_t kMax3mfEntryBytes = uint64_t(1) << 30;
constexpr uint64_t kMax3mfZipBytes = uint64_t(2) << 30;

// Throws Error "<path>: cannot read: not a 3MF file PriMo accepts (<rule>)" when the zip in
// `bytes` has an entry that would inflate beyond the limits above, no model part (the start
// part _rels/.rels names, as Assimp finds it), or a model part that libxml2 refuses (see
// scan_xml in collada_checks.h) or that holds:
// - a <component> or build <item> naming an object the file does not have (Assimp leaves it
//   out); components that form a cycle, nest deeper than kMaxSceneNodeDepth below the build or
//   expand it to more than kMaxSceneNodeInstances objects (node_graph_limits.h); a component
//   or item that refers to another model part (p:path), which Assimp does not read;
// - a <triangle> without v1, v2 or v3 or naming a vertex its mesh lacks, a <vertex> without
//   numeric x, y and z, a mesh with more than one <vertices> or <triangles> or its triangles
//   before its vertices (Assimp keeps the last list, and reads them in order);
// - a property index (p1, p2, p3, pindex) beyond its base materials or texture coordinates, a
//   transform that is not 12 numbers, two resources with one id, an id that is no number.
// Bytes that are no zip minizip can open are left to Assimp (the same minizip), which says so.
void check_3mf(std::string_view bytes, const std::string& path);

}  // namespace primo::detail
