#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Cut every model of a folder by a set of planes, on all cores, with the Python module `cleave`.

usage: batch_slice.py INPUT_DIR --out OUT_DIR [--plane NX NY NZ D]... [--slices K [--axis x|y|z]]
                      [--workers N] [--format obj|glb] [--open refuse|cap-closed|bridge] [--hollow]
                      [--report FILE]

Each model (.obj .off .stl .ply .gltf .glb, found recursively) is cut by every plane in turn: the
first plane cuts the model, the next cuts every piece, and so on; a plane that misses a piece leaves
it whole. --plane gives planes {x : dot(n, x) = D} in the model's units (repeatable); --slices K adds
K planes across each model's own bounds along --axis, evenly spaced (slabs). Pieces are written to
OUT_DIR/<model>/piece_<k>.<format>; the JSON report (OUT_DIR/report.json unless --report) lists per
model the pieces (file, volume, closed, centre of mass), the input's and the pieces' total volume,
the seconds taken and the errors. A model that cannot be read or cut is reported, not fatal.

The work per model is slice_model(), a pure function of its arguments, mapped over the models with
concurrent.futures.ProcessPoolExecutor (docs/python.md shows the same map on Dask or Ray).
Exit status: 0 when every model was sliced, 1 when some failed, 2 for bad arguments.
"""
import argparse
import json
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

MESH_EXTENSIONS = (".obj", ".off", ".stl", ".ply", ".gltf", ".glb")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def import_cleave():
    """The module `cleave`: from the path, else from the checkout's build/python."""
    try:
        import cleave
    except ImportError:
        sys.path.insert(0, os.path.join(ROOT, "build", "python"))
        import cleave
    return cleave


def find_models(folder):
    """Every mesh file under `folder`, sorted, as paths relative to it."""
    found = []
    for directory, _, files in os.walk(folder):
        for name in files:
            if name.lower().endswith(MESH_EXTENSIONS):
                found.append(os.path.relpath(os.path.join(directory, name), folder))
    return sorted(found)


def slab_planes(vertices, count, axis):
    """`count` planes normal to `axis` (0, 1, 2), evenly spaced inside the bounds of `vertices`."""
    low, high = float(vertices[:, axis].min()), float(vertices[:, axis].max())
    normal = [0.0, 0.0, 0.0]
    normal[axis] = 1.0
    return [(tuple(normal), low + (high - low) * (k + 1) / (count + 1)) for k in range(count)]


def cut_all(cleave, pieces, planes, options):
    """Cut every piece by every plane in turn; a plane that misses a piece keeps it whole.
    `pieces` are (vertices, faces, piece-or-None) triples; returns the final ones."""
    for normal, offset in planes:
        next_pieces = []
        for vertices, faces, piece in pieces:
            try:
                cut = cleave.split(vertices, faces, normal=normal, offset=offset, **options)
            except cleave.SplitError as error:
                if error.status != "PlaneMissesMesh":
                    raise
                next_pieces.append((vertices, faces, piece))
                continue
            next_pieces.extend((p.vertices, p.faces, p) for p in cut)
        pieces = next_pieces
    return pieces


def piece_record(vertices, faces, piece):
    """The report entry of one final piece; a model no plane reached is one piece, as read."""
    if piece is None:
        return {"volume": input_volume(vertices, faces), "closed": None, "center_of_mass": None,
                "faces": int(len(faces))}
    return {"volume": piece.volume, "closed": piece.closed, "center_of_mass": piece.center_of_mass.tolist(),
            "faces": int(len(faces))}


def slice_model(path, planes=(), slices=0, axis=1, out_dir=None, file_format="obj", options=None):
    """Read the model at `path`, cut it by `planes` ((normal, offset) pairs) and, with `slices` > 0,
    by that many slab planes along `axis` across its bounds; write the pieces into `out_dir` when
    given. Returns a JSON-ready dict: pieces, volumes, seconds, error (None when it went well).
    Never raises for a bad model: the error is in the result."""
    cleave = import_cleave()
    start = time.perf_counter()
    result = {"model": path, "pieces": [], "input_volume": None, "pieces_volume": None, "planes": 0,
              "seconds": 0.0, "error": None}
    try:
        vertices, faces, _, _ = cleave.read_mesh(path)
        all_planes = list(planes) + (slab_planes(vertices, slices, axis) if slices > 0 else [])
        result["planes"] = len(all_planes)
        result["input_volume"] = input_volume(vertices, faces)
        final = cut_all(cleave, [(vertices, faces, None)], all_planes, dict(options or {}))
        if out_dir:
            os.makedirs(out_dir, exist_ok=True)
        for k, (piece_vertices, piece_faces, piece) in enumerate(final):
            record = piece_record(piece_vertices, piece_faces, piece)
            if out_dir:
                record["file"] = os.path.join(out_dir, f"piece_{k}.{file_format}")
                cleave.write_mesh(record["file"], piece_vertices, piece_faces)
            result["pieces"].append(record)
        result["pieces_volume"] = sum(p["volume"] for p in result["pieces"])
    except (OSError, ValueError) as error:
        result["error"] = f"{type(error).__name__}: {error}"
    result["seconds"] = time.perf_counter() - start
    return result


