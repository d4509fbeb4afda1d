"""The primo Python module: arrays in and out, deformers, scenarios, sessions and errors.

Run by ctest (Python.Module) with PYTHONPATH set to the build's python/ folder; by hand:
    PYTHONPATH=build/python /usr/bin/python3 -m pytest -q tests/python
"""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import primo

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ASSETS = os.path.join(SOURCE, "assets")
SHARED_MESHES = os.path.join(os.path.dirname(SOURCE), "shared", "meshes")


def tube(segments=12, bands=20, radius=0.25, length=2.0):
    """An open quad tube along +y."""
    V = [[radius * math.cos(2 * math.pi * i / segments), length * j / bands,
          radius * math.sin(2 * math.pi * i / segments)]
         for j in range(bands + 1) for i in range(segments)]
    F = [[j * segments + i, (j + 1) * segments + i, (j + 1) * segments + (i + 1) % segments,
          j * segments + (i + 1) % segments]
         for j in range(bands) for i in range(segments)]
    return np.array(V), np.array(F)


def test_arrays_round_trip_and_polygons_stay_polygons(tmp_path):
    V, F = tube()
    mesh = primo.Mesh(V, F)
    assert (mesh.n_vertices, mesh.n_faces) == (len(V), len(F))
    assert np.array_equal(mesh.vertices, V)
    assert mesh.faces.shape == F.shape and np.array_equal(mesh.faces, F)
    # Mixed polygons come back as lists, in file order.
    square_and_triangle = primo.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]],
                                     [[0, 1, 2, 3], [1, 4, 2]])
    assert square_and_triangle.faces == [[0, 1, 2, 3], [1, 4, 2]]
    path = str(tmp_path / "tube.obj")
    primo.save_mesh(mesh, path)
    again = primo.load_mesh(path)
    assert np.allclose(again.vertices, V, atol=1e-15) and np.array_equal(again.faces, F)


def test_bad_input_raises_primo_errors_with_the_cores_messages(tmp_path):
    with pytest.raises(primo.Error, match="face 0"):
        primo.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 7]])
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        primo.Mesh(np.zeros((4, 2)), [[0, 1, 2]])
    missing = str(tmp_path / "missing.obj")
    with pytest.raises(primo.Error, match="missing.obj"):
        primo.load_mesh(missing)
    mesh = primo.Mesh(*tube())
    with pytest.raises(primo.Error, match="out of range"):
        primo.Deformer(mesh, [primo.Handle([10**6])])
    with pytest.raises(ValueError, match="fix"):
        primo.Handle([0], fix="sideways")
    d = primo.Deformer(mesh, [primo.Handle([0])])
    with pytest.raises(IndexError):
        d.set_handle_transform(3, translate=[0, 1, 0])
    with pytest.raises(ValueError, match="rotation"):
        d.set_handle_transform(0, matrix=np.diag([2.0, 1.0, 1.0, 1.0]))


def test_hostile_scene_files_raise_instead_of_crashing_python(tmp_path):
    # Assimp reads scene files in a child process: what crashed it (a COLLADA node that
    # instances itself, an FBX model that is its own parent) is a primo.Error here.
    cube = open(os.path.join(SOURCE, "tests", "data", "scenes", "cube_emptyTags.dae")).read()
    looped = tmp_path / "own-instance.dae"
    looped.write_text(cube.replace('<instance_geometry url="#box-lib">',
                                   '<instance_node url="#Box"/><instance_geometry url="#box-lib">', 1))
    with pytest.raises(primo.Error, match="own-instance.dae: cannot read"):
        primo.load_mesh(str(looped))
    fbx = tmp_path / "own-parent.fbx"
    fbx.write_text('; FBX 7.4.0 project file\nObjects:  {\n\tModel: 2000, "Model::m", "Mesh" {\n\t}\n}\n'
                   'Connections:  {\n\tC: "OO",2000,0\n\tC: "OO",2000,2000\n}\n')
    with pytest.raises(primo.Error, match="own-parent.fbx: cannot read"):
        primo.load_mesh(str(fbx))
    assert primo.load_mesh(os.path.join(SOURCE, "tests", "data", "scenes", "box.3mf")).n_faces == 12


