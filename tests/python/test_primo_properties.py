"""Property tests: the primo module never crashes Python, whatever the arguments.

Hypothesis draws arguments of every kind (integers beyond 64 bits, NumPy arrays of every dtype
and shape, NaN and infinities, arbitrary strings and matrices). Each call either works, and
then its result is sound (finite vertices, faces as given), or raises a Python exception; a
crash would take the test run with it. The draws are derandomized so that every run checks
the same cases.

Run by ctest (Python.Module) with the module's other tests.
"""
import math

import numpy as np
import pytest

import primo

hypothesis = pytest.importorskip("hypothesis", reason="python3-hypothesis is not installed")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from hypothesis.extra import numpy as hnp  # noqa: E402

REFUSED = (TypeError, ValueError, IndexError, OverflowError, primo.Error)
SETTINGS = settings(max_examples=150, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow])


def tube(segments=6, bands=4):
    V = [[0.25 * math.cos(2 * math.pi * i / segments), 2.0 * j / bands,
          0.25 * math.sin(2 * math.pi * i / segments)]
         for j in range(bands + 1) for i in range(segments)]
    F = [[j * segments + i, (j + 1) * segments + i, (j + 1) * segments + (i + 1) % segments,
          j * segments + (i + 1) % segments]
         for j in range(bands) for i in range(segments)]
    return np.array(V), np.array(F)


V, F = tube()
MESH = primo.Mesh(V, F)

any_number = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                       st.integers(min_value=-2**70, max_value=2**70))
any_index = st.one_of(st.integers(min_value=-2**70, max_value=2**70),
                      st.integers(min_value=-2, max_value=len(F) + 2),
                      st.floats(allow_nan=True, allow_infinity=True), st.booleans(), st.text(max_size=3))
dtypes = st.one_of(hnp.integer_dtypes(), hnp.unsigned_integer_dtypes(), hnp.floating_dtypes(),
                   hnp.boolean_dtypes())
any_array = hnp.arrays(dtypes, hnp.array_shapes(min_dims=0, max_dims=3, max_side=6))
# Arrays of the right shape, with any float in them (NaN and infinities included).
any_floats = st.floats(allow_nan=True, allow_infinity=True)
points = hnp.arrays(np.float64, st.tuples(st.integers(0, 8), st.just(3)),
                    elements=st.one_of(st.floats(-10, 10), any_floats))
vec3 = st.one_of(st.lists(st.floats(-5, 5), min_size=3, max_size=3), st.lists(any_number, max_size=4))


def refused_or(call, check=lambda result: None):
    """Runs call(); a refusal must be a Python exception, a result must pass check."""
    try:
        result = call()
    except REFUSED:
        return None
    check(result)
    return result


@SETTINGS
@given(st.one_of(st.lists(any_index, max_size=6), any_array))
def test_handles_take_valid_face_lists_and_refuse_the_rest(faces):
    def check(handle):
        assert all(0 <= f < 2**31 for f in handle.faces)
    refused_or(lambda: primo.Handle(faces), check)


@SETTINGS
@given(st.one_of(any_array, points,
                 hnp.arrays(np.float64, V.shape, elements=st.floats(-0.01, 0.01)).map(lambda d: V + d)),
       st.one_of(any_array, st.lists(st.lists(any_index, max_size=5), max_size=4),
                 st.lists(st.lists(st.integers(-1, 9), min_size=3, max_size=5), min_size=1, max_size=6),
                 st.lists(st.sampled_from(F.tolist()), min_size=1, max_size=len(F), unique_by=tuple)))
def test_meshes_take_finite_vertices_and_valid_faces_and_refuse_the_rest(vertices, faces):
    def check(mesh):
        assert np.isfinite(mesh.vertices).all()
        assert all(0 <= i < mesh.n_vertices for face in mesh.faces for i in face)
    refused_or(lambda: primo.Mesh(vertices, faces), check)


@SETTINGS
@given(st.fixed_dictionaries({}, optional={
    "height": any_number, "half_thickness": any_number, "normal_blend": any_number,
    "width": any_number, "height_factors": any_array, "width_factors": any_array}))
def test_deformer_materials_are_checked(kwargs):
    def check(deformer):
        assert deformer.solve(max_iterations=5).energy >= 0.0
        assert np.isfinite(deformer.vertices()).all()
    refused_or(lambda: primo.Deformer(MESH, [primo.Handle([0])], **kwargs), check)


@SETTINGS
@given(st.one_of(st.sampled_from([0, 1]), st.integers(min_value=-2**40, max_value=2**40)),
       st.one_of(st.none(), st.none(), any_array,
                 hnp.arrays(np.float64, (4, 4), elements=st.floats(-2, 2)),
                 st.just(np.eye(4))),
       vec3, vec3, st.one_of(st.floats(-720, 720), any_number), st.one_of(st.none(), vec3))
def test_handle_transforms_are_rigid_and_finite_or_refused(handle, matrix, translate, axis, angle,
                                                           center):
    deformer = primo.Deformer(MESH, [primo.Handle([0]), primo.Handle([len(F) - 1], fix="position")])
    kwargs = {"translate": translate, "axis": axis, "angle_deg": angle, "center": center}
    if matrix is not None:
        kwargs = {"matrix": matrix}
    refused_or(lambda: deformer.set_handle_transform(handle, **kwargs))
    report = deformer.solve(max_iterations=20)
    assert math.isfinite(report.energy)
    assert np.isfinite(deformer.vertices()).all()


@SETTINGS
@given(st.one_of(st.sampled_from(["auto", "global", "hierarchical", "local"]), st.text(max_size=8)),
       st.integers(min_value=-2**40, max_value=2**40), any_number, st.booleans())
def test_solve_settings_are_checked(method, max_iterations, tolerance, path):
    deformer = primo.Deformer(MESH, [primo.Handle([0]), primo.Handle([len(F) - 1])])
    deformer.set_handle_transform(0, translate=[0.1, 0.2, 0.0], axis=[0, 1, 0], angle_deg=30)

    def check(report):
        assert math.isfinite(report.energy) and report.energy >= 0.0
        assert np.isfinite(deformer.vertices()).all()
    # Iterations beyond 200 only lengthen the run: the count's checks are at its bounds.
    iterations = max_iterations if max_iterations < 0 or max_iterations > 2**31 else min(max_iterations, 200)
    refused_or(lambda: deformer.solve(method=method, max_iterations=iterations, tolerance=tolerance,
                                      path=path), check)


@SETTINGS
@given(st.one_of(any_array, hnp.arrays(np.float64, (MESH.n_vertices, 3),
                                         elements=st.one_of(st.floats(-10, 10), any_floats))))
def test_with_vertices_takes_only_finite_arrays_of_the_meshs_shape(vertices):
    def check(mesh):
        assert mesh.n_vertices == MESH.n_vertices and np.isfinite(mesh.vertices).all()
    refused_or(lambda: MESH.with_vertices(vertices), check)


@SETTINGS
@given(st.one_of(st.lists(any_index, max_size=4), st.lists(st.integers(0, len(F) - 1), max_size=4)),
       st.one_of(st.floats(0, 10), any_number), vec3, st.text(max_size=4))
def test_forces_are_checked(faces, stiffness, offset, name):
    def check(force):
        deformer = primo.Deformer(MESH, [primo.Handle([0])], [force])
        refused_or(lambda: deformer.set_force_offset(0, offset))
        assert np.isfinite(deformer.vertices()).all()
    refused_or(lambda: primo.Force(faces, stiffness=stiffness, offset=offset, name=name), check)
