// Face-corner attributes through reading and writing (docs/mesh-io.md, "Attributes"): an OBJ
// written back changes only its `v` and `vn` lines, normals are recomputed per normal slot,
// glTF and FBX characters exported as glTF keep their UVs, materials and textures (read back
// through Assimp), and bad attribute data is refused with the file named.

#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "primo/util/error.h"
#include "primo/mesh/mesh_attributes.h"
#include "primo/io/mesh_import.h"
#include "primo/io/mesh_io.h"
#include "support/test_support.h"

using primo::test::read_text;
using primo::test::temp_dir;
using primo::test::write_text;

namespace {

// A unit cube (tests/data/textured_cube) with a UV per corner of its net, one normal per face
// (hard edges), two materials in its library, groups and smoothing statements, and a vertex
// colour after one vertex's coordinates.
std::string textured_cube_text() {
  return read_text(primo::test::source_path("tests/data/textured_cube/cube.obj"));
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

bool starts_with(const std::string& line, const char* prefix) { return line.rfind(prefix, 0) == 0; }

std::vector<double> numbers_after_keyword(const std::string& line) {
  std::istringstream in(line);
  std::string word;
  in >> word;
  std::vector<double> values;
  while (in >> word) {
    double value;
    std::from_chars(word.data(), word.data() + word.size(), value);
    values.push_back(value);
  }
  return values;
}

struct WrittenCube {
  std::string folder, input, output;
};

WrittenCube textured_cube() {
  WrittenCube cube{temp_dir(), "", ""};
  cube.input = cube.folder + "/cube.obj";
  cube.output = cube.folder + "/posed.obj";
  write_text(cube.input, textured_cube_text());
  write_text(cube.folder + "/cube.mtl",
             read_text(primo::test::source_path("tests/data/textured_cube/cube.mtl")));
  return cube;
}

TEST(MeshAttributesObj, ReadsUvsNormalSlotsAndMaterials) {
  const WrittenCube cube = textured_cube();
  const primo::LoadedMesh loaded = primo::load_mesh_noted(cube.input);
  EXPECT_EQ(loaded.note, "");
  const primo::MeshAttributes& a = loaded.attributes;
  ASSERT_EQ(a.texcoords.size(), 1u);
  EXPECT_EQ(a.texcoords[0].values.size(), 4u);
  EXPECT_EQ(a.texcoords[0].corner.size(), 24u);
  EXPECT_EQ(a.n_normals, 6);
  ASSERT_EQ(a.materials.size(), 2u);
  EXPECT_EQ(a.materials[0].name, "red");
  EXPECT_EQ(a.materials[0].base_color[0], 1.0);
  EXPECT_EQ(a.materials[1].base_color[2], 1.0);
  ASSERT_EQ(a.images.size(), 1u);
  EXPECT_EQ(a.images[0].uri, "red.png");
  EXPECT_EQ(a.face_material, (std::vector<int>{0, 1, 1, 1, 0, 0}));
}

TEST(MeshAttributesObj, UnposedWriteChangesOnlyVertexAndNormalLines) {
  const WrittenCube cube = textured_cube();
  const primo::LoadedMesh loaded = primo::load_mesh_noted(cube.input);
  primo::save_mesh(loaded.mesh, loaded.attributes, cube.output);
  const std::vector<std::string> in = lines_of(textured_cube_text()),
                                 out = lines_of(read_text(cube.output));
  ASSERT_EQ(in.size(), out.size());
  for (size_t i = 0; i < in.size(); ++i) {
    if (starts_with(in[i], "v ")) {
      EXPECT_EQ(numbers_after_keyword(in[i]), numbers_after_keyword(out[i])) << in[i];
    } else if (!starts_with(in[i], "vn ")) {
      EXPECT_EQ(in[i], out[i]);
    }
  }
  // The cube's face normals recomputed are the ones the file lists.
  for (size_t i = 0; i < in.size(); ++i) {
    if (!starts_with(in[i], "vn ")) continue;
    EXPECT_EQ(numbers_after_keyword(in[i]), numbers_after_keyword(out[i]));
  }
}

TEST(MeshAttributesObj, RotatedCubeNormalsRotateAndStayHard) {
  const WrittenCube cube = textured_cube();
  primo::LoadedMesh loaded = primo::load_mesh_noted(cube.input);
  // A quarter turn about z: (x, y, z) -> (-y, x, z), exact in doubles.
  for (auto v : loaded.mesh.vertices()) {
    const primo::Vec3 p = loaded.mesh.point(v);
    loaded.mesh.set_point(v, primo::Vec3(-p.y(), p.x(), p.z()));
  }
  primo::save_mesh(loaded.mesh, loaded.attributes, cube.output);
  const std::vector<std::string> in = lines_of(textured_cube_text()),
                                 out = lines_of(read_text(cube.output));
  int normals = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    if (!starts_with(in[i], "vn ")) continue;
    ++normals;
    const std::vector<double> n = numbers_after_keyword(in[i]), m = numbers_after_keyword(out[i]);
    ASSERT_EQ(m.size(), 3u);
    EXPECT_NEAR(m[0], -n[1], 1e-15);
    EXPECT_NEAR(m[1], n[0], 1e-15);
    EXPECT_NEAR(m[2], n[2], 1e-15);
  }
  EXPECT_EQ(normals, 6);
}

TEST(MeshAttributesObj, SmoothNormalSlotAveragesItsFaces) {
  // Two triangles folded at a right angle sharing normal 1 on their common edge.
  const std::string folder = temp_dir();
  write_text(folder + "/fold.obj",
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
             "f 1//1 2//2 3//2\nf 1//1 4//3 2//3\n");
  const primo::LoadedMesh loaded = primo::load_mesh_noted(folder + "/fold.obj");
  const std::vector<primo::Vec3> normals = primo::corner_normals(loaded.mesh, loaded.attributes);
  ASSERT_EQ(normals.size(), 3u);
  EXPECT_NEAR(normals[1].z(), 1.0, 1e-15);             // the first face alone
  EXPECT_NEAR(normals[2].y(), 1.0, 1e-15);             // the second face alone
  EXPECT_NEAR(normals[0].y(), std::sqrt(0.5), 1e-15);  // both, equal areas
  EXPECT_NEAR(normals[0].z(), std::sqrt(0.5), 1e-15);
}

TEST(MeshAttributesObj, LibraryIsReachedFromAnotherFolder) {
  const WrittenCube cube = textured_cube();
  const std::string other = temp_dir();
  const primo::LoadedMesh loaded = primo::load_mesh_noted(cube.input);
  primo::save_mesh(loaded.mesh, loaded.attributes, other + "/posed.obj");
  const primo::LoadedMesh again = primo::load_mesh_noted(other + "/posed.obj");
  EXPECT_EQ(again.note, "");
  EXPECT_EQ(again.attributes.materials[0].base_color[0], 1.0);
}

TEST(MeshAttributesObj, ObjFromAScenePairsCornersWithUvsNormalsAndMaterials) {
  const primo::LoadedMesh box =
      primo::load_mesh_noted(primo::test::source_path("tests/data/scenes/BoxTextured.glb"));
  const std::string path = temp_dir() + "/box.obj";
  primo::save_mesh(box.mesh, box.attributes, path);
  const primo::LoadedMesh again = primo::load_mesh_noted(path);
  ASSERT_EQ(again.attributes.texcoords.size(), 1u);
  const auto& a = box.attributes.texcoords[0];
  const auto& b = again.attributes.texcoords[0];
  ASSERT_EQ(a.corner.size(), b.corner.size());
  for (size_t c = 0; c < a.corner.size(); ++c)
    EXPECT_EQ(a.values[size_t(a.corner[c])], b.values[size_t(b.corner[c])]) << "corner " << c;
  EXPECT_EQ(again.attributes.n_normals, box.attributes.n_normals);
  EXPECT_EQ(again.attributes.face_material.size(), box.attributes.face_material.size());
}

TEST(MeshAttributesObj, BadAttributeDataIsRefusedWithTheFileNamed) {
  const std::string folder = temp_dir();
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  primo::test::expect_one_line_error(
      [&] {
        write_text(folder + "/uv.obj", quad + "vt 0 0\nf 1/1 2/2 3/1 4/1\n");
        primo::load_mesh(folder + "/uv.obj");
      },
      folder + "/uv.obj", "texture coordinate index 2 is out of range");
  primo::test::expect_one_line_error(
      [&] {
        write_text(folder + "/nan.obj", quad + "vt nan 0\nf 1/1 2/1 3/1 4/1\n");
        primo::load_mesh(folder + "/nan.obj");
      },
      folder + "/nan.obj", "is not finite");
  primo::test::expect_one_line_error(
      [&] {
        write_text(folder + "/vn.obj", quad + "vn 0 0 1\nf 1//1 2//1 3//2 4//1\n");
        primo::load_mesh(folder + "/vn.obj");
      },
      folder + "/vn.obj", "normal index 2 is out of range");
  write_text(folder + "/lib.obj", "mtllib missing.mtl\n" + quad + "usemtl skin\nf 1 2 3 4\n");
  const primo::LoadedMesh loaded = primo::load_mesh_noted(folder + "/lib.obj");
  EXPECT_NE(loaded.note.find(folder + "/lib.obj: materials keep their names only"),
            std::string::npos)
      << loaded.note;
  EXPECT_NE(loaded.note.find("missing.mtl"), std::string::npos) << loaded.note;
  ASSERT_EQ(loaded.attributes.materials.size(), 1u);
  EXPECT_EQ(loaded.attributes.materials[0].name, "skin");
}

TEST(MeshAttributesCheck, AttributesOfAnotherMeshAreRefused) {
  const WrittenCube cube = textured_cube();
  const primo::LoadedMesh loaded = primo::load_mesh_noted(cube.input);
  primo::MeshAttributes wrong = loaded.attributes;
  wrong.texcoords[0].corner.pop_back();
  primo::test::expect_one_line_error([&] { primo::save_mesh(loaded.mesh, wrong, cube.output); },
                                     cube.output, "texture coordinate set 0 has 23 corners");
  wrong = loaded.attributes;
  wrong.face_material[2] = 7;
  primo::test::expect_one_line_error(
      [&] { primo::save_mesh(loaded.mesh, wrong, cube.output + ".gltf"); }, cube.output + ".gltf",
      "face 2 refers to material 7 of 2");
}

TEST(MeshAttributesGltf, ColoursAndTwoUvSetsComeBackPerCorner) {
  const WrittenCube cube = textured_cube();
  primo::LoadedMesh loaded = primo::load_mesh_noted(cube.input);
  primo::MeshAttributes& a = loaded.attributes;
  a.obj_text.clear();
  // A colour per vertex (corners of one vertex share it) and a second UV set, per corner.
  primo::CornerValues<4> colors;
  primo::CornerValues<2> second;
  for (auto f : loaded.mesh.faces())
    for (auto v : f.vertices()) {
      colors.corner.push_back(v.idx());
      second.corner.push_back(int(second.values.size()));
      second.values.push_back({0.125 * double(second.values.size() % 8), 0.5});
    }
  for (int v = 0; v < 8; ++v) colors.values.push_back({v / 8.0, 1 - v / 8.0, 0.25, 1});
  a.colors.push_back(colors);
  a.texcoords.push_back(second);
  const std::string output = cube.folder + "/coloured.glb";
  primo::test::expect_one_line_error([&] { primo::save_mesh(loaded.mesh, a, output); }, output,
                                     "a GLB embeds its images, and " + cube.folder + "/red.png");
  write_text(cube.folder + "/red.png", "\x89PNG stand-in");
  primo::save_mesh(loaded.mesh, a, output);
  const primo::LoadedMesh back = primo::load_mesh_noted(output);
  ASSERT_EQ(back.attributes.colors.size(), 1u);
  ASSERT_EQ(back.attributes.texcoords.size(), 2u);
  // Two materials: faces come back grouped by material (red: 0, 4, 5; blue: 1, 2, 3).
  const std::vector<size_t> order = {0, 4, 5, 1, 2, 3};
  const std::vector<int> first = primo::first_corners(loaded.mesh);
  size_t c = 0;
  for (size_t face : order)
    for (int k = first[face]; k < first[face + 1]; ++k, ++c) {
      const auto& color = back.attributes.colors[0];
      EXPECT_EQ(color.values[size_t(color.corner[c])],
                colors.values[size_t(colors.corner[size_t(k)])]);
      const auto& uv = back.attributes.texcoords[1];
      for (int i = 0; i < 2; ++i)
        EXPECT_NEAR(uv.values[size_t(uv.corner[c])][size_t(i)],
                    second.values[size_t(second.corner[size_t(k)])][size_t(i)], 1e-7);
    }
  EXPECT_EQ(back.attributes.face_material, (std::vector<int>{0, 0, 0, 1, 1, 1}));
}

// ---------------------------------------------------------------------------------------------
// Scenes exported as glTF, read back through Assimp

struct SceneCorner {
  std::array<float, 3> position;
  std::array<float, 2> uv;
  bool operator<(const SceneCorner& o) const {
    return std::tie(position, uv) < std::tie(o.position, o.uv);
  }
};

struct SceneSummary {
  std::vector<SceneCorner> corners;  // every face corner, sorted
  std::vector<std::string> materials;
  std::vector<std::array<float, 4>> base_colors;
  std::vector<std::string> textures;  // the base colour texture's path ("" for none)
  size_t embedded_textures = 0;
};

// Every face corner's position (with its node's global transform) and first UV, and the
// materials the faces use.
SceneSummary summarize(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  EXPECT_NE(scene, nullptr) << importer.GetErrorString();
  SceneSummary out;
  if (!scene) return out;
  out.embedded_textures = scene->mNumTextures;
  std::set<unsigned> used;
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> nodes = {
      {scene->mRootNode, scene->mRootNode->mTransformation}};
  while (!nodes.empty()) {
    const auto [node, transform] = nodes.back();
    nodes.pop_back();
    for (unsigned c = 0; c < node->mNumChildren; ++c)
      nodes.emplace_back(node->mChildren[c], transform * node->mChildren[c]->mTransformation);
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const aiMesh& mesh = *scene->mMeshes[node->mMeshes[i]];
      used.insert(mesh.mMaterialIndex);
      for (unsigned f = 0; f < mesh.mNumFaces; ++f)
        for (unsigned k = 0; k < mesh.mFaces[f].mNumIndices; ++k) {
          const unsigned v = mesh.mFaces[f].mIndices[k];
          const aiVector3D p = transform * mesh.mVertices[v];
          const aiVector3D uv = mesh.HasTextureCoords(0) ? mesh.mTextureCoords[0][v] : aiVector3D();
          out.corners.push_back({{p.x, p.y, p.z}, {uv.x, uv.y}});
        }
    }
  }
  std::sort(out.corners.begin(), out.corners.end());
  for (unsigned m : used) {
    const aiMaterial& material = *scene->mMaterials[m];
    out.materials.push_back(material.GetName().C_Str());
    aiColor4D color(0, 0, 0, 0);
    if (material.Get(AI_MATKEY_BASE_COLOR, color) != aiReturn_SUCCESS)
      material.Get(AI_MATKEY_COLOR_DIFFUSE, color);
    out.base_colors.push_back({color.r, color.g, color.b, color.a});
    aiString texture;
    if (material.GetTextureCount(aiTextureType_DIFFUSE) > 0)
      material.GetTexture(aiTextureType_DIFFUSE, 0, &texture);
    out.textures.push_back(texture.C_Str());
  }
  return out;
}

