// The checks of COLLADA and 3MF files before Assimp reads them (collada_checks.h,
// threemf_checks.h; docs/mesh-io.md, "Scene formats"). Each rule is shown on a file that
// breaks it, read from the file and from memory (the fuzz targets' path), and refused in one
// line naming the rule; without its check each of these files crashed Assimp, exhausted
// memory, or was read wrong without a word. Sound files, the shipped samples included, still
// load with the right faces.

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "../../../src/core/io/scene/checks/collada_checks.h"
#include "../../../src/core/io/scene/checks/threemf_checks.h"
#include "primo/util/error.h"
#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

using primo::test::expect_refused_from_file_and_bytes;
using primo::test::read_text;
using primo::test::source_path;
using primo::test::temp_dir;
using primo::test::write_text;

namespace primo {
namespace {

struct Bad {
  std::string name, bytes, needle;
};

void expect_each_refused(const std::vector<Bad>& bad) {
  const std::string dir = temp_dir();
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.name);
    expect_refused_from_file_and_bytes(dir + "/" + b.name, b.bytes, b.needle);
  }
}

// `text` with the first `from` replaced by `to` (a test failure when `from` is missing).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string repeated(const std::string& text, int times) {
  std::string out;
  for (int k = 0; k < times; ++k) out += text;
  return out;
}

// --- COLLADA
// --------------------------------------------------------------------------------------

// assimp's test cube (6 quads, 8 positions, 24 normals; its node 'Box' instances the geometry).
std::string cube() { return read_text(source_path("tests/data/scenes/cube_emptyTags.dae")); }

// The cube with `libraries` before its visual scene and the Box node's geometry instance
// replaced by `box`.
std::string cube_with(const std::string& libraries, const std::string& box) {
  std::string text =
      replaced(cube(), "<library_visual_scenes>", libraries + "<library_visual_scenes>");
  const size_t from = text.find("<instance_geometry url=\"#box-lib\">");
  const std::string end = "</instance_geometry>";
  const size_t to = text.find(end, from);
  EXPECT_NE(from, std::string::npos);
  return text.replace(from, to + end.size() - from, box);
}

// Library nodes n0 ... n<count-1>, each instancing the next `copies` times; the last instances
// the cube's geometry.
std::string chain(int count, int copies) {
  std::string nodes = "<library_nodes>";
  for (int k = 0; k < count; ++k) {
    nodes += "<node id=\"n" + std::to_string(k) + "\">";
    if (k + 1 < count)
      nodes += repeated("<instance_node url=\"#n" + std::to_string(k + 1) + "\"/>", copies);
    else
      nodes += "<instance_geometry url=\"#box-lib\"/>";
    nodes += "</node>";
  }
  return nodes + "</library_nodes>";
}

// A skin of the cube: one joint ('Box'), `weights` vertices weighed, joint `joint` for each.
std::string skinned_cube(int weights, int joint) {
  std::string pairs;
  for (int k = 0; k < weights; ++k) pairs += std::to_string(joint) + " 0 ";
  const std::string controllers =
      R"(<library_controllers><controller id="skin"><skin source="#box-lib">
      <bind_shape_matrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</bind_shape_matrix>
      <source id="skin-joints"><Name_array id="skin-joints-array" count="1">Box</Name_array>
        <technique_common><accessor source="#skin-joints-array" count="1" stride="1">
          <param name="JOINT" type="name"/></accessor></technique_common></source>
      <source id="skin-bind"><float_array id="skin-bind-array" count="16">1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</float_array>
        <technique_common><accessor source="#skin-bind-array" count="1" stride="16">
          <param name="TRANSFORM" type="float4x4"/></accessor></technique_common></source>
      <source id="skin-weights"><float_array id="skin-weights-array" count="1">1</float_array>
        <technique_common><accessor source="#skin-weights-array" count="1" stride="1">
          <param name="WEIGHT" type="float"/></accessor></technique_common></source>
      <joints><input semantic="JOINT" source="#skin-joints"/>
        <input semantic="INV_BIND_MATRIX" source="#skin-bind"/></joints>
      <vertex_weights count=")" +
      std::to_string(weights) + R"(">
        <input semantic="JOINT" source="#skin-joints" offset="0"/>
        <input semantic="WEIGHT" source="#skin-weights" offset="1"/>
        <vcount>)" +
      repeated("1 ", weights) + "</vcount><v>" + pairs + R"(</v></vertex_weights>
    </skin></controller></library_controllers>)";
  return cube_with(controllers, "<instance_controller url=\"#skin\"/>");
}

