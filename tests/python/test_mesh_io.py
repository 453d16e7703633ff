# SPDX-License-Identifier: MIT
"""cleave.read_mesh on files trimesh writes (OBJ, OFF, STL, PLY, GLB) and cleave.write_mesh round
trips, checked against trimesh's own reading of the same meshes."""
import numpy as np
import pytest
import trimesh

import cleave
from conftest import as_trimesh


@pytest.mark.parametrize("extension", ["obj", "off", "stl", "ply", "glb"])
def test_reads_what_trimesh_writes(tmp_path, sphere, extension):
    path = tmp_path / f"sphere.{extension}"
    sphere.export(path)
    vertices, faces, normals, uvs = cleave.read_mesh(path)
    assert vertices.dtype == np.float32 and vertices.shape[1] == 3
    assert faces.dtype == np.int64 and faces.shape == (len(sphere.faces), 3)
    assert normals is None or normals.shape == vertices.shape
    assert uvs is None or uvs.shape == (len(vertices), 2)
    read = as_trimesh(vertices, faces)
    assert read.is_watertight
    assert read.volume == pytest.approx(sphere.volume, rel=1e-5)


@pytest.mark.parametrize("extension", ["obj", "glb"])
def test_write_then_read_keeps_the_mesh(tmp_path, torus, extension):
    normals = torus.vertex_normals.astype(np.float32)
    uvs = (torus.vertices[:, :2] * 0.25 + 0.5).astype(np.float32)
    path = tmp_path / f"torus.{extension}"
    cleave.write_mesh(path, torus.vertices, torus.faces, normals=normals, uvs=uvs)
    vertices, faces, read_normals, read_uvs = cleave.read_mesh(str(path))
    assert len(faces) == len(torus.faces)
    np.testing.assert_allclose(vertices[faces], torus.vertices[torus.faces], atol=1e-6)
    np.testing.assert_allclose(read_normals[faces], normals[torus.faces], atol=1e-6)
    np.testing.assert_allclose(read_uvs[faces], uvs[torus.faces], atol=1e-6)
    plain = tmp_path / f"plain.{extension}"  # without UVs, which trimesh would read with Pillow
    cleave.write_mesh(plain, torus.vertices, torus.faces, normals=normals)
    loaded = trimesh.load(plain, force="mesh")
    assert len(loaded.faces) == len(torus.faces)
    assert loaded.volume == pytest.approx(torus.volume, rel=1e-5)


def test_pieces_written_and_read_back_are_still_watertight(tmp_path, torus):
    pieces = cleave.split(torus.vertices, torus.faces, normal=(0.2, 0.3, 1.0), offset=0.05)
    assert len(pieces) == 2
    for k, piece in enumerate(pieces):
        path = tmp_path / f"piece_{k}.obj"
        cleave.write_mesh(path, piece.vertices, piece.faces)
        loaded = trimesh.load(path, force="mesh")
        assert loaded.is_watertight
        assert loaded.volume == pytest.approx(piece.volume, rel=1e-6)
