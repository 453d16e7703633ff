# SPDX-License-Identifier: MIT
"""cleave.split on meshes made by trimesh, checked with trimesh: exact box pieces, watertight pieces
whose volumes add up to the input's, sides, a torus's pieces and caps, the options' words."""
import re
import os

import numpy as np
import pytest
import trimesh

import cleave
from conftest import SOURCE_DIR, as_trimesh, expect_closed_pieces, expect_sides


def box_inertia(volume, a, b, c):
    """Inertia of a solid box of sides a, b, c (density 1) about its centre."""
    return np.diag([volume * (b * b + c * c) / 12, volume * (a * a + c * c) / 12, volume * (a * a + b * b) / 12])


def test_box_cut_gives_exact_volumes_centres_and_inertia(unit_cube):
    pieces = cleave.split(unit_cube.vertices, unit_cube.faces, normal=(1, 0, 0), offset=0.25)
    assert [p.side for p in pieces] == [1, -1]
    above, below = pieces
    assert above.volume == pytest.approx(0.75, abs=1e-12)
    assert below.volume == pytest.approx(0.25, abs=1e-12)
    np.testing.assert_allclose(above.center_of_mass, [0.625, 0.5, 0.5], atol=1e-12)
    np.testing.assert_allclose(below.center_of_mass, [0.125, 0.5, 0.5], atol=1e-12)
    np.testing.assert_allclose(above.inertia, box_inertia(0.75, 0.75, 1, 1), atol=1e-12)
    np.testing.assert_allclose(below.inertia, box_inertia(0.25, 0.25, 1, 1), atol=1e-12)
    assert above.cap_triangles >= 2 and above.cap_loops == 1
    expect_closed_pieces(pieces)
    expect_sides(pieces, (1, 0, 0), 0.25)


def test_piece_arrays_have_the_documented_types(unit_cube):
    piece = cleave.split(unit_cube.vertices, unit_cube.faces, offset=0.5)[0]
    assert piece.vertices.dtype == np.float32 and piece.vertices.shape[1] == 3
    assert piece.faces.dtype == np.int64 and piece.faces.shape[1] == 3
    assert piece.faces.min() >= 0 and piece.faces.max() < len(piece.vertices)
    assert piece.center_of_mass.shape == (3,) and piece.inertia.shape == (3, 3)
    np.testing.assert_allclose(piece.inertia, piece.inertia.T)
    assert piece.normals is None and piece.uvs is None
    assert piece.source_triangles.shape == (len(piece.faces),)
    caps = piece.source_triangles == -1
    assert caps.sum() == piece.cap_triangles
    assert piece.source_triangles[~caps].max() < len(unit_cube.faces)
    assert "side=1" in repr(piece)


@pytest.mark.parametrize("normal, offset", [((0, 1, 0), 0.0), ((1, 2, 3), 0.4), ((-0.3, 0.1, 1), -0.2),
                                            ((0, 0, 5), 2.5), ((1, 1, 1), 0.0)])
def test_sphere_pieces_are_watertight_and_keep_the_volume(sphere, normal, offset):
    pieces = cleave.split(sphere.vertices, sphere.faces, normal=normal, offset=offset)
    assert len(pieces) == 2
    expect_closed_pieces(pieces)
    expect_sides(pieces, normal, offset)
    assert sum(p.volume for p in pieces) == pytest.approx(sphere.volume, rel=1e-6)


def test_torus_cut_through_its_axis_gives_two_halves_with_two_caps_each(torus):
    pieces = cleave.split(torus.vertices, torus.faces, normal=(1, 0, 0), offset=0.0)
    assert [p.side for p in pieces] == [1, -1]
    assert [p.cap_loops for p in pieces] == [2, 2]  # each half is a C with a disc at each end
    expect_closed_pieces(pieces)
    expect_sides(pieces, (1, 0, 0), 0.0)
    assert pieces[0].volume == pytest.approx(torus.volume / 2, rel=1e-6)
    assert sum(p.volume for p in pieces) == pytest.approx(torus.volume, rel=1e-6)


