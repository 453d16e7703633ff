# SPDX-License-Identifier: MIT
"""Bad input raises ValueError (or OSError for files) with the reason, and never crashes."""
import os

import numpy as np
import pytest

import cleave


def cube():
    vertices = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
    faces = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                      [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]], dtype=np.int64)
    return vertices, faces


def with_value(array, index, value):
    out = np.array(array, dtype=np.float64)
    out[index] = value
    return out


V, F = cube()

BAD_SPLITS = [
    ("nan vertex", dict(vertices=with_value(V, (3, 1), np.nan)), r"vertices\[3, 1\] is NaN"),
    ("infinite vertex", dict(vertices=with_value(V, (2, 0), -np.inf)), r"vertices\[2, 0\] is infinite"),
    ("beyond float32", dict(vertices=with_value(V, (0, 2), 1e39)), r"does not fit a float32"),
    ("index out of range", dict(faces=np.where(F == 7, 8, F)), r"out of range \(8 vertices"),
    ("negative index", dict(faces=np.where(F == 7, -1, F)), r"= -1 is out of range"),
    ("huge unsigned index", dict(faces=F.astype(np.uint64) + np.uint64(2**63)), r"out of range"),
    ("float faces", dict(faces=F.astype(np.float64)), r"faces must be an array of integers, not of dtype float64"),
    ("bool faces", dict(faces=F > 3), r"faces must be an array of integers"),
    ("complex vertices", dict(vertices=V.astype(complex)), r"real numbers, not of dtype complex128"),
    ("string vertices", dict(vertices=V.astype(str)), r"real numbers"),
    ("object vertices", dict(vertices=np.array([[1, "a", None]] * 8, dtype=object)), r"real numbers"),
    ("vertices N x 2", dict(vertices=V[:, :2]), r"shape \(N, 3\), not \(8, 2\)"),
    ("flat vertices", dict(vertices=V.ravel()), r"shape \(N, 3\), not \(24,\)"),
    ("faces N x 4", dict(faces=np.hstack([F, F[:, :1]])), r"faces must have shape \(N, 3\)"),
    ("no faces", dict(faces=np.zeros((0, 3), dtype=np.int64)), r"faces is empty"),
    ("no vertices", dict(vertices=np.zeros((0, 3))), r"vertices is empty"),
    ("ragged list", dict(vertices=[[0, 0, 0], [1, 1]]), r"vertices is not an array of numbers"),
    ("None vertices", dict(vertices=None), r"vertices must be an array, not None"),
    ("normals rows", dict(normals=np.zeros((3, 3))), r"normals has 3 rows but there are 8 vertices"),
    ("nan normal", dict(normals=with_value(np.ones((8, 3)), (5, 2), np.nan)), r"normals\[5, 2\] is NaN"),
    ("uvs shape", dict(uvs=np.zeros((8, 3))), r"uvs must have shape \(N, 2\)"),
    ("inf uv", dict(uvs=with_value(np.zeros((8, 2)), (1, 1), np.inf)), r"uvs\[1, 1\] is infinite"),
    ("unknown open word", dict(open="close"), r"open must be one of refuse, cap-closed, bridge, not 'close'"),
    ("open not a word", dict(open=3), r"open must be one of"),
    ("unknown uv word", dict(uv="planar"), r"uv must be one of world, bounds, not 'planar'"),
    ("unknown islands word", dict(islands="all"), r"islands must be one of touching, connected"),
    ("islands a number", dict(islands=2), r"islands must be True, False, 'touching' or 'connected', not 2"),
    ("zero normal", dict(normal=(0, 0, 0)), r"normal must not be zero"),
    ("nan normal", dict(normal=(0, np.nan, 1)), r"normal must be finite"),
    ("two-number normal", dict(normal=(0, 1)), r"normal must be three real numbers"),
    ("text normal", dict(normal="up"), r"normal must be three real numbers"),
    ("nan offset", dict(offset=float("nan")), r"offset must be finite"),
]


@pytest.mark.parametrize("case, change, message", BAD_SPLITS, ids=[c[0] for c in BAD_SPLITS])
def test_bad_split_arguments_raise_value_error(case, change, message):
    arguments = dict(vertices=V, faces=F, offset=0.5)
    arguments.update(change)
    with pytest.raises(ValueError, match=message):
        cleave.split(**arguments)


def test_a_plane_that_misses_the_mesh_raises_split_error():
    with pytest.raises(cleave.SplitError, match="PlaneMissesMesh") as missed:
        cleave.split(V, F, normal=(0, 1, 0), offset=5.0)
    assert missed.value.status == "PlaneMissesMesh"
    assert isinstance(missed.value, ValueError)


def test_a_degenerate_mesh_does_not_crash():
    flat = np.zeros((3, 3))
    with pytest.raises(cleave.SplitError):
        cleave.split(flat, [[0, 1, 2]], offset=0.0)
    line = np.array([[0, -1, 0], [0, 1, 0], [0, 1, 0]], dtype=float)
    try:
        pieces = cleave.split(line, [[0, 1, 2], [2, 1, 0]], offset=0.0)
    except cleave.SplitError:
        pieces = []
    for piece in pieces:
        assert np.isfinite(piece.volume)


def test_missing_file_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        cleave.read_mesh(tmp_path / "nothing.obj")


def test_folder_raises_is_a_directory(tmp_path):
    (tmp_path / "folder.obj").mkdir()
    with pytest.raises(IsADirectoryError):
        cleave.read_mesh(str(tmp_path / "folder.obj"))


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads files whatever their mode")
def test_unreadable_file_raises_permission_error(tmp_path):
    path = tmp_path / "locked.obj"
    path.write_text("v 0 0 0\n")
    path.chmod(0)
    with pytest.raises(PermissionError):
        cleave.read_mesh(path)


@pytest.mark.parametrize("name, content, message", [
    ("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", r"bad\.obj:4: .*out of range"),
    ("words.obj", "v 0 0 zero\n", r"words\.obj:1:"),
    ("empty.stl", "", r"empty\.stl"),
    ("short.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nend_header\n", r"short\.ply"),
    ("nan.off", "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n", r"nan\.off"),
    ("junk.glb", "not a glb at all", r"junk\.glb"),
])
def test_a_file_the_reader_refuses_raises_value_error_with_the_reason(tmp_path, name, content, message):
    path = tmp_path / name
    path.write_text(content)
    with pytest.raises(ValueError, match=message):
        cleave.read_mesh(path)


def test_unknown_extension_raises_value_error(tmp_path):
    path = tmp_path / "mesh.xyz"
    path.write_text("v 0 0 0\n")
    with pytest.raises(ValueError, match="unknown mesh format"):
        cleave.read_mesh(path)


def test_write_mesh_refuses_bad_paths_and_arrays(tmp_path):
    with pytest.raises(ValueError, match=r"writes \.obj and \.glb"):
        cleave.write_mesh(tmp_path / "mesh.stl", V, F)
    with pytest.raises(FileNotFoundError):
        cleave.write_mesh(tmp_path / "no" / "such" / "mesh.obj", V, F)
    folder = tmp_path / "folder.obj"
    folder.mkdir()
    with pytest.raises(IsADirectoryError):
        cleave.write_mesh(folder, V, F)
    with pytest.raises(ValueError, match="out of range"):
        cleave.write_mesh(tmp_path / "mesh.obj", V, F + 1)
    with pytest.raises(ValueError, match="NaN"):
        cleave.write_mesh(tmp_path / "mesh.glb", with_value(V, (0, 0), np.nan), F)
    assert not (tmp_path / "mesh.obj").exists() and not (tmp_path / "mesh.glb").exists()

