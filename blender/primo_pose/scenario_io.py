"""PriMo scenarios (primo-scenario/1, docs/scenario-format.md) from and to Blender objects.

Export writes the rest mesh as an OBJ beside the scenario and the setup in the object's own
coordinates: every handle and fixed region as `{"faces": [...]}` (Blender's face order, which
the OBJ keeps), each handle's Empty motion as a transform about the Empty's rest position, the
painted factors as one region per value, the material with `half_thickness`, and Blender's
up (+z) and front (-y) for the editor. The module's reader checks the file before it is
written. Import reads a scenario with the module, so its selections and regions are resolved
as `primo deform` resolves them, and builds the object, vertex groups and Empties.
"""

import math
import os

import bpy
import mathutils
import numpy as np

from . import painted_factors, pose_setup

BLENDER_ORIENTATION = {"up": "+z", "front": "-y"}


def rotation_axis_angle(r):
    """(unit axis, angle in degrees, 0 to 180) of a rotation matrix."""
    skew = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    sine = np.linalg.norm(skew) / 2.0
    cosine = (np.trace(r) - 1.0) / 2.0
    angle = math.atan2(sine, cosine)
    if sine > 1e-6:
        return skew / (2.0 * sine), math.degrees(angle)
    if cosine > 0:
        return np.array([0.0, 0.0, 1.0]), 0.0
    # Half a turn: the axis is the direction R leaves fixed, a column of R + I.
    columns = r + np.eye(3)
    axis = columns[:, np.argmax(np.linalg.norm(columns, axis=0))]
    return axis / np.linalg.norm(axis), 180.0


def rotation_matrix(axis, angle_deg):
    axis = np.asarray(axis, dtype=np.float64)
    if angle_deg == 0.0:
        return np.eye(3)
    x, y, z = axis / np.linalg.norm(axis)
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + s * k + (1 - c) * (k @ k)


def area_weighted_centroid(vertices, faces):
    """The handle's centroid as the format defines it: the area-weighted mean of its faces'
    vertex averages, areas from the Newell vector area."""
    total, weighted = 0.0, np.zeros(3)
    for face in faces:
        p = vertices[face]
        c = p.mean(axis=0)
        area = 0.5 * np.linalg.norm(np.cross(p - c, np.roll(p, -1, axis=0) - c).sum(axis=0))
        total += area
        weighted += area * c
    return weighted / total


def _regions(factors, key, label):
    regions = []
    for value in np.unique(factors):
        if value != 1.0:
            regions.append({"name": "%s x%.2f" % (label, value),
                            "select": {"faces": np.flatnonzero(factors == value).tolist()},
                            key: float(value)})
    return regions


def scenario_of(obj, mesh_file):
    """The scenario dict for the object, its mesh named `mesh_file`."""
    setup = pose_setup.PoseSetup(obj)
    world = pose_setup.matrix_array(obj.matrix_world)
    handles, fixed = [], []
    for i, (h, (name, faces, fix)) in enumerate(zip(obj.primo.handles, setup.handles)):
        entry = {"name": name, "select": {"faces": faces.tolist()}, "fix": fix}
        if h.kind == 'HANDLE':
            m = pose_setup.handle_matrix(obj, h)
            rest = np.array(h.rest_matrix, dtype=np.float64).reshape(4, 4)
            center = np.linalg.solve(world, rest[:, 3])[:3]
            axis, angle = rotation_axis_angle(m[:3, :3])
            entry["transform"] = {"translate": (m[:3, :3] @ center + m[:3, 3] - center).tolist(),
                                  "axis": axis.tolist(), "angle_deg": angle, "center": center.tolist()}
        else:
            fixed.append(i)
        handles.append(entry)
    scenario = {
        "format": "primo-scenario/1",
        "mesh": mesh_file,
        "prisms": {"half_thickness": setup.half_thickness, "normal_blend": setup.normal_blend,
                   "width": setup.width},
        "regions": _regions(setup.height_factors, "height", "stiffness")
                   + _regions(setup.width_factors, "width", "width"),
        "handles": handles,
        "editor": {"orientation": dict(BLENDER_ORIENTATION)},
    }
    if fixed:
        scenario["editor"]["fixed_regions"] = fixed
    return scenario, setup


def export_scenario(primo, obj, path):
    """Writes the scenario to `path` and the rest mesh beside it; returns the mesh's path."""
    path = bpy.path.abspath(path)
    mesh_file = os.path.splitext(os.path.basename(path))[0] + ".obj"
    scenario, setup = scenario_of(obj, mesh_file)
    mesh_path = os.path.join(os.path.dirname(path), mesh_file)
    primo.save_scenario(scenario, path)  # checked first: nothing is written if it is refused
    primo.save_mesh(primo.Mesh(setup.vertices, setup.faces), mesh_path)
    return mesh_path


