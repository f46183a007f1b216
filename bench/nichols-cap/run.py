#!/usr/bin/env python3
"""Nichols 2010 results that need the indirect-resolution cap (setting `indirectSize`) or that were not
measured yet: R2 and R3 as the thesis measured them (fixed output, indirect resolution varied), the
points/quads splat switch (§3.4.1), and R7 (isr / hisr saturate once gathering stops dominating).

Usage: bench/nichols-cap/run.py [BOUNCE] [--reps N] [--output N] [--r3-output N] [--quick]
       (defaults: build/src/app/bounce, 5 repetitions, R2 at a 1024^2 output, R3 / points-quads / R7 at 512^2
       and 256^2; --quick: 2 repetitions, outputs 256^2, for a smoke run)

Every run is one `bounce render --frames 2 --stats` with `renderer.timing=finish` (a glFinish at every pass
boundary: each pass's wall-clock work on llvmpipe); the second frame is measured (the first compiles
shaders). Sides of a comparison are interleaved (A B A B ...); ratios per repetition, min / median / max.
  r2      `multires-splat` on `cornell-box` at a fixed output, indirectSize 32 / 64 / 128 / 256 (and the
          output size): counter fillFraction = splats / (VPLs x indirect pixels) and subsplats per level
          (Table 3.1: ~46 / 21 / 10 / 5 % at 32^2..256^2 in a 1024^2 window). Counts: one run each.
  r3      `multires-splat` on `atrium` (25K / 100K / 400K triangles) at a fixed output, indirectSize 128,
          interleaved; and on `cornell-box` indirectSize 128 against the output size (Table 3.2: 128^2 ->
          1024^2 indirect costs the thesis 2-3x in fps).
  prim    `multires-splat` splatPrimitive=points against quads (§3.4.1: points ~5 % faster on its GPU), interleaved.
  r7      frame time and each pass's share against the VPL count: `isr vplMode=regular` with vplGrid 4 / 8 /
          16 / 32 and `hisr` with tau 0.1 / 0.03 / 0.01 / 0.003 (more nodes walked as tau falls), `cornell-box`.
The raw record goes to bench/results/nichols-cap-<date>.json; bench/tables.py makes the README table.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from cli import ROOT, counter_mean, option, pass_ms, render, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402

FRAMES = 2
FINISH = {"renderer.timing": "finish"}
# The thesis's multiresolution splatting (Nichols 2010 ch. 3): point splats and geometry-shader refinement, not
# bounce's defaults (splatPrimitive=auto, refinePass=compute; same images, docs/techniques/multires-splat.md).
THESIS = {"splatPrimitive": "points", "refinePass": "geometry"}


def mean(values):
    values = list(values)
    return sum(values) / len(values)


def frame_ms(r):
    return mean(pass_ms(r, "frame"))


def passes(r):
    """Mean ms of every pass of the measured frames (the frame scope excluded)."""
    frames = r["frames"][1:] or r["frames"]
    names = sorted({k for f in frames for k in f["gpu_ms"] if k != "frame"})
    return {n: mean(f["gpu_ms"].get(n, 0.0) for f in frames) for n in names}


def interleaved(bounce, sides, reps, size, measure):
    out = {name: [] for name in sides}
    commands = {}
    for _ in range(reps):
        for name, (scene, technique, settings, params) in sides.items():
            r, cmd = render(bounce, scene, technique, size, FRAMES, {**FINISH, **settings}, params)
            commands[name] = cmd
            out[name].append(measure(r))
    return out, commands


def ratio(a, b):
    return summary(x / y for x, y in zip(a, b))


def main():
    args = sys.argv[1:]
    quick = "--quick" in args
    args = [a for a in args if a != "--quick"]
    reps = option(args, "--reps", 2 if quick else 5)
    output = option(args, "--output", 256 if quick else 1024)
    r3_output = option(args, "--r3-output", 256 if quick else 512)
    r7_output = option(args, "--r7-output", 256)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    rec = new_record("nichols-cap", f"bench/nichols-cap/run.py --reps {reps} --output {output} --r3-output {r3_output} "
                     f"--r7-output {r7_output}", bounce)
    rec.update({"reps": reps, "frames": FRAMES, "timing": "finish"})

    # r2: counts at a fixed output.
    r2 = {"output": output, "cases": {}}
    for cap in [32, 64, 128, 256, output]:
        if cap > output or str(cap) in r2["cases"]:
            continue
        r, cmd = render(bounce, "cornell-box", "multires-splat", output, FRAMES, {**FINISH, "indirectSize": cap})
        levels = sorted(int(k.split("-")[-1]) for k in r["frames"][-1]["counters"] if k.startswith("subsplats/level-"))
        r2["cases"][str(cap)] = {"command": cmd, "fillFraction": counter_mean(r, "fillFraction"),
                                 "subsplats": counter_mean(r, "subsplats"), "frameMs": frame_ms(r),
                                 "levels": {str(k): counter_mean(r, f"subsplats/level-{k}") for k in levels}}
    rec["r2"] = r2
    print("r2", {k: round(100 * v["fillFraction"], 1) for k, v in r2["cases"].items()}, flush=True)

    # r3: triangles at a fixed output and indirect resolution; then the indirect resolution's cost.
    r3reps = max(2, reps - 2)
    sides = {t: ("atrium", "multires-splat", {**THESIS, "indirectSize": 128}, [f"triangles={t}"]) for t in ["25000", "100000", "400000"]}
    runs, cmds = interleaved(bounce, sides, r3reps, r3_output,
                             lambda r: {"frame": frame_ms(r), "triangles": counter_mean(r, "triangles")})
    rec["r3"] = {"output": r3_output, "indirectSize": 128, "reps": r3reps, "commands": cmds,
                 "cases": {k: {"triangles": v[0]["triangles"], "frameMs": summary(x["frame"] for x in v)} for k, v in runs.items()}}
    sides = {"128": ("cornell-box", "multires-splat", {**THESIS, "indirectSize": 128}, []),
             str(r3_output): ("cornell-box", "multires-splat", {**THESIS, "indirectSize": 0}, [])}
    runs, cmds = interleaved(bounce, sides, reps, r3_output, frame_ms)
    rec["r3"]["resolution"] = {"commands": cmds, "frameMs": {k: summary(v) for k, v in runs.items()},
                               "ratio": ratio(runs[str(r3_output)], runs["128"])}
    print("r3", {k: round(v["frameMs"]["median"]) for k, v in rec["r3"]["cases"].items()},
          round(rec["r3"]["resolution"]["ratio"]["median"], 2), flush=True)

    # prim: points vs quads (same fragments, same image).
    sides = {"points": ("cornell-box", "multires-splat", {**THESIS, "splatPrimitive": "points"}, []),
             "quads": ("cornell-box", "multires-splat", {**THESIS, "splatPrimitive": "quads"}, [])}
    runs, cmds = interleaved(bounce, sides, reps, r3_output,
                             lambda r: {"frame": frame_ms(r), "splat": mean(pass_ms(r, "multires-splat/splat"))})
    rec["prim"] = {"output": r3_output, "reps": reps, "commands": cmds,
                   "frameMs": {k: summary(x["frame"] for x in v) for k, v in runs.items()},
                   "splatMs": {k: summary(x["splat"] for x in v) for k, v in runs.items()},
                   "frameRatio": ratio([x["frame"] for x in runs["quads"]], [x["frame"] for x in runs["points"]]),
                   "splatRatio": ratio([x["splat"] for x in runs["quads"]], [x["splat"] for x in runs["points"]])}
    print("prim", round(rec["prim"]["frameRatio"]["median"], 3), round(rec["prim"]["splatRatio"]["median"], 3), flush=True)

    # r7: frame time and pass shares against the VPL count.
    r7reps = max(2, reps - 2)
    sides = {f"isr vplGrid={g}": ("cornell-box", "isr", {"vplMode": "regular", "vplGrid": g}, []) for g in [4, 8, 16, 32]}
    sides.update({f"hisr tau={t}": ("cornell-box", "hisr", {"tau": t}, []) for t in ["0.1", "0.03", "0.01", "0.003"]})
    runs, cmds = interleaved(bounce, sides, r7reps, r7_output,
                             lambda r: {"frame": frame_ms(r), "passes": passes(r), "vpls": counter_mean(r, "vpls"),
                                        "gatherFragments": counter_mean(r, "gatherFragments"),
                                        "nodesPerFragment": counter_mean(r, "nodesPerFragment")})
    cases = {}
    for k, v in runs.items():
        names = sorted({n for x in v for n in x["passes"]})
        cases[k] = {"vpls": v[0]["vpls"], "nodesPerFragment": v[0]["nodesPerFragment"], "gatherFragments": v[0]["gatherFragments"],
                    "frameMs": summary(x["frame"] for x in v),
                    "passMs": {n: summary(x["passes"].get(n, 0.0) for x in v) for n in names}}
    rec["r7"] = {"output": r7_output, "reps": r7reps, "commands": cmds, "cases": cases}
    print("r7", {k: round(v["frameMs"]["median"]) for k, v in cases.items()}, flush=True)
    print(write_record(rec))


if __name__ == "__main__":
    main()
