# SPDX-License-Identifier: MIT
"""tools/batch_slice.py on a small folder of models it makes: every model cut on two processes,
pieces written and watertight, volumes kept, a broken model reported without stopping the rest."""
import json
import os
import subprocess
import sys

import pytest
import trimesh

import cleave
from conftest import SOURCE_DIR

TOOL = os.path.join(SOURCE_DIR, "tools", "batch_slice.py")


@pytest.fixture
def model_folder(tmp_path):
    folder = tmp_path / "models"
    (folder / "nested").mkdir(parents=True)
    trimesh.creation.box(extents=(2, 2, 2)).export(folder / "box.obj")
    trimesh.creation.icosphere(subdivisions=2, radius=1.0).export(folder / "sphere.stl")
    trimesh.creation.torus(major_radius=1.0, minor_radius=0.3).export(folder / "nested" / "torus.ply")
    (folder / "broken.off").write_text("OFF\n3 1 0\n0 0 0\n")
    (folder / "notes.txt").write_text("not a model\n")
    return folder


def run_tool(*args):
    return subprocess.run([sys.executable, TOOL, *map(str, args)], capture_output=True, text=True, timeout=300)


def test_slices_every_model_and_reports_it(model_folder, tmp_path):
    out = tmp_path / "out"
    done = run_tool(model_folder, "--out", out, "--plane", 1, 0, 0, 0.1, "--slices", 2, "--axis", "z",
                    "--workers", 2)
    assert done.returncode == 1, done.stderr  # broken.off fails, the others are sliced
    assert "4/4" in done.stderr  # the progress bar reached the end
    report = json.loads((out / "report.json").read_text())
    assert report["models"] == 4 and report["failed"] == 1 and report["workers"] == 2
    results = {os.path.basename(r["model"]): r for r in report["results"]}
    assert set(results) == {"box.obj", "sphere.stl", "torus.ply", "broken.off"}
    assert "broken.off" in results["broken.off"]["error"] and results["broken.off"]["pieces"] == []
    # The box: x = 0.1 and two slabs at z = -1/3 and 1/3 make 2 x 3 = 6 pieces.
    assert len(results["box.obj"]["pieces"]) == 6
    assert results["box.obj"]["input_volume"] == pytest.approx(8.0)
    for name in ("box.obj", "sphere.stl", "torus.ply"):
        result = results[name]
        assert result["error"] is None and result["planes"] == 3 and result["seconds"] > 0
        assert result["pieces_volume"] == pytest.approx(result["input_volume"], rel=1e-6)
        for piece in result["pieces"]:
            assert piece["closed"] is True
            loaded = trimesh.load(piece["file"], force="mesh")
            assert loaded.is_watertight
            assert loaded.volume == pytest.approx(piece["volume"], rel=1e-5)
    assert os.path.isfile(out / "nested" / "torus" / "piece_0.obj")


def test_a_plane_that_misses_leaves_the_model_whole(model_folder, tmp_path):
    out = tmp_path / "out"
    done = run_tool(model_folder, "--out", out, "--plane", 0, 1, 0, 50, "--workers", 1, "--format", "glb",
                    "--report", tmp_path / "r.json")
    report = json.loads((tmp_path / "r.json").read_text())
    box = next(r for r in report["results"] if r["model"].endswith("box.obj"))
    assert done.returncode == 1 and len(box["pieces"]) == 1
    assert box["pieces"][0]["volume"] == pytest.approx(8.0)
    vertices, faces, _, _ = cleave.read_mesh(box["pieces"][0]["file"])
    assert len(faces) == 12


def test_bad_arguments_exit_2(model_folder, tmp_path):
    assert run_tool(model_folder, "--out", tmp_path / "o").returncode == 2  # no plane
    assert run_tool(tmp_path / "missing", "--out", tmp_path / "o", "--slices", 1).returncode == 2