TEST(ColladaChecks, TheNodeGraphIsCheckedBeforeAssimpBuildsIt) {
  const std::string geometry = "<instance_geometry url=\"#box-lib\"/>";
  expect_each_refused({
      // Assimp instanced the node inside itself until its stack overflowed.
      {"self.dae",
       replaced(cube(), "<instance_geometry url=\"#box-lib\">",
                "<instance_node url=\"#Box\"/><instance_geometry url=\"#box-lib\">"),
       "not a COLLADA file PriMo accepts (node 'Box' is its own parent)"},
      {"cycle.dae",
       cube_with("<library_nodes><node id=\"a\"><instance_node url=\"#b\"/></node>"
                 "<node id=\"b\"><instance_node url=\"#a\"/>" +
                     geometry + "</node></library_nodes>",
                 "<instance_node url=\"#a\"/>"),
       "its node tree has a cycle"},
      // 30 nodes each instancing the next twice: 2^30 nodes, until memory ran out.
      {"bomb.dae", cube_with(chain(30, 2), "<instance_node url=\"#n0\"/>"),
       "its node tree expands to more than 1000000 node instances"},
      // A chain of instances as deep as the file is long (Assimp recurses once per level).
      {"deep-instances.dae", cube_with(chain(1100, 1), "<instance_node url=\"#n0\"/>"),
       "its node tree is deeper than 1000 levels"},
      // 7,000 nested nodes crashed Assimp; libxml2 stops at its own limit first.
      {"deep.dae",
       replaced(replaced(cube(), "<node id=\"Box\" name=\"Box\">",
                         repeated("<node>", 7000) + "<node id=\"Box\" name=\"Box\">"),
                "</instance_geometry>\n            </node>",
                "</instance_geometry>\n            </node>" + repeated("</node>", 7000)),
       "its XML is nested deeper than 256 elements (libxml2's limit)"},
      // Assimp leaves an instance it cannot resolve out without a word.
      {"missing-node.dae", cube_with("", "<instance_node url=\"#nowhere\"/>" + geometry),
       "node 'Box' instances '#nowhere' at line"},
      {"other-file.dae", cube_with("", "<instance_node url=\"parts.dae#wheel\"/>" + geometry),
       "which names no node of this file"},
      {"missing-geometry.dae", cube_with("", "<instance_geometry url=\"#nothing\"/>"),
       "node 'Box' instances '#nothing' at line"},
  });
}

