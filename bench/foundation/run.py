#!/usr/bin/env python3
"""The foundation and the ground truth: `direct` frame times and the reference path tracer's rates.

Usage: bench/foundation/run.py [BOUNCE] [--reps N] [--bench BOUNCE_BENCH]
       (defaults: build/src/app/bounce, 3 repetitions, build/bench/bounce_bench)

  direct     `bounce render --technique direct --size 512x512 --frames 20 --stats` on cornell-box and atrium
             (100K triangles), repeated N times interleaved; per run the record's median_ms (frame,
             gbuffer, direct: timestamp queries, the frame as it runs).
  reference  bounce_bench's BM_ReferencePathTracer* and BM_ReferenceRayCaster* with
             --benchmark_repetitions=5 (Google Benchmark JSON kept): camera paths/s and rays/s per
             thread count and kernel (vectorized 0/1) on cornell-box-area 512^2 and the other scenes at 256^2.
The raw record goes to bench/results/foundation-<date>.json; bench/tables.py makes the README tables.
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from cli import ROOT, option, render, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402

SCENES = ["cornell-box", "atrium"]
PASSES = ["frame", "gbuffer", "direct"]


def main():
    args = sys.argv[1:]
    reps = option(args, "--reps", 3)
    bench = option(args, "--bench", os.path.join(ROOT, "build/bench/bounce_bench"), str)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    rec = new_record("foundation", f"bench/foundation/run.py --reps {reps}", bounce)
    runs = {s: {p: [] for p in PASSES} for s in SCENES}
    commands, triangles = {}, {}
    for _ in range(reps):
        for scene in SCENES:
            r, cmd = render(bounce, scene, "direct", 512, 20)
            commands[scene] = cmd
            triangles[scene] = r["scene"]["triangles"]
            for p in PASSES:
                runs[scene][p].append(r["median_ms"].get(p, 0.0))
    rec["direct"] = {s: {"command": commands[s], "triangles": triangles[s],
                         "ms": {p: summary(v) for p, v in runs[s].items()}} for s in SCENES}
    print("direct", {s: round(v["ms"]["frame"]["median"], 1) for s, v in rec["direct"].items()}, flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "bench.json")
        cmd = [bench, "--benchmark_filter=BM_Reference(PathTracer|RayCaster)", "--benchmark_repetitions=5",
               "--benchmark_out_format=json", "--benchmark_out=" + out]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        with open(out) as f:
            data = json.load(f)
    rec["reference"] = {"command": os.path.relpath(bench, ROOT) + " " + " ".join(cmd[1:4]),
                        "context": {k: data["context"].get(k) for k in ["num_cpus", "mhz_per_cpu", "library_build_type"]},
                        "benchmarks": [{k: v for k, v in b.items() if isinstance(v, (int, float, str))} for b in data["benchmarks"]]}
    print(write_record(rec))


if __name__ == "__main__":
    main()