def test_a_bent_tube_follows_its_handles_and_drags_back_to_rest():
    V, F = tube()
    mesh = primo.Mesh(V, F)
    c = mesh.face_centroids()
    bottom, top = c[:, 1] < 0.15, c[:, 1] > 1.85
    d = primo.Deformer(mesh, [primo.Handle(bottom), primo.Handle(top, name="top")])
    d.set_handle_transform(1, translate=[0.5, -0.3, 0], axis=[0, 0, 1], angle_deg=60)
    report = d.solve(tolerance=1e-10)
    assert report.converged and report.energy > 0
    X = d.vertices()
    assert X.shape == V.shape and X.dtype == np.float64
    assert np.abs(X - V).max() > 0.3
    # The top ring moved rigidly to its target: rotate about the handle's centroid (its faces'
    # area-weighted centroid at rest), then translate.
    top_vertices = V[:, 1] > 1.99
    centre = c[top].mean(axis=0)
    a = math.radians(60)
    R = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    expected = (V[top_vertices] - centre) @ R.T + centre + [0.5, -0.3, 0]
    assert np.abs(X[top_vertices] - expected).max() < 1e-3
    # The same target as a 4x4 matrix gives the same pose.
    M = np.eye(4)
    M[:3, :3] = R
    M[:3, 3] = centre - R @ centre + [0.5, -0.3, 0]
    d2 = primo.Deformer(mesh, [primo.Handle(bottom), primo.Handle(top)])
    d2.set_handle_transform(1, matrix=M)
    d2.solve(tolerance=1e-10)
    assert np.abs(d2.vertices() - X).max() < 1e-6 * mesh.bbox_diagonal
    # Back to rest: the rest pose is the unique minimum.
    d.set_handle_transform(1)
    d.solve(tolerance=1e-12)
    assert np.abs(d.vertices() - V).max() < 1e-6 * mesh.bbox_diagonal


def test_springs_prisms_and_painted_factors_change_the_pose():
    V, F = tube()
    mesh = primo.Mesh(V, F)
    c = mesh.face_centroids()
    bottom, top = c[:, 1] < 0.15, c[:, 1] > 1.85
    # A weak spring: the tube's stiffness decides how far it goes.
    spring = primo.Deformer(mesh, [primo.Handle(bottom)], [primo.Force(top, stiffness=0.01, offset=[0.6, 0, 0])])
    spring.solve(tolerance=1e-10)
    pulled = spring.vertices()
    assert pulled[V[:, 1] > 1.99, 0].mean() > 0.2
    # A softer middle (height factors below 1) bends more under the same pull.
    soft = np.where(np.abs(c[:, 1] - 1.0) < 0.3, 0.3, 1.0)
    softer = primo.Deformer(mesh, [primo.Handle(bottom)], [primo.Force(top, stiffness=0.01, offset=[0.6, 0, 0])],
                            height_factors=soft)
    softer.solve(tolerance=1e-10)
    assert softer.vertices()[V[:, 1] > 1.99, 0].mean() > pulled[V[:, 1] > 1.99, 0].mean() + 0.005
    with pytest.raises(ValueError, match="at most one"):
        primo.Deformer(mesh, [primo.Handle(bottom)], height=1.0, half_thickness=0.1)


def test_the_vertices_array_owns_its_memory_without_a_copy():
    mesh = primo.Mesh(*tube())
    d = primo.Deformer(mesh, [primo.Handle([0])])
    X = d.vertices()
    assert X.flags["C_CONTIGUOUS"] and not X.flags["OWNDATA"]  # a view of the solver's vector
    del d
    assert np.isfinite(X).all()  # still valid: the array keeps the vector alive


def test_a_scenario_solves_as_primo_deform_does(tmp_path):
    scenario = os.path.join(ASSETS, "scenarios", "bar-bend.json")
    X, report = primo.deform_scenario(scenario)
    assert report.converged
    out = str(tmp_path / "bar.obj")
    exe = os.environ.get("PRIMO_EXECUTABLE")
    if not exe:
        pytest.skip("PRIMO_EXECUTABLE not set: cannot compare with primo deform")
    subprocess.run([exe, "deform", scenario, "-o", out], check=True, capture_output=True)
    assert np.abs(primo.load_mesh(out).vertices - X).max() < 1e-12
    with pytest.raises(primo.Error, match="no-such.json"):
        primo.deform_scenario(str(tmp_path / "no-such.json"))


