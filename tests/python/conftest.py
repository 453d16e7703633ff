# SPDX-License-Identifier: MIT
"""Shared helpers of the Python tests: meshes made by trimesh (independent of the engine's own
primitives) and checks of pieces with trimesh."""
import os

import numpy as np
import pytest
import trimesh

import cleave

SOURCE_DIR = os.environ.get("CLEAVE_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))


def as_trimesh(vertices, faces):
    """A trimesh of the arrays with vertices at equal positions merged (seams of normals or UVs and
    the cap's own vertices), so that watertightness is judged on positions."""
    mesh = trimesh.Trimesh(vertices=np.asarray(vertices, dtype=np.float64), faces=faces, process=False)
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    return mesh


def expect_closed_pieces(pieces):
    """Every piece is closed by cleave's account and watertight and consistently wound by trimesh's,
    with a positive volume that matches trimesh's."""
    for piece in pieces:
        checked = as_trimesh(piece.vertices, piece.faces)
        assert piece.closed
        assert checked.is_watertight, piece
        assert checked.is_winding_consistent, piece
        assert piece.volume > 0
        assert checked.volume == pytest.approx(piece.volume, rel=1e-6, abs=1e-12)  # cleave integrates the exact cut points, trimesh their float32 rounding


def expect_sides(pieces, normal, offset, tolerance=1e-5):
    """Pieces of side +1 lie above the plane, those of side -1 below (within float rounding)."""
    unit = np.asarray(normal, dtype=np.float64)
    length = np.linalg.norm(unit)
    unit, offset = unit / length, offset / length
    for piece in pieces:
        heights = piece.vertices.astype(np.float64) @ unit - offset
        if piece.side > 0:
            assert heights.min() >= -tolerance, piece
        else:
            assert piece.side == -1
            assert heights.max() <= tolerance, piece


@pytest.fixture
def unit_cube():
    """The cube [0, 1]^3, 8 vertices and 12 triangles wound outwards."""
    return trimesh.creation.box(extents=(1.0, 1.0, 1.0), transform=trimesh.transformations.translation_matrix((0.5, 0.5, 0.5)))


@pytest.fixture
def torus():
    """A torus around the z axis: major radius 1, minor radius 0.25."""
    return trimesh.creation.torus(major_radius=1.0, minor_radius=0.25, major_sections=64, minor_sections=32)


@pytest.fixture
def sphere():
    """An icosphere of radius 1 (642 vertices)."""
    return trimesh.creation.icosphere(subdivisions=3, radius=1.0)
