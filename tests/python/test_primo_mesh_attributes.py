"""The primo module keeps what a mesh file carries beside its positions: a textured mesh
loaded, posed with with_vertices and saved keeps its UVs, normals slots and materials.

The written files are read back here without primo: the OBJ as text, the GLB by its JSON and
binary chunks, so that a reader of primo's own cannot hide a loss.
"""
import json
import os
import shutil
import struct

import numpy as np
import pytest

import primo

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CUBE = os.path.join(SOURCE, "tests", "data", "textured_cube")


def textured_cube(folder):
    """The textured cube (cube.obj, cube.mtl) and the red.png its library names."""
    for name in ("cube.obj", "cube.mtl"):
        shutil.copy(os.path.join(CUBE, name), folder / name)
    (folder / "red.png").write_bytes(b"\x89PNG\r\n\x1a\n not decoded by the writer")
    return str(folder / "cube.obj")


def obj_corners(path):
    """Every face corner of an OBJ as (position, uv), and the materials its faces use."""
    positions, uvs, corners, materials = [], [], [], []
    for line in open(path):
        words = line.split()
        if not words:
            continue
        if words[0] == "v":
            positions.append([float(x) for x in words[1:4]])
        elif words[0] == "vt":
            uvs.append([float(x) for x in words[1:3]])
        elif words[0] == "usemtl":
            materials.append(words[1])
        elif words[0] == "f":
            for corner in words[1:]:
                v, t = corner.split("/")[:2]
                corners.append((positions[int(v) - 1], uvs[int(t) - 1]))
    return corners, materials


def glb_parts(path):
    """A GLB's JSON and an accessor reader over its binary chunk."""
    data = open(path, "rb").read()
    magic, version, _ = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67 and version == 2
    json_length, _ = struct.unpack_from("<II", data, 12)
    document = json.loads(data[20:20 + json_length])
    binary = data[20 + json_length + 8:]
    widths = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
    types = {5126: np.float32, 5125: np.uint32}

    def accessor(index):
        a = document["accessors"][index]
        view = document["bufferViews"][a["bufferView"]]
        count = a["count"] * widths[a["type"]]
        values = np.frombuffer(binary, dtype=types[a["componentType"]], count=count,
                               offset=view.get("byteOffset", 0) + a.get("byteOffset", 0))
        return values.reshape(a["count"], widths[a["type"]])

    return document, accessor


def glb_corners(path):
    """Every triangle corner of a GLB as (position, uv with v up), and its material names."""
    document, accessor = glb_parts(path)
    corners = []
    for mesh in document["meshes"]:
        for primitive in mesh["primitives"]:
            positions = accessor(primitive["attributes"]["POSITION"])
            uvs = accessor(primitive["attributes"]["TEXCOORD_0"])
            for i in accessor(primitive["indices"]).ravel():
                corners.append((positions[i].tolist(), [uvs[i][0], 1.0 - uvs[i][1]]))
    return corners, [m["name"] for m in document.get("materials", [])]


def as_set(corners, digits=6):
    return {tuple(np.round(p, digits)) + tuple(np.round(uv, digits)) for p, uv in corners}


def pose(points):
    """A quarter turn about z and a step along x."""
    turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    return np.asarray(points) @ turn.T + [2.0, 0.0, 0.0]


def saved_posed_cube(folder, name):
    """The textured cube read, posed and saved as `name`: (source, written file, posed mesh)."""
    source = textured_cube(folder)
    posed = primo.load_mesh(source).with_vertices(pose(primo.load_mesh(source).vertices))
    out = str(folder / name)
    primo.save_mesh(posed, out)
    return source, out, posed


def test_a_posed_textured_obj_saved_as_obj_keeps_its_uvs_and_materials(tmp_path):
    source, out, _ = saved_posed_cube(tmp_path, "posed.obj")
    corners, materials = obj_corners(out)
    before, source_materials = obj_corners(source)
    assert materials == source_materials == ["red", "blue", "red"]
    assert len(corners) == len(before) == 24
    for (p, uv), (p0, uv0) in zip(corners, before):
        assert np.allclose(uv, uv0, atol=1e-6)
        assert np.allclose(p, pose(p0), atol=1e-12)
    assert "mtllib cube.mtl" in open(out).read()


def test_a_posed_textured_obj_saved_as_glb_keeps_uvs_per_corner_and_materials(tmp_path):
    source, out, posed = saved_posed_cube(tmp_path, "posed.glb")
    corners, materials = glb_corners(out)
    assert materials == ["red", "blue"]
    before, _ = obj_corners(source)
    expected = [(pose(p).tolist(), uv) for p, uv in before]
    # Quads become two triangles: the corners are the same (position, uv) pairs, each to 1e-6.
    assert len(corners) == 36
    assert as_set(corners) == as_set(expected)
    # Read back by primo, the posed mesh carries the attributes again.
    # (Its vertices in the order its corners first use them.)
    again = primo.load_mesh(out)
    assert np.allclose(np.sort(again.vertices, axis=0), np.sort(posed.vertices, axis=0), atol=1e-6)
    primo.save_mesh(again, str(tmp_path / "again.glb"))
    assert as_set(glb_corners(str(tmp_path / "again.glb"))[0]) == as_set(expected)


def test_meshes_made_from_arrays_are_saved_without_attributes(tmp_path):
    read = primo.load_mesh(textured_cube(tmp_path))
    plain = primo.Mesh(read.vertices, read.faces)
    out = str(tmp_path / "plain.glb")
    primo.save_mesh(plain, out)
    document, _ = glb_parts(out)
    assert "materials" not in document
    assert all("TEXCOORD_0" not in p["attributes"]
               for m in document["meshes"] for p in m["primitives"])


def test_a_missing_texture_is_an_error_naming_it_when_a_glb_must_embed_it(tmp_path):
    source = textured_cube(tmp_path)
    os.remove(tmp_path / "red.png")
    posed = primo.load_mesh(source).with_vertices(pose(primo.load_mesh(source).vertices))
    with pytest.raises(primo.Error, match="red.png"):
        primo.save_mesh(posed, str(tmp_path / "posed.glb"))
    assert not (tmp_path / "posed.glb").exists()