def test_scenarios_load_resolved_and_save_checked(tmp_path):
    loaded = primo.load_scenario(os.path.join(ASSETS, "scenarios", "bar-bend.json"))
    scenario, mesh = loaded["scenario"], loaded["mesh"]
    assert scenario["format"] == "primo-scenario/1" and scenario["mesh"] == "../meshes/bar.obj"
    assert os.path.samefile(loaded["mesh_path"], os.path.join(ASSETS, "meshes", "bar.obj"))
    # The box selections resolved as primo deform resolves them: faces whose centroid is inside.
    c = mesh.face_centroids()
    for faces, handle in zip(loaded["handle_faces"], scenario["handles"]):
        box = handle["select"]["box"]
        inside = np.all((c >= box["min"]) & (c <= box["max"]), axis=1)
        assert faces == np.flatnonzero(inside).tolist() and faces
    assert loaded["height_factors"] == [1.0] * mesh.n_faces == loaded["width_factors"]

    # Saved beside a copy of its mesh, it solves as the original does.
    primo.save_mesh(mesh, str(tmp_path / "bar.obj"))
    scenario["mesh"] = "bar.obj"
    scenario["regions"] = [{"select": {"faces": [0, 1, 2]}, "height": 0.5}]
    primo.save_scenario(scenario, str(tmp_path / "copy.json"))
    again = primo.load_scenario(str(tmp_path / "copy.json"))
    assert again["handle_faces"] == loaded["handle_faces"]
    assert again["height_factors"][:4] == [0.5, 0.5, 0.5, 1.0]

    # What the reader refuses is not written, and the message names the file and the key.
    scenario["handels"] = []
    with pytest.raises(primo.Error, match=r"refused\.json.*handels"):
        primo.save_scenario(scenario, str(tmp_path / "refused.json"))
    assert not (tmp_path / "refused.json").exists()
    with pytest.raises(primo.Error, match="missing.json"):
        primo.load_scenario(str(tmp_path / "missing.json"))


def test_a_recorded_session_replays():
    session = os.path.join(ASSETS, "sessions", "spot-pose.session.json")
    result = primo.replay_session(session)
    assert result["frames"] > 0 and result["converged"]
    assert result["vertices"].shape == (2930, 3)


def test_results_do_not_depend_on_the_thread_count():
    V, F = tube(segments=48, bands=120)
    mesh = primo.Mesh(V, F)
    c = mesh.face_centroids()
    results = []
    for threads in (1, 2, 3):
        primo.set_thread_count(threads)
        d = primo.Deformer(mesh, [primo.Handle(c[:, 1] < 0.1), primo.Handle(c[:, 1] > 1.9)])
        d.set_handle_transform(1, axis=[1, 0, 0], angle_deg=90, translate=[0, -0.5, 0.5])
        d.solve(method="hierarchical", max_iterations=5, tolerance=0)
        results.append(d.vertices())
    primo.set_thread_count(0)
    assert all(np.array_equal(r, results[0]) for r in results)


def test_objects_never_initialised_raise_instead_of_crashing():
    # Type.__new__(Type) makes an instance whose __init__ never ran: its methods and the
    # functions taking it raise TypeError.
    mesh = primo.Mesh.__new__(primo.Mesh)
    with pytest.raises(TypeError, match="Mesh.__init__ was not called"):
        mesh.n_faces
    with pytest.raises(TypeError, match="Mesh.__init__ was not called"):
        primo.Deformer(mesh)
    d = primo.Deformer.__new__(primo.Deformer)
    for use in (lambda: d.energy, lambda: d.vertices(), lambda: d.solve(), lambda: d.reset(),
                lambda: d.set_handle_transform(0)):
        with pytest.raises(TypeError, match="Deformer.__init__ was not called"):
            use()
    good = primo.Mesh(*tube())
    for cls in (primo.Handle, primo.Force):
        with pytest.raises(TypeError, match="__init__ was not called"):
            primo.Deformer(good, [cls.__new__(cls)] if cls is primo.Handle else [],
                           [cls.__new__(cls)] if cls is primo.Force else [])
    with pytest.raises(TypeError, match="expected a primo.Mesh"):
        primo.Mesh.n_faces.fget(42)