TEST(ColladaChecks, AccessorsAndArraysMustHoldWhatTheyDeclare) {
  const std::string accessor =
      R"(<accessor count="8" offset="0" source="#box-lib-positions-array" stride="3">)";
  auto positions = [&](const std::string& with) { return replaced(cube(), accessor, with); };
  expect_each_refused({
      // An offset of 4e9 read far outside the array: Assimp crashed.
      {"offset.dae",
       positions(
           R"(<accessor count="8" offset="4000000000" source="#box-lib-positions-array" stride="3">)"),
       "the accessor of source 'box-lib-positions' (line 14) reads 4000000024 values (offset "
       "4000000000, 8 elements of stride 3), but its array 'box-lib-positions-array' has 24"},
      // One element past the array: Assimp invented a 9th vertex from the bytes after it.
      {"past.dae",
       positions(R"(<accessor count="9" offset="0" source="#box-lib-positions-array" stride="3">)"),
       "reads 27 values"},
      {"stride.dae",
       positions(R"(<accessor count="8" offset="0" source="#box-lib-positions-array" stride="2">)"),
       "has a stride of 2, smaller than its 3 values per element"},
      {"negative-count.dae",
       positions(
           R"(<accessor count="-1" offset="0" source="#box-lib-positions-array" stride="3">)"),
       "has count='-1', which is no whole number"},
      {"short-array.dae",
       replaced(cube(), R"(<float_array id="box-lib-positions-array" count="24">)",
                R"(<float_array id="box-lib-positions-array" count="25">)"),
       "the array 'box-lib-positions-array' declares 25 values but holds 24"},
      {"huge-count.dae",
       replaced(cube(), R"(<float_array id="box-lib-positions-array" count="24">)",
                R"(<float_array id="box-lib-positions-array" count="99999999999">)"),
       "a count of more than"},
      {"duplicate-source.dae",
       replaced(cube(), R"(<source id="box-lib-normals" name="normal">)",
                R"(<source id="box-lib-positions" name="normal">)"),
       "two <source>s have the id 'box-lib-positions'"},
      // Assimp read the positions from the (empty) number list of a name array.
      {"names.dae",
       replaced(replaced(cube(), R"(<float_array id="box-lib-positions-array" count="24">)",
                         R"(<Name_array id="box-lib-positions-array" count="24">)"),
                "</float_array>", "</Name_array>"),
       "reads source 'box-lib-positions', whose array holds names, not numbers"},
      // Assimp writes each value of a color into a color of 4: 16 overran it.
      {"color.dae",
       replaced(
           replaced(
               cube(), "<vertices id=\"box-lib-vertices\">",
               R"(<source id="box-lib-colors"><float_array id="box-lib-colors-array" count="384">)" +
                   repeated("0 ", 384) +
                   R"(</float_array><technique_common><accessor count="24" source="#box-lib-colors-array" stride="16">
                <param name="R" type="float4x4"/></accessor></technique_common></source>
                <vertices id="box-lib-vertices">)"),
           R"(<vcount>)",
           R"(<input offset="1" semantic="COLOR" source="#box-lib-colors"/><vcount>)"),
       "whose colors have 16 values (at most 4)"},
  });
}

TEST(ColladaChecks, PrimitivesMustMatchTheirInputsAndCounts) {
  const std::string p = "<p>0 0 2 1 3 2 1 3 ";
  expect_each_refused({
      {"index-past.dae", replaced(cube(), p, "<p>8 0 2 1 3 2 1 3 "),
       "holds the index 8, beyond the 8 values of source 'box-lib-positions'"},
      // Assimp reads a negative index as 0.
      {"negative-index.dae", replaced(cube(), p, "<p>-3 0 2 1 3 2 1 3 "),
       "holds the negative index -3, which Assimp reads as 0"},
      // Assimp reads "0.5" as 0 and stays at the '.', reading zeros until memory runs out.
      {"fraction.dae", replaced(cube(), p, "<p>0.5 0 2 1 3 2 1 3 "),
       "holds '0.5' where an index belongs"},
      {"short-p.dae",
       replaced(cube(), "5 18 1 19 5 20 7 21 6 22 4 23</p>", "5 18 1 19 5 20 7 21 6 22</p>"),
       "declares 24 corners of 2 indices each (48), but its <p> holds 46"},
      // Assimp read the polygon sizes from beyond an empty list.
      {"no-vcount.dae", replaced(cube(), "<vcount>4 4 4 4 4 4</vcount>", ""),
       "has no <vcount> of its 6 polygons before its <p>"},
      {"bad-vcount.dae",
       replaced(cube(), "<vcount>4 4 4 4 4 4</vcount>", "<vcount>4 4 4 4 4 x</vcount>"),
       "holds 'x', which is no polygon size"},
      // Assimp reserved 24 x 10^8 indices before finding that the <p> is shorter.
      {"offset-input.dae",
       replaced(cube(), R"(<input offset="1" semantic="NORMAL")",
                R"(<input offset="100000000" semantic="NORMAL")"),
       "indices, more than the file's size"},
      // Assimp read the index before the list for each corner's vertex.
      {"no-vertex.dae",
       replaced(cube(), R"(<input offset="0" semantic="VERTEX" source="#box-lib-vertices"/>)", ""),
       "has no VERTEX input"},
      {"two-positions.dae",
       replaced(
           cube(), R"(<input semantic="POSITION" source="#box-lib-positions"/>)",
           R"(<input semantic="POSITION" source="#box-lib-positions"/><input semantic="POSITION" source="#box-lib-positions"/>)"),
       "has 2 POSITION inputs (through <vertices> and its own); it needs exactly one"},
  });
}

TEST(ColladaChecks, ASkinMustWeighTheVerticesAndJointsItHas) {
  expect_each_refused({
      // Assimp looked the weights of vertices 4-7 up past the end of a list of 4.
      {"few-weights.dae", skinned_cube(4, 0),
       "skin 'skin' (instanced at line 80) weighs 4 vertices, but its mesh 'box-lib' uses vertex "
       "7"},
      // ... and wrote the weights of joint 5 past the end of a list of 1.
      {"joint.dae", skinned_cube(8, 5),
       "skin 'skin' weighs vertices by joint 5, but it has 1 joints"},
  });
  // The sound skin loads, in its bind pose.
  const std::string path = temp_dir() + "/skin.dae";
  write_text(path, skinned_cube(8, 0));
  const LoadedMesh loaded = load_mesh_noted(path);
  EXPECT_EQ(loaded.mesh.n_faces(), 6u);
  EXPECT_NE(loaded.note.find("skin"), std::string::npos) << loaded.note;
}

TEST(ColladaChecks, EntitiesAreRefusedQuickly) {
  // A billion laughs: ten entities, each ten of the one before, before the COLLADA root.
  std::string dtd = "<?xml version=\"1.0\"?>\n<!DOCTYPE COLLADA [\n <!ENTITY lol0 \"lol\">\n";
  for (int k = 1; k < 10; ++k)
    dtd += " <!ENTITY lol" + std::to_string(k) + " \"" +
           repeated("&lol" + std::to_string(k - 1) + ";", 10) + "\">\n";
  dtd += "]>\n";
  std::string bomb = replaced(cube(), "<?xml version=\"1.0\"?>\n", dtd);
  bomb = replaced(bomb, "<library_cameras>", "<library_cameras>&lol9;");
  const auto start = std::chrono::steady_clock::now();
  expect_each_refused({{"laughs.dae", bomb, "it declares XML entities ('lol0')"}});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
}

TEST(ColladaChecks, SoundFilesStillLoad) {
  const std::string dir = temp_dir();
  EXPECT_EQ(load_mesh(source_path("tests/data/scenes/cube_emptyTags.dae")).n_faces(), 6u);
  // A library node instanced by two nodes is two cubes.
  const std::string shared = dir + "/shared.dae";
  write_text(shared,
             cube_with("<library_nodes><node id=\"shared\"><instance_geometry url=\"#box-lib\"/>"
                       "</node></library_nodes>",
                       "<node id=\"left\"><instance_node url=\"#shared\"/></node>"
                       "<node id=\"right\"><translate>300 0 0</translate>"
                       "<instance_node url=\"#shared\"/></node>"));
  const Mesh two = load_mesh(shared);
  EXPECT_EQ(two.n_faces(), 12u);
  EXPECT_EQ(two.n_vertices(), 16u);
  // A node instanced by its name, found in the scene's tree as Assimp finds it, and a chain of
  // instances within the limit.
  const std::string by_name = dir + "/by-name.dae";
  write_text(
      by_name,
      cube_with("",
                "<node id=\"inner\" name=\"Inner\"><instance_geometry url=\"#box-lib\"/></node>"
                "<node id=\"copy\"><translate>300 0 0</translate>"
                "<instance_node url=\"#Inner\"/></node>"));
  EXPECT_EQ(load_mesh(by_name).n_faces(), 12u);
  const std::string deep = dir + "/deep-enough.dae";
  write_text(deep, cube_with(chain(900, 1), "<instance_node url=\"#n0\"/>"));
  EXPECT_EQ(load_mesh(deep).n_faces(), 6u);
}

// --- 3MF ---------------------------------------------------------------------------------------

uint32_t crc32(const std::string& bytes) {
  uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char c : bytes) {
    crc ^= c;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put16(std::string& out, uint32_t v) {
  out += char(v & 0xFF);
  out += char((v >> 8) & 0xFF);
}
void put32(std::string& out, uint32_t v) {
  put16(out, v & 0xFFFF);
  put16(out, v >> 16);
}

struct ZipEntry {
  std::string name, data;
  uint32_t declared = 0;  // the uncompressed size the headers claim (0: the data's)
};

// A zip of stored (uncompressed) entries; an entry that declares more than it holds claims to
// be deflated.
std::string zip(const std::vector<ZipEntry>& entries) {
  std::string out, directory;
  for (const ZipEntry& e : entries) {
    const uint32_t offset = uint32_t(out.size());
    const uint32_t size = uint32_t(e.data.size());
    const uint32_t declared = e.declared ? e.declared : size;
    const uint16_t method = e.declared ? 8 : 0;
    const uint32_t crc = crc32(e.data);
    auto header = [&](std::string& to, bool central) {
      put32(to, central ? 0x02014b50 : 0x04034b50);
      if (central) put16(to, 20);
      put16(to, 20);
      put16(to, 0);
      put16(to, method);
      put16(to, 0);
      put16(to, 0x21);
      put32(to, crc);
      put32(to, size);
      put32(to, declared);
      put16(to, uint16_t(e.name.size()));
      put16(to, 0);
      if (central) {
        put16(to, 0);
        put16(to, 0);
        put16(to, 0);
        put32(to, 0);
        put32(to, offset);
      }
      to += e.name;
    };
    header(out, false);
    out += e.data;
    header(directory, true);
  }
  const uint32_t directory_offset = uint32_t(out.size());
  out += directory;
  put32(out, 0x06054b50);
  put16(out, 0);
  put16(out, 0);
  put16(out, uint16_t(entries.size()));
  put16(out, uint16_t(entries.size()));
  put32(out, uint32_t(directory.size()));
  put32(out, directory_offset);
  put16(out, 0);
  return out;
}

const char* kRels =
    R"(<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel" /></Relationships>)";
const char* kContentTypes =
    R"(<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>)";

std::string model(const std::string& resources, const std::string& build) {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
 xmlns:m="http://schemas.microsoft.com/3dmanufacturing/material/2015/02"
 xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06">
<resources>)" +
         resources + "</resources>\n<build>" + build + "</build>\n</model>\n";
}

// box.3mf's box: 8 vertices, 12 triangles, outwards.
const char* kBoxVertices = R"(<vertices><vertex x="0" y="0" z="0"/><vertex x="10" y="0" z="0"/>
<vertex x="10" y="20" z="0"/><vertex x="0" y="20" z="0"/><vertex x="0" y="0" z="30"/>
<vertex x="10" y="0" z="30"/><vertex x="10" y="20" z="30"/><vertex x="0" y="20" z="30"/></vertices>)";
const char* kBoxTriangles =
    R"(<triangles><triangle v1="3" v2="2" v3="1"/><triangle v1="1" v2="0" v3="3"/>
<triangle v1="4" v2="5" v3="6"/><triangle v1="6" v2="7" v3="4"/><triangle v1="0" v2="1" v3="5"/>
<triangle v1="5" v2="4" v3="0"/><triangle v1="1" v2="2" v3="6"/><triangle v1="6" v2="5" v3="1"/>
<triangle v1="2" v2="3" v3="7"/><triangle v1="7" v2="6" v3="2"/><triangle v1="3" v2="0" v3="4"/>
<triangle v1="4" v2="7" v3="3"/></triangles>)";

std::string box(int id, const std::string& mesh_body = std::string(kBoxVertices) + kBoxTriangles,
                const std::string& attributes = "") {
  return "<object id=\"" + std::to_string(id) + "\" type=\"model\"" + attributes + "><mesh>" +
         mesh_body + "</mesh></object>\n";
}

std::string package(const std::string& model_text) {
  return zip({{"[Content_Types].xml", kContentTypes, 0},
              {"_rels/.rels", kRels, 0},
              {"3D/3dmodel.model", model_text, 0}});
}

// A box (object 1) and object `id` made of `components`, built as `items`.
std::string assembly(int id, const std::string& components, const std::string& items) {
  return package(model(box(1) + "<object id=\"" + std::to_string(id) +
                           "\" type=\"model\"><components>" + components +
                           "</components></object>\n",
                       items));
}

std::string component(int id, const std::string& extra = "") {
  return "<component objectid=\"" + std::to_string(id) + "\"" + extra + "/>";
}

TEST(ThreeMfChecks, TheZipIsCheckedBeforeAnythingIsInflated) {
  const std::string sound = model(box(1), "<item objectid=\"1\"/>");
  expect_each_refused({
      // 1,000 bytes claiming to inflate to 5 MB: Assimp allocates what an entry declares.
      {"bomb.3mf",
       zip({{"_rels/.rels", kRels, 0},
            {"3D/3dmodel.model", sound, 0},
            {"Metadata/thumbnail.png", std::string(1000, 'x'), 5000000}}),
       "its entry 'Metadata/thumbnail.png' would inflate from 1000 to 5000000 bytes, more than "
       "1000 times its size"},
      {"huge.3mf",
       zip({{"_rels/.rels", kRels, 0},
            {"3D/3dmodel.model", sound, 0},
            {"big.png", std::string(1200000, 'x'), 1200000000u}}),
       "would inflate from 1200000 to 1200000000 bytes, more than an entry may (1 GiB)"},
      {"no-rels.3mf", zip({{"3D/3dmodel.model", sound, 0}}),
       "it has no _rels/.rels to name its model part"},
      {"no-start.3mf",
       zip({{"_rels/.rels", "<Relationships/>", 0}, {"3D/3dmodel.model", sound, 0}}),
       "its _rels/.rels names no model part"},
      {"no-model.3mf", zip({{"_rels/.rels", kRels, 0}}),
       "its model part '/3D/3dmodel.model' is missing"},
      {"bad-rels.3mf", zip({{"_rels/.rels", "<Relationships>", 0}, {"3D/3dmodel.model", sound, 0}}),
       "_rels/.rels: its XML is not well-formed"},
      {"damaged.3mf",
       zip({{"_rels/.rels", kRels, 0}, {"3D/3dmodel.model", std::string(100, 'x'), 200}}),
       "its entry '3D/3dmodel.model' is damaged (it does not inflate to the 200 bytes it declares"},
  });
}

TEST(ThreeMfChecks, ComponentsMustFormATreeOfObjectsTheFileHas) {
  std::string bomb_objects = box(1);
  for (int k = 2; k <= 31; ++k)
    bomb_objects += "<object id=\"" + std::to_string(k) + "\" type=\"model\"><components>" +
                    component(k - 1) + component(k - 1) + "</components></object>\n";
  std::string deep_objects = box(1);
  for (int k = 2; k <= 1102; ++k)
    deep_objects += "<object id=\"" + std::to_string(k) + "\" type=\"model\"><components>" +
                    component(k - 1) + "</components></object>\n";
  expect_each_refused({
      // Assimp added the object to itself until its stack overflowed.
      {"self.3mf", assembly(2, component(1) + component(2), "<item objectid=\"2\"/>"),
       "not a 3MF file PriMo accepts (object 2 is its own parent)"},
      {"cycle.3mf",
       package(model(box(1) + "<object id=\"2\"><components>" + component(3) +
                         "</components></object>"
                         "<object id=\"3\"><components>" +
                         component(2) + component(1) + "</components></object>",
                     "<item objectid=\"2\"/>")),
       "its node tree has a cycle"},
      {"bomb.3mf", package(model(bomb_objects, "<item objectid=\"31\"/>")),
       "its node tree expands to more than 1000000 node instances"},
      {"deep.3mf", package(model(deep_objects, "<item objectid=\"1102\"/>")),
       "its node tree is deeper than 1000 levels"},
      // Assimp leaves out a component or item whose object is missing, without a word.
      {"missing-component.3mf", assembly(2, component(1) + component(9), "<item objectid=\"2\"/>"),
       "a component of object 2 (line 12) names object 9, which the file does not have"},
      {"missing-item.3mf",
       assembly(2, component(1), "<item objectid=\"2\"/><item objectid=\"7\"/>"),
       "names object 7, which the file does not have"},
      // Assimp reads no other model part: it would take object 1 of this one.
      {"path.3mf",
       assembly(2, component(1, " p:path=\"/3D/other.model\""), "<item objectid=\"2\"/>"),
       "refers to an object of the model part '/3D/other.model', which Assimp does not read"},
      {"transform.3mf",
       assembly(2, component(1, " transform=\"1 0 0 0 1 0 0 0 1 0 0\""), "<item objectid=\"2\"/>"),
       "is not 12 numbers"},
      {"same-id.3mf", package(model(box(1) + box(1), "<item objectid=\"1\"/>")),
       "two resources have the id 1"},
      {"word-id.3mf", package(model(box(1), "<item objectid=\"one\"/>")),
       "has objectid='one', which is no whole number"},
  });
}

TEST(ThreeMfChecks, TrianglesVerticesAndPropertiesMustBeComplete) {
  const std::string vertices = kBoxVertices, triangles = kBoxTriangles;
  auto single = [](const std::string& object) {
    return package(model(object, "<item objectid=\"1\"/>"));
  };
  const std::string first = R"(<triangle v1="3" v2="2" v3="1"/>)";
  const std::string materials =
      R"(<basematerials id="5"><base name="red" displaycolor="#FF0000"/></basematerials>)";
  const std::string group =
      R"(<m:texture2dgroup id="6" texid="7"><m:tex2coord u="0" v="0"/><m:tex2coord u="1" v="0"/></m:texture2dgroup>)";
  expect_each_refused({
      // Assimp read a missing v3 as vertex 0.
      {"no-v3.3mf",
       single(box(1, vertices + replaced(triangles, first, R"(<triangle v1="3" v2="2"/>)"))),
       "has no v3 (Assimp would read vertex 0)"},
      // Assimp dropped the triangle naming a ninth vertex of eight.
      {"past.3mf",
       single(box(1, vertices + replaced(triangles, first, R"(<triangle v1="8" v2="2" v3="1"/>)"))),
       "has v1='8', but its mesh has 8 vertices"},
      {"negative.3mf",
       single(
           box(1, vertices + replaced(triangles, first, R"(<triangle v1="-1" v2="2" v3="1"/>)"))),
       "has v1='-1', but its mesh has 8 vertices"},
      {"no-z.3mf",
       single(
           box(1, replaced(vertices, R"(<vertex x="0" y="0" z="0"/>)", R"(<vertex x="0" y="0"/>)") +
                      triangles)),
       "has no z (Assimp would read 0)"},
      {"two-lists.3mf", single(box(1, vertices + triangles + triangles)),
       "has a second <triangles>"},
      {"order.3mf", single(box(1, triangles + vertices)), "comes before its mesh's <vertices>"},
      // Assimp read the material of p1 = 3 from a list of 1.
      {"material.3mf",
       package(model(
           materials +
               box(1, vertices + replaced(triangles, first,
                                          R"(<triangle v1="3" v2="2" v3="1" pid="5" p1="3"/>)")),
           "<item objectid=\"1\"/>")),
       "has p1=3, but base materials 5 has 1"},
      {"pindex.3mf",
       package(model(materials + box(1, vertices + triangles, " pid=\"5\" pindex=\"2\""),
                     "<item objectid=\"1\"/>")),
       "object 1 has pindex=2, but base materials 5 has 1"},
      // ... and the texture coordinate of a missing p2 from before its list.
      {"texture.3mf",
       package(model(
           group +
               box(1, vertices + replaced(triangles, first,
                                          R"(<triangle v1="3" v2="2" v3="1" pid="6" p1="0"/>)")),
           "<item objectid=\"1\"/>")),
       "has p2=-1, but texture group 6 has 2 coordinates (Assimp reads a missing one as -1)"},
      {"laughs.3mf",
       package(replaced(model(box(1), "<item objectid=\"1\"/>"), "<model ",
                        "<!DOCTYPE model [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b "
                        "\"&a;&a;&a;&a;&a;&a;&a;&a;\">]>\n<model ")),
       "it declares XML entities ('a')"},
      {"deep-xml.3mf",
       single(box(1, vertices + triangles + repeated("<x>", 300) + repeated("</x>", 300))),
       "its XML is nested deeper than 256 elements (libxml2's limit)"},
  });
}

TEST(ThreeMfChecks, SoundFilesStillLoad) {
  const std::string dir = temp_dir();
  EXPECT_EQ(load_mesh(source_path("tests/data/scenes/box.3mf")).n_faces(), 12u);
  const std::string one = dir + "/one.3mf";
  write_text(one, package(model(box(1), "<item objectid=\"1\"/>")));
  EXPECT_EQ(load_mesh(one).n_faces(), 12u);
  // An object used twice as a component, moved apart, and base materials in range.
  const std::string two = dir + "/two.3mf";
  write_text(
      two,
      package(model(
          R"(<basematerials id="5"><base name="red" displaycolor="#FF0000"/></basematerials>)" +
              box(1, std::string(kBoxVertices) + kBoxTriangles, " pid=\"5\" pindex=\"0\"") +
              "<object id=\"2\" type=\"model\"><components>" + component(1) +
              component(1, " transform=\"1 0 0 0 1 0 0 0 1 50 0 0\"") + "</components></object>",
          "<item objectid=\"2\"/>")));
  const Mesh mesh = load_mesh(two);
  EXPECT_EQ(mesh.n_faces(), 24u);
  EXPECT_EQ(mesh.n_vertices(), 16u);
}

}  // namespace
}  // namespace primo
