#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs the mutations of tests/mutations.md: each breaks the production code in one place, builds,
runs the tests that should notice, and puts the file back as it was (uncommitted edits included).

    tools/run_mutations.py [--build-dir DIR] [--only SUBSTRING]

Prints one row per mutation (caught by which tests, or NOT CAUGHT) and exits 1 when any mutation
is not caught or a mutation site is no longer found. Builds in DIR (default build/, configured as
./cleave test configures it); a run of every mutation takes about as long as 15 incremental builds.
"""
import argparse
import pathlib
import re
import signal
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

# (name, file, text to replace, replacement, ctest regex of the tests to run)
MUTATIONS = [
    ("unknown handler commits", "components/split_system.cpp",
     "    if (it == handlers_.end())\n      return finish(",
     "    if (false)\n      return finish(",
     "SplitPipeline"),
    ("splitter ignores SplitOptions::threads", "engine/geometry/mesh_splitter.cpp",
     "  threads_ = options.threads;", "  threads_ = 1;",
     "ConcaveSplitter|PassThreads"),
    ("split workers never used", "components/split_workers.cpp",
     "  } else if (threads_.empty()) {", "  } else if (true) {",
     "SplitPipeline|SplitSystem|Shatter|EveryReplayGivesTheSameState"),
    ("worker-time budget check off", "components/split_budget.cpp",
     " ||\n                                stats_.workerMillisecondsCharged >= settings_.workerMillisecondsPerTick)",
     ")",
     "SplitBudget"),
    ("busy target not waited for", "components/split_budget.cpp",
     "    if (host.isBusy(r.target)) continue;", "",
     "SplitBudget"),
    ("lost skin committed", "components/split_system.cpp",
     "  if (job.skinned() && !w.world.has<SkinnedMesh>(target))", "  if (false)",
     "SkinnedSplit"),
    ("changed hierarchy part committed", "components/split_system.cpp",
     "    if (!same) return finish(", "    if (same && !same) return finish(",
     "HierarchySplit"),
    ("flat cap triangles not flipped", "engine/geometry/mesh_splitter.cpp",
     "void Splitter::flipFlatCapTriangles() {\n  flatCaps_.clear();",
     "void Splitter::flipFlatCapTriangles() {\n  flatCaps_.clear();\n  if (capTriangles_.size() < size_t(-1)) return;",
     "FlatCapFlip|ConcaveSplitter|SplitInvariants"),
    ("collapsed triangles kept", "engine/geometry/mesh_splitter.cpp",
     "void Splitter::dropCollapsedTriangles() {\n",
     "void Splitter::dropCollapsedTriangles() {\n  if (sideTris_[0].size() < size_t(-1)) return;\n",
     "ConcaveSplitter|SplitRecutStress|SplitRegression"),
    ("near loop points never merged", "engine/geometry/mesh_splitter.cpp",
     "  const double tolerance2 = mergeTolerance_ * mergeTolerance_;", "  const double tolerance2 = 0.0;",
     "SplitRecutStress|ConcaveSplitter"),
    ("AVX-512 mass kernel off by 1%", "engine/geometry/mass_kernel.cpp",
     "                                                const glm::dvec3& ref, bool flip) {\n"
     "  const MomentSums sums = sumLanes(p, indices, ref, flip);\n  _mm256_zeroupper();\n  return sums;\n}\n#else",
     "                                                const glm::dvec3& ref, bool flip) {\n"
     "  MomentSums sums = sumLanes(p, indices, ref, flip);\n  sums.sixV *= 1.01;\n  _mm256_zeroupper();\n"
     "  return sums;\n}\n#else",
     "MassIntegration"),
    ("fracture seeds ignore the seed after cell 0", "engine/geometry/fracture.cpp",
     "    seeds.push_back(p);\n  }\n  return seeds;",
     "    seeds.push_back(p);\n    if (k == 0) rng = SplitMix{1};\n  }\n  return seeds;",
     "Fracture"),
    ("awake limit only freezes creepers", "components/piece_budget.cpp",
     "  retireAwake(", "  if (false) retireAwake(",
     "PieceBudget"),
    ("a runner wakes the queued pieces twice a tick", "components/scene_runner.cpp",
     "  runner.update(w, tick, dt);  // Gameplay\n",
     "  runner.update(w, tick, dt);  // Gameplay\n  splits.activatePending(w);\n",
     "TickOrder"),
    ("hello_split fails after printing", "examples/hello_split.cpp",
     "  return 0;\n}", "  return 3;\n}",
     "Example|Consumer"),
]


def run(command, **kwargs):
    return subprocess.run(command, cwd=ROOT, text=True, capture_output=True, **kwargs)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--only", default="")
    args = parser.parse_args()
    build = ROOT / args.build_dir
    if not (build / "CMakeCache.txt").exists():
        print(f"{build}: not configured (run ./cleave test first)", file=sys.stderr)
        return 2
    # Stopped (Ctrl-C, a kill): leave through the `finally` below, which puts the file back.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))
    failures = 0
    print("| mutation | caught by |\n|---|---|")
    for name, relative, old, new, tests in MUTATIONS:
        if args.only and args.only not in name:
            continue
        path = ROOT / relative
        original = path.read_text()
        if original.count(old) < 1:
            print(f"| {name} | SITE NOT FOUND in {relative} |")
            failures += 1
            continue
        try:
            path.write_text(original.replace(old, new, 1))
            built = run(["cmake", "--build", str(build), "-j", "2"])
            if built.returncode != 0:
                print(f"| {name} | BUILD FAILED: {built.stdout[-300:]} |")
                failures += 1
                continue
            tested = run(["ctest", "--test-dir", str(build), "-j", "2", "--timeout", "600", "-R", tests])
            caught = re.findall(r"\d+ - (\S+) \(Failed\)", tested.stdout)
            print(f"| {name} | {', '.join(caught) if caught else 'NOT CAUGHT'} |", flush=True)
            failures += not caught
        finally:
            path.write_text(original)
    run(["cmake", "--build", str(build), "-j", "2"])  # back to the code as it is
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