def test_arguments_are_checked_as_the_scenario_reader_checks_them():
    V, F = tube()
    mesh = primo.Mesh(V, F)
    # Indices: integers within range, never truncated floats or wrapped 64-bit values.
    with pytest.raises(IndexError, match="out of range"):
        primo.Handle(np.array([2**32 + 2]))
    with pytest.raises(IndexError, match="out of range"):
        primo.Handle([2**40])
    with pytest.raises(IndexError, match="out of range"):
        primo.Handle([-1])
    with pytest.raises(TypeError, match="integer"):
        primo.Handle(np.array([1.7]))
    with pytest.raises(TypeError, match="integer"):
        primo.Handle([1.0])
    with pytest.raises(TypeError, match="integer"):
        primo.Mesh(V, F.astype(np.float64))
    with pytest.raises(IndexError, match="out of range"):
        primo.Mesh(V, F.astype(np.uint64) + np.uint64(2**63))
    bad_vertices = V.copy()
    bad_vertices[3, 1] = np.nan
    with pytest.raises(ValueError, match="row 3 is not finite"):
        primo.Mesh(bad_vertices, F)
    with pytest.raises(ValueError, match="not finite"):
        mesh.with_vertices(bad_vertices)
    # Materials, forces and solver settings.
    for kwargs in ({"height": -1.0}, {"half_thickness": float("nan")}, {"width": 0.0},
                   {"normal_blend": float("inf")},
                   {"width_factors": np.zeros(len(F))}, {"height_factors": -np.ones(len(F))}):
        with pytest.raises(ValueError):
            primo.Deformer(mesh, [primo.Handle([0])], **kwargs)
    with pytest.raises(ValueError, match="stiffness"):
        primo.Force([1], stiffness=-1.0)
    with pytest.raises(ValueError, match="offset"):
        primo.Force([1], offset=[0, float("nan"), 0])
    d = primo.Deformer(mesh, [primo.Handle([0])])
    with pytest.raises(ValueError, match="method"):
        d.solve(method="bogus")
    with pytest.raises(ValueError, match="tolerance"):
        d.solve(tolerance=float("nan"))
    with pytest.raises(ValueError, match="max_iterations"):
        d.solve(max_iterations=-1)
    not_rigid = np.eye(4)
    not_rigid[3, 0] = 0.5
    with pytest.raises(ValueError, match="bottom row"):
        d.set_handle_transform(0, matrix=not_rigid)
    with pytest.raises(ValueError, match="finite"):
        d.set_handle_transform(0, translate=[0, float("inf"), 0])
    with pytest.raises(ValueError, match="threads"):
        primo.set_thread_count(-2)
    # Nothing refused changed the deformer.
    assert d.solve().converged and d.energy == 0.0


def test_threads_may_share_a_deformer_and_change_the_thread_count():
    # Two threads solving one Deformer take turns, and a thread-count change waits for the
    # running solves: every run ends where a solve on one thread ends.
    import threading
    V, F = tube(segments=40, bands=80)
    mesh = primo.Mesh(V, F)
    c = mesh.face_centroids()

    def posed():
        d = primo.Deformer(mesh, [primo.Handle(c[:, 1] < 0.1), primo.Handle(c[:, 1] > 1.9)])
        d.set_handle_transform(1, axis=[1, 0, 0], angle_deg=70, translate=[0, -0.4, 0.4])
        return d

    reference = posed()
    reference.solve(method="hierarchical", tolerance=1e-10, max_iterations=500)
    shared = posed()
    errors = []

    def solve():
        try:
            shared.solve(method="hierarchical", tolerance=1e-10, max_iterations=500)
            shared.vertices()
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    def change_threads():
        for threads in (1, 2, 0, 3, 0):
            primo.set_thread_count(threads)

    workers = [threading.Thread(target=solve) for _ in range(3)] + [threading.Thread(target=change_threads)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    primo.set_thread_count(0)
    assert not errors
    assert np.abs(shared.vertices() - reference.vertices()).max() < 1e-6 * mesh.bbox_diagonal


def test_the_documented_example_poses_the_armadillos_arm(tmp_path):
    armadillo = os.path.join(SHARED_MESHES, "armadillo_29k.obj")
    if not os.path.exists(armadillo):
        pytest.skip("skipped: ../shared/meshes/armadillo_29k.obj is not here")
    example = os.path.join(SOURCE, "docs", "examples", "pose_armadillo_arm.py")
    out = str(tmp_path / "posed.obj")
    run = subprocess.run([sys.executable, example, armadillo, out], capture_output=True, text=True,
                         env=dict(os.environ))
    assert run.returncode == 0, run.stderr
    assert "converged=True" in run.stdout
    rest, posed = primo.load_mesh(armadillo).vertices, primo.load_mesh(out).vertices
    moved = np.linalg.norm(posed - rest, axis=1)
    hand = (rest[:, 0] > 0.33) & (rest[:, 1] > 0)
    assert moved[hand].min() > 0.1  # the hand went up
    assert moved[rest[:, 1] < -0.5].max() < 1e-9  # the feet stayed
