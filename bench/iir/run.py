#!/usr/bin/env python3
"""Incremental instant radiosity (Laine et al. 2007), `iir`: the paper's headline results as ratios,
measured by interleaving the incremental method and its comparison mode (A B A B ...).

Usage: bench/iir/run.py [BOUNCE] [--reps N] [--frames N] [--size N] [--bench BOUNCE_BENCH]
       (defaults: build/src/app/bounce, 5 pairs, 12 frames, 256^2, build/bench/bounce_bench)

Each side of a pair is one `bounce render --frames N --stats` process with `renderer.timing=finish`
(a glFinish at every pass boundary: the pass times are the passes' own wall-clock cost on llvmpipe,
which otherwise charges deferred rasterisation to later scopes). Per run, over the frames after the
first (frame 0 fills the VPL budget in both modes): the mean frame time ("frame" scope), shadow-map
time ("iir/sm-rendering") and the counts behind them (vplShadowMaps: maps rendered per frame,
vplsCreated / vplsDeleted / vplsInvalidated). A ratio is formed per pair (comparison / incremental)
and reported as min / median / max with the pair count.
  R1  shadow-map time, comparison / incremental (paper 41-45x), beside the map-count ratio that bounds it
  R2  frame speed-up on cornell-box-dynamic (paper CORNELL 1.9x)
  R3  frame speed-up on atrium (20K triangles; paper: grows with complexity, 6.8x on SIBENIK)
  R6  frame speed-up with 1024 VPLs (paper: 31 vs 2 fps on SIBENIK, 15x)
Not ratios of times, run once through bounce_bench (Google Benchmark JSON kept in the record):
  R5  VPL management CPU time, omni / spot (BM_IirOmniVsSpot), flicker (BM_IirFlicker: incremental vs
      comparison, still camera, 30 frames), quality against the one-bounce path tracer (BM_IirQuality*).
The raw record goes to bench/results/iir-<date>.json; bench/tables.py makes the README table from it.
"""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from cli import ROOT, counter_mean, option, pass_ms, render, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402

ATRIUM_TRIANGLES = 20000  # the paper's scenes are 10K-80K triangles; 100K makes a comparison run minutes long
CASES = {
    "cornell-box-dynamic/256": {"scene": "cornell-box-dynamic", "params": [], "maxLights": 256},
    "atrium/256": {"scene": "atrium", "params": [f"triangles={ATRIUM_TRIANGLES}"], "maxLights": 256},
    "cornell-box-dynamic/1024": {"scene": "cornell-box-dynamic", "params": [], "maxLights": 1024},
    "atrium/1024": {"scene": "atrium", "params": [f"triangles={ATRIUM_TRIANGLES}"], "maxLights": 1024},
}
MODES = {"incremental": "true", "comparison": "false"}
COUNTS = ["vplShadowMaps", "vplsCreated", "vplsDeleted", "vplsInvalidated", "vpls"]


def mean(values):
    values = list(values)
    return sum(values) / len(values)


def main():
    args = sys.argv[1:]
    reps = option(args, "--reps", 5)
    frames = option(args, "--frames", 12)
    size = option(args, "--size", 256)
    bench = option(args, "--bench", os.path.join(ROOT, "build/bench/bounce_bench"), str)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    rec = new_record("iir", f"bench/iir/run.py --reps {reps} --frames {frames} --size {size}", bounce)
    rec.update({"reps": reps, "frames": frames, "size": size, "timing": "finish", "cases": {}})
    for name, case in CASES.items():
        runs = {m: [] for m in MODES}
        commands = {}
        for _ in range(reps):
            for mode, flag in MODES.items():  # A B A B ...
                r, cmd = render(bounce, case["scene"], "iir", size, frames,
                                {"incremental": flag, "maxLights": case["maxLights"], "renderer.timing": "finish"},
                                case["params"])
                commands[mode] = cmd
                runs[mode].append({"frameMs": mean(pass_ms(r, "frame")),
                                   "shadowMapMs": mean(pass_ms(r, "iir/sm-rendering")),
                                   "iirMs": mean(pass_ms(r, "iir")),
                                   "counts": {c: counter_mean(r, c) for c in COUNTS}})
        inc, comp = runs["incremental"], runs["comparison"]
        entry = {"scene": case["scene"], "params": case["params"], "maxLights": case["maxLights"],
                 "commands": commands, "runs": runs,
                 "smRatio": summary(c["shadowMapMs"] / i["shadowMapMs"] for i, c in zip(inc, comp)),
                 "mapCountRatio": summary(c["counts"]["vplShadowMaps"] / max(i["counts"]["vplShadowMaps"], 1e-9)
                                          for i, c in zip(inc, comp)),
                 "frameSpeedup": summary(c["frameMs"] / i["frameMs"] for i, c in zip(inc, comp)),
                 "frameMs": {m: summary(x["frameMs"] for x in runs[m]) for m in MODES},
                 "shadowMapMs": {m: summary(x["shadowMapMs"] for x in runs[m]) for m in MODES},
                 "mapsPerFrame": {m: mean(x["counts"]["vplShadowMaps"] for x in runs[m]) for m in MODES}}
        rec["cases"][name] = entry
        print(name, "R1", round(entry["smRatio"]["median"], 1), "maps", round(entry["mapCountRatio"]["median"], 1),
              "frame", round(entry["frameSpeedup"]["median"], 2), flush=True)
    if os.path.exists(bench):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "bench.json")
            cmd = [bench, "--benchmark_filter=BM_Iir(OmniVsSpot|Flicker|QualityCornell|QualityCornellDynamic)/",
                   "--benchmark_out_format=json", "--benchmark_out=" + out]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            with open(out) as f:
                results = json.load(f)["benchmarks"]
        rec["bench"] = {"command": os.path.relpath(bench, ROOT) + " " + " ".join(cmd[1:3]),
                        "benchmarks": {b["name"].split("/")[0]: {k: v for k, v in b.items() if isinstance(v, (int, float))}
                                       for b in results}}
    print(write_record(rec))


if __name__ == "__main__":
    main()