def input_volume(vertices, faces):
    """Signed volume of a closed triangle mesh (divergence theorem), in float64."""
    import numpy as np

    corners = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]
    return float(np.einsum("ij,ij->i", corners[:, 0], np.cross(corners[:, 1], corners[:, 2])).sum() / 6.0)


class Progress:
    """A progress bar on stderr: tqdm when it is installed, else one plain line redrawn."""

    def __init__(self, total):
        """A bar for `total` models, drawn at 0."""
        self.total, self.done, self.bar = total, 0, None
        try:
            from tqdm import tqdm

            self.bar = tqdm(total=total, unit="model", file=sys.stderr)
        except ImportError:
            self.draw()

    def step(self, label):
        """One more model finished."""
        self.done += 1
        if self.bar is not None:
            self.bar.set_postfix_str(label, refresh=False)
            self.bar.update(1)
        else:
            self.draw(label)

    def draw(self, label=""):
        """Redraw the plain bar with the last model's name."""
        width = 30
        filled = width * self.done // max(self.total, 1)
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} {label[-40:]:<40}")
        sys.stderr.flush()

    def close(self):
        """End the bar's line."""
        if self.bar is not None:
            self.bar.close()
        else:
            sys.stderr.write("\n")


def parse_arguments(argv):
    """The command line as an argparse namespace; exits 2 with a message on bad arguments."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("input_dir", help="folder of models, searched recursively")
    parser.add_argument("--out", required=True, help="folder for the pieces and the report")
    parser.add_argument("--plane", nargs=4, type=float, action="append", default=[], metavar=("NX", "NY", "NZ", "D"),
                        help="a cutting plane {x : dot(n, x) = D}; repeatable")
    parser.add_argument("--slices", type=int, default=0, help="K slab planes across each model's bounds")
    parser.add_argument("--axis", choices="xyz", default="y", help="the slabs' axis (default y)")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="processes (default: all cores)")
    parser.add_argument("--format", choices=("obj", "glb"), default="obj", help="piece files (default obj)")
    parser.add_argument("--open", choices=("refuse", "cap-closed", "bridge"), default="cap-closed",
                        help="open art, as cleave-split --open")
    parser.add_argument("--hollow", action="store_true", help="do not cap the cuts")
    parser.add_argument("--report", help="the JSON report (default OUT/report.json)")
    args = parser.parse_args(argv)
    if not args.plane and args.slices <= 0:
        parser.error("give at least one --plane or --slices K")
    if args.workers < 1:
        parser.error("--workers must be at least 1")
    if not os.path.isdir(args.input_dir):
        parser.error(f"{args.input_dir}: not a folder")
    return args


def run(args):
    """Slice every model of args.input_dir on args.workers processes; returns the report dict."""
    models = find_models(args.input_dir)
    planes = [((p[0], p[1], p[2]), p[3]) for p in args.plane]
    options = {"open": args.open, "cap": not args.hollow}
    started = time.perf_counter()
    results = []
    progress = Progress(len(models))
    with ProcessPoolExecutor(max_workers=args.workers) as pool:
        futures = {}
        for model in models:
            out_dir = os.path.join(args.out, os.path.splitext(model)[0])
            futures[pool.submit(slice_model, os.path.join(args.input_dir, model), planes, args.slices,
                                "xyz".index(args.axis), out_dir, args.format, options)] = model
        for future in as_completed(futures):
            try:
                results.append(future.result())
            except Exception as error:  # a worker that died: reported, the others go on
                results.append({"model": os.path.join(args.input_dir, futures[future]), "pieces": [],
                                "error": f"worker failed: {type(error).__name__}: {error}", "seconds": 0.0})
            progress.step(futures[future])
    progress.close()
    results.sort(key=lambda r: r["model"])
    failed = sum(1 for r in results if r["error"])
    return {"input_dir": args.input_dir, "models": len(results), "failed": failed, "workers": args.workers,
            "seconds": time.perf_counter() - started, "results": results}


def main(argv=None):
    """Run the tool; returns the exit status (0 all sliced, 1 some failed)."""
    args = parse_arguments(sys.argv[1:] if argv is None else argv)
    os.makedirs(args.out, exist_ok=True)
    report = run(args)
    path = args.report or os.path.join(args.out, "report.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(report, f, indent=2)
    pieces = sum(len(r["pieces"]) for r in report["results"])
    print(f"{report['models']} models, {pieces} pieces, {report['failed']} failed, "
          f"{report['seconds']:.2f} s on {report['workers']} workers; report {path}")
    for result in report["results"]:
        if result["error"]:
            print(f"  {result['model']}: {result['error']}", file=sys.stderr)
    return 1 if report["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