def test_torus_cut_across_its_tube_gives_ring_caps(torus):
    pieces = cleave.split(torus.vertices, torus.faces, normal=(0, 0, 1), offset=0.1)
    assert len(pieces) == 2
    for piece in pieces:
        assert piece.cap_loops == 2  # an annulus: the outer border and the hole
        cap = as_trimesh(piece.vertices, piece.faces[piece.source_triangles == -1])
        radii = np.linalg.norm(cap.vertices[:, :2], axis=1)
        assert radii.min() > 0.75 and radii.max() < 1.25  # the cap spans the tube only, not the hole
    expect_closed_pieces(pieces)
    assert sum(p.volume for p in pieces) == pytest.approx(torus.volume, rel=1e-6)


def test_torus_cut_off_one_side_of_its_tube(torus):
    # x = 1.1 crosses the tube once, on the +x side: a small piece above, the rest below.
    pieces = cleave.split(torus.vertices, torus.faces, normal=(1, 0, 0), offset=1.1)
    assert [p.side for p in pieces] == [1, -1]
    assert [p.cap_loops for p in pieces] == [1, 1]
    assert pieces[0].volume < 0.05 * torus.volume
    expect_closed_pieces(pieces)
    assert sum(p.volume for p in pieces) == pytest.approx(torus.volume, rel=1e-6)


def two_boxes():
    first = trimesh.creation.box(extents=(1, 1, 1))
    second = trimesh.creation.box(extents=(1, 1, 1), transform=trimesh.transformations.translation_matrix((3, 0, 0)))
    both = trimesh.util.concatenate([first, second])
    return both.vertices, both.faces


@pytest.mark.parametrize("islands, count", [(True, 4), ("touching", 4), ("connected", 4), (False, 2),
                                            (np.bool_(False), 2)])
def test_islands_words(islands, count):
    vertices, faces = two_boxes()
    pieces = cleave.split(vertices, faces, normal=(0, 1, 0), offset=0.1, islands=islands)
    assert len(pieces) == count
    assert sorted(p.side for p in pieces) == [-1] * (count // 2) + [1] * (count // 2)
    assert sum(p.volume for p in pieces) == pytest.approx(2.0, abs=1e-9)


def test_hollow_cut_has_no_caps(unit_cube):
    pieces = cleave.split(unit_cube.vertices, unit_cube.faces, normal=(0, 0, 1), offset=0.5, cap=False)
    assert len(pieces) == 2
    for piece in pieces:
        assert piece.cap_triangles == 0 and not piece.closed
        assert not as_trimesh(piece.vertices, piece.faces).is_watertight


def open_box():
    """The unit cube without its top (z = 1) face: an open surface."""
    cube = trimesh.creation.box(extents=(1, 1, 1), transform=trimesh.transformations.translation_matrix((0.5, 0.5, 0.5)))
    keep = cube.face_normals[:, 2] < 0.5
    return cube.vertices, cube.faces[keep]


def test_open_words_follow_the_command_line():
    vertices, faces = open_box()
    with pytest.raises(cleave.SplitError) as refused:
        cleave.split(vertices, faces, normal=(1, 0, 0), offset=0.5, open="refuse")
    assert refused.value.status == "OpenSection"
    capped = cleave.split(vertices, faces, normal=(1, 0, 0), offset=0.5, open="cap-closed")
    assert len(capped) == 2 and all(not p.closed and p.cap_triangles == 0 for p in capped)
    bridged = cleave.split(vertices, faces, normal=(1, 0, 0), offset=0.5, open="bridge")
    assert len(bridged) == 2 and all(p.cap_triangles > 0 for p in bridged)


def test_normals_and_uvs_are_carried_and_cap_uvs_follow_the_mode(sphere):
    normals = sphere.vertex_normals
    uvs = sphere.vertices[:, :2] * 0.5 + 0.5
    for mode in ("world", "bounds"):
        pieces = cleave.split(sphere.vertices, sphere.faces, normal=(0, 0, 1), offset=0.3, normals=normals, uvs=uvs, uv=mode)
        for piece in pieces:
            assert piece.normals.shape == piece.vertices.shape and piece.normals.dtype == np.float32
            np.testing.assert_allclose(np.linalg.norm(piece.normals, axis=1), 1.0, atol=1e-3)
            assert piece.uvs.shape == (len(piece.vertices), 2)
            cap_uvs = piece.uvs[np.unique(piece.faces[piece.source_triangles == -1])]
            if mode == "bounds":  # normalised to the cap's bounds
                assert cap_uvs.min() >= -1e-6 and cap_uvs.max() <= 1 + 1e-6
                assert cap_uvs.max() - cap_uvs.min() > 0.99
            else:  # world planar, one UV unit per metre: spans the cap's diameter (about 1.9)
                assert np.ptp(cap_uvs, axis=0).max() == pytest.approx(2 * np.sqrt(1 - 0.09), rel=0.02)


def test_float32_and_float64_and_integer_vertices_agree(unit_cube):
    results = [cleave.split(unit_cube.vertices.astype(dtype), unit_cube.faces.astype(np.int32), offset=0.5)
               for dtype in (np.float64, np.float32, np.int64)]
    for pieces in results[1:]:
        assert [p.volume for p in pieces] == [p.volume for p in results[0]]


def test_version_is_the_cmake_version():
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt"), encoding="utf-8") as f:
        version = re.search(r"project\(Cleave VERSION ([0-9.]+)", f.read()).group(1)
    assert cleave.__version__ == version


def test_every_function_and_class_has_a_docstring():
    for name in ("split", "read_mesh", "write_mesh", "Piece", "SplitError"):
        assert len(getattr(cleave, name).__doc__ or "") > 40, name
    for name in ("vertices", "faces", "normals", "uvs", "side", "closed", "volume", "center_of_mass", "inertia",
                 "cap_triangles"):
        assert getattr(cleave.Piece, name).__doc__, name
    assert cleave.__doc__


def test_threads_cut_at_once_and_agree_with_one_thread(sphere):
    from concurrent.futures import ThreadPoolExecutor

    planes = [((np.sin(k), np.cos(k), 0.3), 0.1 * (k % 5) - 0.2) for k in range(16)]
    serial = [[p.volume for p in cleave.split(sphere.vertices, sphere.faces, normal=n, offset=d)] for n, d in planes]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(lambda plane: [p.volume for p in cleave.split(
            sphere.vertices, sphere.faces, normal=plane[0], offset=plane[1])], planes))
    assert threaded == serial