// Each exported corner (triangulated) is a corner of the source with the same UV, up to
// float rounding of the v flip.
void expect_same_uvs(const SceneSummary& source, const SceneSummary& exported) {
  ASSERT_FALSE(exported.corners.empty());
  for (const SceneCorner& c : exported.corners) {
    bool found = false;
    for (const SceneCorner& s : source.corners) {
      bool same = true;
      for (int k = 0; k < 3; ++k) same = same && std::abs(s.position[k] - c.position[k]) < 1e-5f;
      for (int k = 0; k < 2; ++k) same = same && std::abs(s.uv[k] - c.uv[k]) < 1e-6f;
      if (same) found = true;
    }
    EXPECT_TRUE(found) << "corner at " << c.position[0] << " " << c.position[1] << " "
                       << c.position[2] << " uv " << c.uv[0] << " " << c.uv[1];
  }
}

TEST(MeshAttributesGltf, TexturedGlbKeepsUvsMaterialAndEmbeddedImage) {
  const std::string source = primo::test::source_path("tests/data/scenes/BoxTextured.glb");
  const primo::LoadedMesh box = primo::load_mesh_noted(source);
  ASSERT_EQ(box.attributes.materials.size(), 1u);
  ASSERT_EQ(box.attributes.images.size(), 1u);
  EXPECT_FALSE(box.attributes.images[0].bytes.empty());
  const SceneSummary original = summarize(source);
  for (const char* name : {"/box.glb", "/box.gltf"}) {
    const std::string output = temp_dir() + name;
    primo::save_mesh(box.mesh, box.attributes, output);
    const SceneSummary exported = summarize(output);
    expect_same_uvs(original, exported);
    EXPECT_EQ(exported.materials, original.materials);
    EXPECT_EQ(exported.base_colors, original.base_colors);
    EXPECT_EQ(exported.embedded_textures, 1u);
    ASSERT_EQ(exported.textures.size(), 1u);
    EXPECT_EQ(exported.textures[0], "*0");
  }
}

