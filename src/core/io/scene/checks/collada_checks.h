#pragma once
// What a COLLADA file may ask of Assimp 5.2's reader, checked on its XML before Assimp reads it
// (docs/mesh-io.md, "Scene formats"). Assimp's COLLADA reader trusts the file's numbers and
// references: a node that instances itself or a chain of 7,000 nested nodes overflowed its
// stack, 30 library nodes each instancing the next twice asked for 2^30 nodes, an accessor
// offset of 4e9 read far outside its array, and an accessor one vertex longer than its array
// made Assimp invent a vertex from the bytes after it without a word. Each such structure is
// refused in one line naming the rule.
//
// The XML is read once, as a stream (xml_scan.h), with libxml2's own limits in force.

#include <cstddef>
#include <string>
#include <string_view>

namespace primo::detail {

// Throws Error "<path>: cannot read: not a COLLADA file PriMo accepts (<rule>)" when `bytes`
// is XML libxml2 refuses or holds a structure that Assimp 5.2's COLLADA reader mishandles:
// - a count="N" larger than the file (Assimp reserves memory for N values first);
// - a DTD that declares entities (no COLLADA file has one);
// - a node graph (the visual scene's child <node>s and <instance_node url="#id"> references)
//   with a cycle, deeper than kMaxSceneNodeDepth or expanding to more than
//   kMaxSceneNodeInstances instances (node_graph_limits.h), or instancing a node, geometry or
//   controller the file does not have (Assimp leaves it out without a word);
// - an array holding fewer values than its count, an accessor whose stride is smaller than
//   its params or whose last value lies beyond its array, duplicate source or array ids;
// - <p> indices that are no whole numbers, negative (Assimp reads them as 0), beyond the
//   accessor of their input, or a <p> whose length does not match its primitive's count and
//   inputs; a primitive without a VERTEX input or without exactly one POSITION; a <polylist>
//   whose <vcount> is missing or short; polygon holes (<ph>, which Assimp drops); a COLOR
//   input of more than 4 values, an input reading a name array;
// - a skin whose weights cover fewer vertices than its mesh uses or name a joint it lacks.
// Only the bytes are read; files the scene refers to are not.
void check_collada(std::string_view bytes, const std::string& path);

}  // namespace primo::detail