def test_random_triangle_soups_give_pieces_or_split_error():
    rng = np.random.default_rng(7)
    outcomes = {"pieces": 0, "refused": 0}
    for _ in range(300):
        count = int(rng.integers(3, 30))
        vertices = rng.normal(size=(count, 3)) * rng.choice([1e-6, 1.0, 1e6])
        faces = rng.integers(0, count, size=(int(rng.integers(1, 40)), 3))
        try:
            pieces = cleave.split(vertices, faces, normal=rng.normal(size=3), offset=float(rng.normal()),
                                  open=str(rng.choice(["refuse", "cap-closed", "bridge"])),
                                  islands=rng.integers(0, 2) == 1, cap=bool(rng.integers(0, 2)))
        except cleave.SplitError as error:
            assert error.status in ("PlaneMissesMesh", "OpenSection", "TriangulationFailed", "InvalidInput")
            outcomes["refused"] += 1
            continue
        outcomes["pieces"] += 1
        for piece in pieces:
            assert piece.side in (1, -1)
            assert np.isfinite(piece.vertices).all() and np.isfinite(piece.volume)
            assert len(piece.faces) == 0 or piece.faces.max() < len(piece.vertices)
    assert outcomes["pieces"] > 50 and outcomes["refused"] > 0


def test_pieces_pickle_for_worker_processes(torus):
    import pickle

    for piece in cleave.split(torus.vertices, torus.faces, normal=(1, 0, 0), offset=0.0):
        copy = pickle.loads(pickle.dumps(piece))
        np.testing.assert_array_equal(copy.vertices, piece.vertices)
        np.testing.assert_array_equal(copy.faces, piece.faces)
        np.testing.assert_array_equal(copy.inertia, piece.inertia)
        assert (copy.side, copy.volume, copy.closed, copy.cap_loops) == (piece.side, piece.volume, piece.closed, 2)