TEST(MeshAttributesGltf, ReferencedImageIsNamedFromTheOutputFolder) {
  const WrittenCube cube = textured_cube();
  const primo::LoadedMesh loaded = primo::load_mesh_noted(cube.input);
  const std::string other = cube.folder + "/out";
  std::filesystem::create_directory(other);
  primo::save_mesh(loaded.mesh, loaded.attributes, other + "/cube.gltf");
  const SceneSummary exported = summarize(other + "/cube.gltf");
  EXPECT_EQ(exported.materials, (std::vector<std::string>{"red", "blue"}));
  ASSERT_EQ(exported.textures.size(), 2u);
  EXPECT_EQ(exported.textures[0], "../red.png");
  EXPECT_EQ(exported.textures[1], "");
  // v is flipped to glTF's convention and back by Assimp: the OBJ's UVs come back.
  const SceneSummary obj = summarize(cube.input);
  expect_same_uvs(obj, exported);
}

TEST(MeshAttributesGltf, TexturedFbxKeepsUvsAndMaterials) {
  const std::string source = primo::test::source_path("tests/data/scenes/phong_cube.fbx");
  const primo::LoadedMesh cube = primo::load_mesh_noted(source);
  ASSERT_FALSE(cube.attributes.texcoords.empty());
  ASSERT_FALSE(cube.attributes.materials.empty());
  const std::string output = temp_dir() + "/cube.glb";
  primo::save_mesh(cube.mesh, cube.attributes, output);
  const SceneSummary exported = summarize(output);
  EXPECT_EQ(exported.materials.size(), cube.attributes.materials.size());
  EXPECT_EQ(exported.materials[0], cube.attributes.materials[0].name);
  // Positions come back baked (PriMo writes the scene's transforms into them).
  const primo::LoadedMesh again = primo::load_mesh_noted(output);
  ASSERT_EQ(again.attributes.texcoords.size(), cube.attributes.texcoords.size());
  std::multiset<std::array<double, 2>> a, b;
  for (size_t c = 0; c < cube.attributes.texcoords[0].corner.size(); ++c)
    a.insert(cube.attributes.texcoords[0].values[size_t(cube.attributes.texcoords[0].corner[c])]);
  for (const auto& uv : again.attributes.texcoords[0].values) b.insert(uv);
  for (const auto& uv : b) {
    bool found = false;
    for (const auto& u : a)
      found = found || (std::abs(u[0] - uv[0]) < 1e-6 && std::abs(u[1] - uv[1]) < 1e-6);
    EXPECT_TRUE(found) << uv[0] << " " << uv[1];
  }
}