def _vertex_group(obj, name, weights):
    group = obj.vertex_groups.new(name=name)
    for value in np.unique(weights):
        group.add(np.flatnonzero(weights == value).tolist(), float(value), 'REPLACE')
    return group


def import_scenario(primo, context, path):
    """A new mesh object set up as the scenario says, and notes on what Blender cannot hold."""
    path = bpy.path.abspath(path)
    data = primo.load_scenario(path)
    scenario, mesh = data["scenario"], data["mesh"]
    notes = []
    vertices = np.asarray(mesh.vertices)
    faces = [list(map(int, f)) for f in mesh.faces]
    name = os.path.splitext(os.path.basename(path))[0]
    blender_mesh = bpy.data.meshes.new(name)
    blender_mesh.from_pydata(vertices.tolist(), [], faces)
    blender_mesh.update()
    obj = bpy.data.objects.new(name, blender_mesh)
    context.collection.objects.link(obj)
    settings = obj.primo

    prisms = scenario.get("prisms", {})
    if "half_thickness" in prisms:
        settings.thickness_percent = prisms["half_thickness"] * 100.0
    else:
        # `height` counts mean edge lengths; the add-on states thickness per diagonal.
        edges = {tuple(sorted((f[k], f[(k + 1) % len(f)]))) for f in faces for k in range(len(f))}
        edges = np.array(sorted(edges))
        mean_edge = np.linalg.norm(vertices[edges[:, 0]] - vertices[edges[:, 1]], axis=1).mean()
        settings.thickness_percent = 100.0 * prisms.get("height", 1.0) * mean_edge / mesh.bbox_diagonal
        notes.append("prisms.height %g mean edge lengths became a thickness of %.3f%% of the diagonal"
                     % (prisms.get("height", 1.0), settings.thickness_percent))
    settings.normal_blend = prisms.get("normal_blend", 0.0)
    settings.width = prisms.get("width", 1.0)

    corners = np.concatenate([np.asarray(f) for f in faces])
    starts = np.cumsum([0] + [len(f) for f in faces[:-1]])
    for factors, group_name, to_weight, factor_range in (
            (data["height_factors"], settings.stiffness_group, painted_factors.stiffness_weight,
             painted_factors.STIFFNESS_RANGE),
            (data["width_factors"], settings.width_group, painted_factors.width_weight,
             painted_factors.WIDTH_RANGE)):
        factors = np.asarray(factors)
        if np.all(factors == 1.0):
            continue
        if factors.min() < factor_range[0] or factors.max() > factor_range[1]:
            notes.append("%s: factors beyond %g to %g were clamped" % (group_name, *factor_range))
        if np.any(np.round(factors, 2) != factors):
            notes.append("%s: factors are kept to hundredths" % group_name)
        _vertex_group(obj, group_name,
                      painted_factors.vertex_weights_for(factors, corners, starts, len(vertices), to_weight))

    fixed = set(scenario.get("editor", {}).get("fixed_regions", []))
    for i, entry in enumerate(scenario.get("handles", [])):
        handle_faces = data["handle_faces"][i]
        transform = entry.get("transform", {})
        angle = transform.get("angle_deg", 0.0)
        moved = angle != 0.0 or any(transform.get("translate", [0, 0, 0]))
        kind = 'FIXED' if i in fixed and not moved and entry["fix"] == "all" else 'HANDLE'
        handle = settings.handles.add()
        handle.name = entry.get("name") or "%s %d" % ("Fixed" if kind == 'FIXED' else "Handle", i + 1)
        handle.kind = kind
        handle.fix = entry["fix"].upper()
        in_group = np.zeros(len(vertices))
        in_group[np.concatenate([np.asarray(faces[f]) for f in handle_faces])] = 1.0
        handle.vertex_group = _vertex_group(obj, "PriMo " + handle.name, in_group).name
        if kind == 'HANDLE':
            centroid = area_weighted_centroid(vertices, [faces[f] for f in handle_faces])
            center = np.asarray(transform.get("center", centroid), dtype=np.float64)
            r = rotation_matrix(transform.get("axis", [0, 0, 1]), angle)
            motion = np.eye(4)
            motion[:3, :3] = r
            motion[:3, 3] = center - r @ center + np.asarray(transform.get("translate", [0, 0, 0]))
            if abs(angle) > 180.0:
                notes.append("handle '%s': its turn of %g degrees is shown as %g (an Empty's "
                             "matrix keeps no whole turns)" % (handle.name, angle,
                                                                rotation_axis_angle(r)[1]))
            rest = np.eye(4)
            rest[:3, 3] = centroid
            empty = pose_setup.make_handle_empty(handle, "PriMo " + name + " " + handle.name, rest,
                                                 mesh.bbox_diagonal * 0.1, context.collection)
            empty.matrix_world = mathutils.Matrix((motion @ rest).tolist())
    if scenario.get("forces"):
        notes.append("%d spring(s) not imported: the add-on has handles and fixed regions only"
                     % len(scenario["forces"]))
    return obj, notes
