#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Peer comparison of the cleave-split core against VTK and manifold.

Run from the repository root:

    python3 tools/bench/peers/peer_compare.py            # full run (7 rounds)
    python3 tools/bench/peers/peer_compare.py --quick    # smoke run (10k/100k, 3 rounds)

The script creates build/peer-venv (pinned versions from requirements.txt) and
re-executes itself inside it, writes the shared meshes as binary PLY into
build/peer-meshes/, times the three tools round-robin on one pinned core, checks
that every tool conserves the volume of the input, writes raw results to
build/peer-results.json and the summary table into docs/performance.md under the
heading "## Split core against offline libraries".
"""

import argparse
import datetime
import gc
import hashlib
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
REQUIREMENTS = os.path.join(HERE, "requirements.txt")
BUILD_DIR = os.path.join(ROOT, "build")
VENV = os.path.join(BUILD_DIR, "peer-venv")
MESH_DIR = os.path.join(BUILD_DIR, "peer-meshes")
RESULTS_JSON = os.path.join(BUILD_DIR, "peer-results.json")


def set_build_dir(path):
    """Puts the virtualenv, the generated meshes and the raw results under `path`."""
    global BUILD_DIR, VENV, MESH_DIR, RESULTS_JSON
    BUILD_DIR = os.path.abspath(path)
    VENV = os.path.join(BUILD_DIR, "peer-venv")
    MESH_DIR = os.path.join(BUILD_DIR, "peer-meshes")
    RESULTS_JSON = os.path.join(BUILD_DIR, "peer-results.json")
DOC = os.path.join(ROOT, "docs", "performance.md")
HEADING = "## Split core against offline libraries"
VOLUME_TOLERANCE = 1e-3
TOOLS = ("cleave", "vtk", "manifold")

# One thread everywhere; must be in the environment before numpy/vtk/manifold load.
THREAD_ENV = {
    "OMP_NUM_THREADS": "1",
    "OPENBLAS_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "TBB_NUM_THREADS": "1",
    "VTK_SMP_MAX_THREADS": "1",
    "VTK_SMP_BACKEND_IN_USE": "Sequential",
}


class BenchError(Exception):
    """A failure that ends the run with a clear message and a non-zero exit."""


# --------------------------------------------------------------------------
# Virtualenv bootstrap
# --------------------------------------------------------------------------

def venv_python():
    return os.path.join(VENV, "bin", "python")


def inside_venv():
    return os.path.realpath(sys.prefix) == os.path.realpath(VENV)


def ensure_venv_and_reexec():
    """Create build/peer-venv with the pinned packages and re-run this script in it."""
    with open(REQUIREMENTS, "rb") as f:
        wanted = hashlib.sha256(f.read()).hexdigest()
    stamp = os.path.join(VENV, ".requirements.sha256")
    if not os.path.exists(venv_python()):
        print(f"[setup] creating virtualenv {os.path.relpath(VENV, ROOT)}", flush=True)
        subprocess.run([sys.executable, "-m", "venv", VENV], check=True)
    have = open(stamp).read().strip() if os.path.exists(stamp) else ""
    if have != wanted:
        print("[setup] installing pinned packages from requirements.txt", flush=True)
        subprocess.run([venv_python(), "-m", "pip", "install", "-q", "--upgrade", "pip"], check=True)
        subprocess.run([venv_python(), "-m", "pip", "install", "-q", "-r", REQUIREMENTS], check=True)
        with open(stamp, "w") as f:
            f.write(wanted + "\n")
    env = dict(os.environ)
    env.update(THREAD_ENV)
    env["PEER_COMPARE_ORIGINAL_ARGV"] = json.dumps(sys.argv)
    os.execve(venv_python(), [venv_python(), os.path.abspath(__file__)] + sys.argv[1:], env)


# --------------------------------------------------------------------------
# Mesh generation (deterministic, closed, outward oriented)
# --------------------------------------------------------------------------

def uv_sphere(np, slices, stacks, radius=1.0):
    """UV sphere with 2*slices*(stacks-1) triangles. An odd `stacks` keeps the
    equator free of vertex rings."""
    rings = np.arange(1, stacks)  # latitude rings, poles excluded
    theta = np.pi * rings / stacks
    phi = 2.0 * np.pi * np.arange(slices) / slices
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    ring_pts = np.stack(
        [radius * st * np.cos(phi)[None, :], radius * st * np.sin(phi)[None, :],
         np.broadcast_to(radius * ct, (stacks - 1, slices))], axis=-1).reshape(-1, 3)
    north = len(ring_pts)
    south = north + 1
    verts = np.vstack([ring_pts, [[0.0, 0.0, radius]], [[0.0, 0.0, -radius]]])

    j = np.arange(slices)
    jn = (j + 1) % slices
    tris = [np.stack([np.full(slices, north), j, jn], axis=1)]  # north cap
    r = np.arange(stacks - 2)[:, None]
    a = r * slices + j[None, :]
    b = r * slices + jn[None, :]
    c = (r + 1) * slices + j[None, :]
    d = (r + 1) * slices + jn[None, :]
    tris.append(np.stack([a, c, d], axis=-1).reshape(-1, 3))
    tris.append(np.stack([a, d, b], axis=-1).reshape(-1, 3))
    last = (stacks - 2) * slices
    tris.append(np.stack([np.full(slices, south), last + jn, last + j], axis=1))  # south cap
    return verts, np.vstack(tris)


def torus(np, major_segments, minor_segments, major_r=1.0, minor_r=0.35):
    """Torus around z with 2*major*minor triangles. The minor angle is offset by
    half a step so no vertex lies on z = 0 (the middle plane)."""
    u = 2.0 * np.pi * np.arange(major_segments) / major_segments
    v = 2.0 * np.pi * (np.arange(minor_segments) + 0.5) / minor_segments
    cu, su = np.cos(u)[:, None], np.sin(u)[:, None]
    rad = major_r + minor_r * np.cos(v)[None, :]
    verts = np.stack([rad * cu, rad * su,
                      np.broadcast_to(minor_r * np.sin(v)[None, :], (major_segments, minor_segments))],
                     axis=-1).reshape(-1, 3)
    i = np.arange(major_segments)[:, None]
    j = np.arange(minor_segments)[None, :]
    i1 = (i + 1) % major_segments
    j1 = (j + 1) % minor_segments
    a = i * minor_segments + j
    b = i1 * minor_segments + j
    c = i1 * minor_segments + j1
    d = i * minor_segments + j1
    t1 = np.stack([a, b, c], axis=-1).reshape(-1, 3)
    t2 = np.stack([a, c, d], axis=-1).reshape(-1, 3)
    return verts, np.vstack([t1, t2])


def comb_prism(np, teeth=32, tooth_w=4, gap_w=4, tooth_h=40, base_h=8, layers=6,
               cell=0.01, depth=0.12):
    """A comb outline (base bar with `teeth` teeth pointing +y) extruded along z.
    Built on a cell grid: the top and bottom faces are the filled cells, the
    walls are the boundary edges of the filled set extruded in `layers` rows."""
    width = teeth * tooth_w + (teeth - 1) * gap_w
    height = base_h + tooth_h
    filled = np.zeros((width, height), dtype=bool)
    filled[:, :base_h] = True
    for t in range(teeth):
        x0 = t * (tooth_w + gap_w)
        filled[x0:x0 + tooth_w, base_h:] = True

    index = {}
    verts = []

    def vid(ix, iy, iz):
        key = (ix, iy, iz)
        k = index.get(key)
        if k is None:
            k = len(verts)
            index[key] = k
            verts.append((ix * cell, iy * cell, iz * depth / layers))
        return k

    def is_filled(ix, iy):
        return 0 <= ix < width and 0 <= iy < height and filled[ix, iy]

    tris = []
    for ix in range(width):
        for iy in range(height):
            if not filled[ix, iy]:
                continue
            # top face (+z) counter-clockwise seen from +z, bottom face reversed
            a, b, c, d = (vid(ix, iy, layers), vid(ix + 1, iy, layers),
                          vid(ix + 1, iy + 1, layers), vid(ix, iy + 1, layers))
            tris += [(a, b, c), (a, c, d)]
            a, b, c, d = (vid(ix, iy, 0), vid(ix + 1, iy, 0),
                          vid(ix + 1, iy + 1, 0), vid(ix, iy + 1, 0))
            tris += [(a, c, b), (a, d, c)]
            # walls: cell edges walked counter-clockwise, where the neighbour is empty
            edges = []
            if not is_filled(ix, iy - 1):
                edges.append(((ix, iy), (ix + 1, iy)))
            if not is_filled(ix + 1, iy):
                edges.append(((ix + 1, iy), (ix + 1, iy + 1)))
            if not is_filled(ix, iy + 1):
                edges.append(((ix + 1, iy + 1), (ix, iy + 1)))
            if not is_filled(ix - 1, iy):
                edges.append(((ix, iy + 1), (ix, iy)))
            for (p, q) in edges:
                for k in range(layers):
                    pk, qk = vid(p[0], p[1], k), vid(q[0], q[1], k)
                    pk1, qk1 = vid(p[0], p[1], k + 1), vid(q[0], q[1], k + 1)
                    tris += [(pk, qk, qk1), (pk, qk1, pk1)]
    info = {"cut_y": (base_h + 0.5 * tooth_h + 0.37) * cell}
    return np.array(verts, dtype=np.float64), np.array(tris, dtype=np.int64), info


def check_closed_oriented(np, tris, name):
    """Every directed edge exactly once and its reverse exactly once."""
    e = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    n = int(tris.max()) + 1
    key = e[:, 0].astype(np.int64) * n + e[:, 1]
    rkey = e[:, 1].astype(np.int64) * n + e[:, 0]
    if len(np.unique(key)) != len(key):
        raise BenchError(f"generated mesh {name}: a directed edge repeats (not consistently oriented)")
    if not np.isin(rkey, key).all():
        raise BenchError(f"generated mesh {name}: an edge has no opposite half-edge (not closed)")


def signed_volume(np, verts, tris):
    a, b, c = verts[tris[:, 0]], verts[tris[:, 1]], verts[tris[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def write_ply(np, path, verts, tris):
    """Binary little-endian PLY: float x y z, list uchar int vertex_indices."""
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(verts)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        f"element face {len(tris)}\n"
        "property list uchar int vertex_indices\nend_header\n"
    ).encode("ascii")
    face_dtype = np.dtype([("n", "u1"), ("idx", "<i4", (3,))])
    faces = np.empty(len(tris), dtype=face_dtype)
    faces["n"] = 3
    faces["idx"] = tris
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(header)
        f.write(verts.astype("<f4").tobytes())
        f.write(faces.tobytes())
    os.replace(tmp, path)


def unit(np, v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v)


def build_cases(np, quick):
    """Returns the benchmark cases: name, description, vertices, triangles, plane (n, D)."""
    oblique = unit(np, [0.12, 0.07, 1.0])  # non-negative: no "-" arguments on the command line
    specs = [
        ("sphere-10k", "UV sphere 100x51", lambda: uv_sphere(np, 100, 51), (oblique, 0.0137)),
        ("sphere-100k", "UV sphere 250x201", lambda: uv_sphere(np, 250, 201), (oblique, 0.0137)),
        ("torus-100k", "torus 250x200, middle plane", lambda: torus(np, 250, 200),
         (np.array([0.0, 0.0, 1.0]), 0.0)),
        ("comb-32", "32-tooth comb prism, across all teeth", None, None),
    ]
    if not quick:
        specs.insert(2, ("sphere-1m", "UV sphere 1000x501", lambda: uv_sphere(np, 1000, 501),
                         (oblique, 0.0137)))
    else:
        specs = [s for s in specs if s[0] in ("sphere-10k", "sphere-100k")]

    cases = []
    os.makedirs(MESH_DIR, exist_ok=True)
    for name, desc, make, plane in specs:
        if name == "comb-32":
            verts, tris, info = comb_prism(np)
            plane = (np.array([0.0, 1.0, 0.0]), info["cut_y"])
        else:
            verts, tris = make()
        # Everyone sees exactly the float32 positions that the PLY file stores.
        verts = verts.astype(np.float32).astype(np.float64)
        tris = tris.astype(np.int64)
        check_closed_oriented(np, tris, name)
        vol = signed_volume(np, verts, tris)
        if vol <= 0:
            raise BenchError(f"generated mesh {name}: non-positive volume {vol} (inside out)")
        path = os.path.join(MESH_DIR, name + ".ply")
        write_ply(np, path, verts, tris)
        cases.append({"name": name, "desc": desc, "path": path, "verts": verts, "tris": tris,
                      "normal": plane[0], "d": float(plane[1]), "volume": vol})
    return cases


# --------------------------------------------------------------------------
# The three tools
# --------------------------------------------------------------------------

def fmt_float(x):
    return repr(float(x))


def half_volumes(result):
    """Volumes on each side of the plane (pieces grouped by their side label), sorted."""
    sides = {}
    for p in result["pieces"]:
        key = str(p.get("side"))
        sides[key] = sides.get(key, 0.0) + float(p.get("volume") or 0.0)
    return sorted(sides.values())


class CleaveRunner:
    name = "cleave"

    def __init__(self, exe, case, repeat, warmup):
        self.exe = exe
        self.case = case
        self.repeat = repeat
        n = case["normal"]
        # Each round is a new process, while VTK and manifold run in this one and are warm after
        # the warm-up round: cleave-split gets that round's worth of untimed splits in every round.
        self.cmd = [exe, case["path"], "--plane", fmt_float(n[0]), fmt_float(n[1]), fmt_float(n[2]),
                    fmt_float(case["d"]), "--json", "--repeat", str(repeat),
                    "--warmup", str(repeat if warmup > 0 else 0)]

    def run(self):
        proc = subprocess.run(self.cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if proc.returncode != 0:
            raise BenchError(f"cleave-split failed (exit {proc.returncode}) on {self.case['name']}:\n"
                             f"  {shlex.join(self.cmd)}\n{proc.stderr.strip()}")
        try:
            out = json.loads(proc.stdout)
        except json.JSONDecodeError as e:
            raise BenchError(f"cleave-split printed no valid JSON on {self.case['name']}: {e}\n"
                             f"{proc.stdout[:500]}")
        timing = out.get("timing") or {}
        if "split_ms_median" not in timing:
            raise BenchError(f"cleave-split JSON has no timing.split_ms_median on {self.case['name']}")
        pieces = out.get("pieces") or []
        if not pieces:
            raise BenchError(f"cleave-split produced no pieces on {self.case['name']} "
                             f"(status {out.get('status')!r})")
        result = {
            "ms": float(timing["split_ms_median"]),
            "ms_min": float(timing.get("split_ms_min", timing["split_ms_median"])),
            "setup_ms": float(timing.get("setup_ms_median", 0.0)),
            "cut_ms": float(timing.get("cut_ms_median", timing["split_ms_median"])),
            "first_ms": float(timing.get("first_cut_ms_median", timing["split_ms_median"])),
            "status": out.get("status"),
            "input": out.get("input"),
            "volume": sum(float(p.get("volume", 0.0)) for p in pieces),
            "pieces": [{"side": p.get("side"), "triangles": p.get("triangles"),
                        "cap_triangles": p.get("cap_triangles"), "cap_loops": p.get("cap_loops"),
                        "closed": p.get("closed"), "volume": p.get("volume")} for p in pieces],
        }
        result["triangles"] = sum(int(p.get("triangles") or 0) for p in pieces)
        return result


class VtkRunner:
    name = "vtk"

    def __init__(self, np, vtk_mods, case, repeat):
        self.np = np
        self.repeat = repeat
        self.case = case
        m = vtk_mods
        verts, tris = case["verts"], case["tris"]
        pts = m.vtkPoints()
        pts.SetData(m.numpy_to_vtk(np.ascontiguousarray(verts), deep=True))
        cells = m.vtkCellArray()
        offsets = np.arange(0, 3 * len(tris) + 1, 3, dtype=np.int64)
        cells.SetData(m.numpy_to_vtkIdTypeArray(offsets, deep=True),
                      m.numpy_to_vtkIdTypeArray(np.ascontiguousarray(tris.reshape(-1)), deep=True))
        self.poly = m.vtkPolyData()
        self.poly.SetPoints(pts)
        self.poly.SetPolys(cells)
        n, d = case["normal"], case["d"]
        origin = n * d
        self.filters = []
        for sign in (1.0, -1.0):
            plane = m.vtkPlane()
            plane.SetOrigin(*origin)
            plane.SetNormal(*(sign * n))
            planes = m.vtkPlaneCollection()
            planes.AddItem(plane)
            f = m.vtkClipClosedSurface()
            f.SetInputData(self.poly)
            f.SetClippingPlanes(planes)
            f.SetGenerateFaces(1)
            f.SetGenerateOutline(0)
            f.SetScalarModeToNone()
            f.SetPassPointData(0)
            self.filters.append(f)
        self.vtk_to_numpy = m.vtk_to_numpy

    def once(self):
        for f in self.filters:
            f.Modified()
        t0 = time.perf_counter_ns()
        for f in self.filters:
            f.Update()
        return (time.perf_counter_ns() - t0) / 1e6

    def _piece(self, out):
        np = self.np
        if out.GetNumberOfPoints() == 0:
            return 0, 0.0
        pts = self.vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
        polys = out.GetPolys()
        off = self.vtk_to_numpy(polys.GetOffsetsArray()).astype(np.int64)
        conn = self.vtk_to_numpy(polys.GetConnectivityArray()).astype(np.int64)
        sizes = np.diff(off)
        ntri = sizes - 2
        if (ntri < 1).any():
            raise BenchError("vtk produced a degenerate polygon")
        # Fan triangulation (exact signed volume for planar polygons).
        starts = np.repeat(off[:-1], ntri)
        k = np.arange(int(ntri.sum())) - np.repeat(np.cumsum(ntri) - ntri, ntri) + 1
        tris = np.stack([conn[starts], conn[starts + k], conn[starts + k + 1]], axis=1)
        return int(len(tris)), signed_volume(np, pts, tris)

    def run(self):
        samples = [self.once() for _ in range(self.repeat)]
        pieces = []
        for sign, f in zip(("positive", "negative"), self.filters):
            ntri, vol = self._piece(f.GetOutput())
            pieces.append({"side": sign, "triangles": ntri, "volume": vol})
        return {"ms": statistics.median(samples), "ms_min": min(samples), "samples": samples,
                "volume": sum(p["volume"] for p in pieces),
                "triangles": sum(p["triangles"] for p in pieces), "pieces": pieces}


class ManifoldRunner:
    name = "manifold"

    def __init__(self, np, m3d, case, repeat):
        self.repeat = repeat
        mesh = m3d.Mesh64(vert_properties=np.ascontiguousarray(case["verts"], dtype=np.float64),
                          tri_verts=np.ascontiguousarray(case["tris"], dtype=np.uint64))
        self.solid = m3d.Manifold(mesh)
        if self.solid.status() != m3d.Error.NoError:
            raise BenchError(f"manifold rejected {case['name']}: {self.solid.status()}")
        self.solid.num_tri()  # evaluate the input outside the timed region
        self.normal = tuple(float(x) for x in case["normal"])  # unit length
        self.offset = float(case["d"])
        self.last = None

    def once(self):
        t0 = time.perf_counter_ns()
        pos, neg = self.solid.split_by_plane(self.normal, self.offset)
        pos.num_tri()
        neg.num_tri()
        ms = (time.perf_counter_ns() - t0) / 1e6
        self.last = (pos, neg)
        return ms

    def run(self):
        samples = [self.once() for _ in range(self.repeat)]
        pos, neg = self.last
        pieces = [{"side": "positive", "triangles": pos.num_tri(), "volume": pos.volume()},
                  {"side": "negative", "triangles": neg.num_tri(), "volume": neg.volume()}]
        return {"ms": statistics.median(samples), "ms_min": min(samples), "samples": samples,
                "volume": sum(p["volume"] for p in pieces),
                "triangles": sum(p["triangles"] for p in pieces), "pieces": pieces}


# --------------------------------------------------------------------------
# Reporting
# --------------------------------------------------------------------------

def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def fmt_ms(x):
    if x is None:
        return "n/a"
    if x >= 100:
        return f"{x:.0f}"
    if x >= 10:
        return f"{x:.1f}"
    return f"{x:.2f}"


def fmt_ratio(a, b):
    if a is None or b is None or b <= 0:
        return "n/a"
    return f"{a / b:.1f}x"


def summarize(results):
    """Per case and tool: median over rounds of the per-round figure, min over all samples."""
    rows = []
    for case in results["cases"]:
        row = {"name": case["name"], "desc": case["desc"], "triangles": case["input_triangles"],
               "plane": case["plane"]}
        for tool in results["tools"]:
            rounds = case["rounds"].get(tool) or []
            if rounds:
                row[tool] = {"median": statistics.median(r["ms"] for r in rounds),
                             "cut_median": statistics.median(r.get("cut_ms", r["ms"]) for r in rounds),
                             "setup_median": statistics.median(r.get("setup_ms", 0.0) for r in rounds),
                             "first_median": statistics.median(r.get("first_ms", r["ms"]) for r in rounds),
                             "min": min(r["ms_min"] for r in rounds),
                             "triangles": rounds[-1]["triangles"],
                             "pieces": len(rounds[-1]["pieces"]),
                             "volume_rel_err": max(max(abs(r["volume"] - case["volume"]) / case["volume"],
                                                       r.get("half_volume_rel_err", 0.0))
                                                   for r in rounds)}
        rows.append(row)
    return rows


def markdown(results, rows):
    tools = results["tools"]
    meta = results["meta"]
    lines = []
    lines.append(f"Measured {meta['date']} on {meta['cpu']} ({meta['cpus_online']} logical CPUs, "
                 f"run pinned to CPU {meta['pinned_cpu']}, one thread per library), "
                 f"load average at start {meta['loadavg_start']}.")
    lines.append(f"Versions: Python {meta['python']}, {', '.join(f'{k} {v}' for k, v in meta['versions'].items())}"
                 + (f", cleave-split built from the work tree at commit {meta['cleave_commit']}"
                    if meta.get("cleave_commit") else
                    (f", cleave-split given as {meta['cleave']}" if meta.get("cleave") else "")) + ".")
    lines.append(f"{meta['rounds']} measured round(s) round-robin ({' → '.join(tools)}), each tool "
                 f"repeating the split {meta['repeat']} time(s) per round (the round's figure is the median "
                 f"of those), after {meta['warmup']} warm-up round(s). Columns: median over rounds, and the "
                 "fastest single split.")
    lines.append("")
    lines.append(f"Command: `{meta['command']}`")
    lines.append("")
    head = ["Mesh", "Input tris"]
    for t in tools:
        head += [f"{t} median ms", f"{t} min ms"]
    if "cleave" in tools:
        head += [f"{t}/cleave" for t in tools if t != "cleave"]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|")
    for r in rows:
        cells = [f"{r['name']} ({r['desc']})", f"{r['triangles']:,}"]
        for t in tools:
            cells += [fmt_ms(r[t]["median"]), fmt_ms(r[t]["min"])]
        if "cleave" in tools:
            cells += [fmt_ratio(r[t]["median"], r["cleave"]["median"]) for t in tools if t != "cleave"]
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    lines.append("Output check: total triangles of all pieces / number of pieces, and the worst relative "
                 "error (to the input volume) of the summed piece volumes against the input and of the "
                 f"volume on each side of the plane against manifold's; the limit is {VOLUME_TOLERANCE:g}.")
    if "cleave" in tools:
        lines.append("")
        lines.append("cleave's figure above is a cut as the engine makes it of a mesh it has seen: the "
                     "`MeshContainer` takes the mesh with its known weld (every piece carries the weld its "
                     "split gave it; the split system keeps the weld of each mesh it cut), then the split. "
                     "The first cut of a mesh never seen also welds it (set-up from nothing: weld by "
                     "position, closedness). Both, and the split alone, median over rounds of the "
                     "per-round medians:")
        lines.append("")
        others = [t for t in tools if t != "cleave"]
        head = (["Mesh", "cleave set-up from nothing ms", "cleave first cut ms", "cleave split alone ms"]
                + [f"{t}/first cut" for t in others] + [f"{t}/split alone" for t in others])
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|")
        for r in rows:
            c = r["cleave"]
            cells = [r["name"], fmt_ms(c["setup_median"]), fmt_ms(c["first_median"]), fmt_ms(c["cut_median"])]
            cells += [fmt_ratio(r[t]["median"], c["first_median"]) for t in others]
            cells += [fmt_ratio(r[t]["median"], c["cut_median"]) for t in others]
            lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    head = ["Mesh"] + [f"{t} tris / pieces" for t in tools] + [f"{t} vol. err" for t in tools]
    lines.append("| " + " | ".join(head) + " |")
    lines.append("|" + "|".join(["---"] + ["---:"] * (len(head) - 1)) + "|")
    for r in rows:
        cells = [r["name"]]
        cells += [f"{r[t]['triangles']:,} / {r[t]['pieces']}" for t in tools]
        cells += [f"{r[t]['volume_rel_err']:.1e}" for t in tools]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


SECTION_NOTES = """\
What is timed: cleave is `cleave-split FILE --plane NX NY NZ D --json --repeat R --warmup R`, the
tool's own timer around a cut (the container taking the mesh and its weld, both halves, caps,
island separation, mass properties; no file I/O). VTK and manifold run in the script's own process
and are warm after the warm-up round; cleave-split is a new process each round, so it makes R
untimed splits first (with `--warmup 0`, neither side is warmed).
VTK is `vtkClipClosedSurface` with one clipping plane and generated cap faces, run twice (the
plane and its flip) for the two halves, on a `vtkPolyData` built once. manifold is
`Manifold.split_by_plane` (one call gives both halves) on a `Manifold` built once, with
`num_tri()` on both results inside the timed region to force evaluation. VTK and manifold do
not separate islands or compute mass properties, so their timed work is a subset of cleave's.
Meshes are generated by the script (binary PLY in BUILD/peer-meshes/); planes avoid passing
exactly through vertices. Raw samples are in BUILD/peer-results.json.
"""


def write_doc(section_body):
    notes = SECTION_NOTES.replace("BUILD/", os.path.relpath(BUILD_DIR, ROOT) + "/")
    text = f"{HEADING}\n\n{notes}\n{section_body}\n"
    if os.path.exists(DOC):
        with open(DOC) as f:
            old = f.read()
    else:
        old = "# Performance\n\n"
    lines = old.splitlines(keepends=True)
    start = next((i for i, l in enumerate(lines) if l.rstrip() == HEADING), None)
    if start is None:
        new = old.rstrip("\n") + "\n\n" + text
    else:
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
        tail = "".join(lines[end:])
        new = "".join(lines[:start]) + text + ("\n" + tail if tail else "")
    os.makedirs(os.path.dirname(DOC), exist_ok=True)
    with open(DOC, "w") as f:
        f.write(new)


# --------------------------------------------------------------------------
# Main
# --------------------------------------------------------------------------

def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--rounds", type=int, default=None, help="measured rounds (default 7, --quick 3)")
    p.add_argument("--repeat", type=int, default=3, help="splits per tool per round (default 3)")
    p.add_argument("--warmup", type=int, default=1, help="unrecorded warm-up rounds (default 1)")
    p.add_argument("--quick", action="store_true", help="only the 10k and 100k spheres, 3 rounds")
    p.add_argument("--cleave", metavar="PATH", help="cleave-split executable "
                   "(default BUILD_DIR/bin/cleave-split)")
    p.add_argument("--build-dir", metavar="DIR", default=os.path.join(ROOT, "build"),
                   help="build folder holding bin/cleave-split; the virtualenv, meshes and raw results "
                   "go there too (default build)")
    p.add_argument("--peers-only", action="store_true",
                   help="run only VTK and manifold (no cleave-split; docs/performance.md untouched)")
    p.add_argument("--no-doc", action="store_true", help="do not write docs/performance.md")
    p.add_argument("--cpu", type=int, default=None, help="CPU to pin to (default: the last allowed one)")
    p.add_argument("--no-venv", action="store_true",
                   help="use the current interpreter instead of build/peer-venv")
    args = p.parse_args(argv)
    if args.rounds is None:
        args.rounds = 3 if args.quick else 7
    if args.rounds < 1 or args.repeat < 1 or args.warmup < 0:
        p.error("--rounds and --repeat must be >= 1, --warmup >= 0")
    return args


def find_cleave(args):
    if args.cleave:
        path = os.path.abspath(args.cleave)
    else:
        path = os.path.join(BUILD_DIR, "bin", "cleave-split")
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        raise BenchError(
            f"cleave-split not found or not executable at {os.path.relpath(path, ROOT)}.\n"
            "Build it first (cmake --build build --target cleave-split) or pass --cleave PATH; "
            "use --peers-only to time only VTK and manifold.")
    return path


def git_commit():
    try:
        return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None


def main(argv):
    args = parse_args(argv)
    set_build_dir(args.build_dir)
    if not args.no_venv and not inside_venv():
        ensure_venv_and_reexec()  # does not return
    os.environ.update(THREAD_ENV)

    original = json.loads(os.environ.get("PEER_COMPARE_ORIGINAL_ARGV", "null")) or sys.argv
    shown = []
    for a in original[1:]:
        # Paths inside the repository are shown relative to its root.
        if os.path.isabs(a) and os.path.abspath(a).startswith(ROOT + os.sep):
            a = os.path.relpath(a, ROOT)
        shown.append(a)
    command = "python3 tools/bench/peers/peer_compare.py" + (" " + shlex.join(shown) if shown else "")

    cleave_exe = None if args.peers_only else find_cleave(args)

    allowed = sorted(os.sched_getaffinity(0))
    cpu = args.cpu if args.cpu is not None else allowed[-1]
    os.sched_setaffinity(0, {cpu})  # inherited by cleave-split subprocesses

    import numpy as np
    import manifold3d as m3d
    from vtkmodules.vtkCommonCore import vtkPoints, vtkSMPTools, vtkVersion
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPlane, vtkPlaneCollection, vtkPolyData
    from vtkmodules.vtkFiltersGeneral import vtkClipClosedSurface
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
    from importlib.metadata import version as pkg_version

    vtkSMPTools.SetBackend("Sequential")
    vtkSMPTools.Initialize(1)

    class VtkMods:
        pass
    vm = VtkMods()
    for k, v in dict(vtkPoints=vtkPoints, vtkCellArray=vtkCellArray, vtkPlane=vtkPlane,
                     vtkPlaneCollection=vtkPlaneCollection, vtkPolyData=vtkPolyData,
                     vtkClipClosedSurface=vtkClipClosedSurface, numpy_to_vtk=numpy_to_vtk,
                     numpy_to_vtkIdTypeArray=numpy_to_vtkIdTypeArray, vtk_to_numpy=vtk_to_numpy).items():
        setattr(vm, k, v)

    tools = ["vtk", "manifold"] if args.peers_only else list(TOOLS)
    meta = {
        "date": datetime.date.today().isoformat(),
        "cpu": cpu_model(),
        "cpus_online": os.cpu_count(),
        "pinned_cpu": cpu,
        "loadavg_start": " ".join(f"{x:.2f}" for x in os.getloadavg()),
        "python": platform.python_version(),
        "versions": {"vtk": vtkVersion.GetVTKVersion(), "manifold3d": pkg_version("manifold3d"),
                     "numpy": np.__version__},
        "vtk_smp_backend": vtkSMPTools.GetBackend(),
        "rounds": args.rounds, "repeat": args.repeat, "warmup": args.warmup,
        "command": command,
        "cleave": os.path.relpath(cleave_exe, ROOT) if cleave_exe else None,
        # The work tree's commit only describes the default build; an executable given with
        # --cleave is named by its path (its commit is not known here).
        "cleave_commit": git_commit() if cleave_exe and not args.cleave else None,
    }
    print(f"[info] cpu {meta['cpu']}, pinned to CPU {cpu}, load {meta['loadavg_start']}, "
          f"vtk {meta['versions']['vtk']} ({meta['vtk_smp_backend']}), "
          f"manifold3d {meta['versions']['manifold3d']}, numpy {np.__version__}", flush=True)

    print("[mesh] generating meshes into " + os.path.relpath(MESH_DIR, ROOT), flush=True)
    cases = build_cases(np, args.quick)
    for c in cases:
        print(f"[mesh] {c['name']:12s} {len(c['tris']):>9,} triangles  volume {c['volume']:.6f}  "
              f"plane n=({', '.join(f'{x:.4f}' for x in c['normal'])}) D={c['d']:.6f}", flush=True)

    results = {"meta": meta, "tools": tools, "cases": []}
    failures = []
    for case in cases:
        runners = {}
        if "cleave" in tools:
            runners["cleave"] = CleaveRunner(cleave_exe, case, args.repeat, args.warmup)
        runners["vtk"] = VtkRunner(np, vm, case, args.repeat)
        runners["manifold"] = ManifoldRunner(np, m3d, case, args.repeat)
        rec = {"name": case["name"], "desc": case["desc"], "file": os.path.relpath(case["path"], ROOT),
               "input_triangles": int(len(case["tris"])), "input_vertices": int(len(case["verts"])),
               "volume": case["volume"],
               "plane": {"normal": [float(x) for x in case["normal"]], "d": case["d"]},
               "rounds": {t: [] for t in tools}}
        total = args.warmup + args.rounds
        for rnd in range(total):
            for tool in tools:
                gc.collect()
                gc.disable()
                try:
                    r = runners[tool].run()
                finally:
                    gc.enable()
                if rnd >= args.warmup:
                    rec["rounds"][tool].append(r)
            label = "warm-up" if rnd < args.warmup else f"round {rnd - args.warmup + 1}/{args.rounds}"
            if rnd >= args.warmup:
                print(f"[run] {case['name']:12s} {label:12s} " +
                      "  ".join(f"{t} {rec['rounds'][t][-1]['ms']:9.2f} ms" for t in tools), flush=True)
            else:
                print(f"[run] {case['name']:12s} {label}", flush=True)
        # Volume sanity check: the pieces of every tool add up to the input volume, and the
        # volume on each side of the plane agrees between the tools.
        ref_halves = half_volumes(rec["rounds"][tools[-1]][-1])
        for tool in tools:
            worst = max(abs(r["volume"] - case["volume"]) / case["volume"] for r in rec["rounds"][tool])
            halves = half_volumes(rec["rounds"][tool][-1])
            if len(halves) == len(ref_halves):
                half_err = max(abs(a - b) for a, b in zip(halves, ref_halves)) / case["volume"]
            else:
                half_err = float("inf")
            for r in rec["rounds"][tool]:
                r["half_volume_rel_err"] = half_err
            worst = max(worst, half_err)
            ok = worst <= VOLUME_TOLERANCE
            print(f"[check] {case['name']:12s} {tool:8s} total volume "
                  f"{rec['rounds'][tool][-1]['volume']:.6f} vs input {case['volume']:.6f} "
                  f"(rel. err {worst:.1e}) {'ok' if ok else 'MISMATCH'}; "
                  f"{len(rec['rounds'][tool][-1]['pieces'])} pieces, "
                  f"{rec['rounds'][tool][-1]['triangles']:,} triangles", flush=True)
            if not ok:
                failures.append(f"{case['name']}: {tool} volume differs from the input by {worst:.1e} relative")
        results["cases"].append(rec)
        del runners

    rows = summarize(results)
    body = markdown(results, rows)
    results["summary"] = rows
    os.makedirs(os.path.dirname(RESULTS_JSON), exist_ok=True)
    with open(RESULTS_JSON, "w") as f:
        json.dump(results, f, indent=1)
    print()
    print(body)
    print()
    print(f"[out] raw results: {os.path.relpath(RESULTS_JSON, ROOT)}")
    if failures:
        raise BenchError("volume check failed:\n  " + "\n  ".join(failures))
    if not args.peers_only and not args.no_doc:
        write_doc(body)
        print(f"[out] table written to {os.path.relpath(DOC, ROOT)} under '{HEADING}'")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except BenchError as e:
        print(f"peer_compare: error: {e}", file=sys.stderr)
        sys.exit(1)