// The posed file read back by PriMo has the source's faces in order (one material), so each
// corner's UV can be compared with the same corner's in the source.
void expect_posed_export_keeps_uvs_and_materials(const std::string& source,
                                                 const std::string& scenario,
                                                 const std::string& output) {
  const primo::test::CommandResult r =
      primo::test::run_primo("deform " + scenario + " -o " + output);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const primo::LoadedMesh rest = primo::load_mesh_noted(source);
  const primo::LoadedMesh posed = primo::load_mesh_noted(output);
  ASSERT_EQ(posed.mesh.n_faces(), rest.mesh.n_faces());
  double moved = 0;
  for (auto v : rest.mesh.vertices())
    moved = std::max(moved, (posed.mesh.point(v) - rest.mesh.point(v)).norm());
  EXPECT_GT(moved, 0.01) << "the pose moved the mesh";
  ASSERT_EQ(posed.attributes.texcoords.size(), rest.attributes.texcoords.size());
  ASSERT_FALSE(rest.attributes.texcoords.empty());
  const auto& a = rest.attributes.texcoords[0];
  const auto& b = posed.attributes.texcoords[0];
  ASSERT_EQ(a.corner.size(), b.corner.size());
  for (size_t c = 0; c < a.corner.size(); ++c)
    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(a.values[size_t(a.corner[c])][size_t(k)],
                  b.values[size_t(b.corner[c])][size_t(k)], 1e-6)
          << "corner " << c;
  ASSERT_EQ(posed.attributes.materials.size(), rest.attributes.materials.size());
  for (size_t m = 0; m < rest.attributes.materials.size(); ++m) {
    EXPECT_EQ(posed.attributes.materials[m].name, rest.attributes.materials[m].name);
    EXPECT_EQ(posed.attributes.materials[m].base_color, rest.attributes.materials[m].base_color);
    EXPECT_EQ(posed.attributes.materials[m].base_color_texture.image >= 0,
              rest.attributes.materials[m].base_color_texture.image >= 0);
  }
  EXPECT_EQ(posed.attributes.images.size(), rest.attributes.images.size());
  EXPECT_EQ(posed.attributes.face_material, rest.attributes.face_material);
}

TEST(MeshAttributesPosed, FbxCharacterPosedToGlbKeepsItsUvsAndMaterial) {
  expect_posed_export_keeps_uvs_and_materials(
      primo::test::source_path("assets/meshes/huesitos.fbx"),
      primo::test::source_path("assets/scenarios/huesitos-raise.json"), temp_dir() + "/raised.glb");
}

TEST(MeshAttributesPosed, TexturedGlbPosedToGltfKeepsItsUvsMaterialAndImage) {
  const std::string dir = temp_dir();
  write_text(dir + "/box.json", R"({"format": "primo-scenario/1", "mesh": ")" +
                                    primo::test::source_path("tests/data/scenes/BoxTextured.glb") +
                                    R"(", "handles": [
    {"name": "a", "select": {"faces": [0, 1]}, "fix": "all"},
    {"name": "b", "select": {"faces": [2, 3]}, "fix": "all",
     "transform": {"translate": [0.1, 0, 0], "axis": [0, 0, 1], "angle_deg": 10}}]})");
  expect_posed_export_keeps_uvs_and_materials(
      primo::test::source_path("tests/data/scenes/BoxTextured.glb"), dir + "/box.json",
      dir + "/posed.gltf");
}

}  // namespace
