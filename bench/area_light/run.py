#!/usr/bin/env python3
"""Benchmarks of `area-light` (Nichols 2010 ch. 5) through the CLI's run records.

Usage: bench/area_light/run.py [BOUNCE] [--quick] [--reps N]   (BOUNCE defaults to build/src/app/bounce)

R8 rows (summary ../shared/specs, result R8; thesis §5.4):
  fractions  fraction of each level's cells rendered (thesis: ~50 % of 64^2 fragments, 10-15 % of
             1024^2 pixels), at 1024^2 (512^2 with --quick); partially visible VPLs per 3x3
             neighbourhood (thesis: < 5 %).
  incremental vs brute-force visibility: rays cast and reused, gather and frame GPU ms, interleaved
             (incremental, brute, incremental, ...), --reps repetitions; ratio per rep.
  voxels     128^2 x 128 vs 1024^2 x 128 voxel grids (thesis: "almost indistinguishable"): relMSE and
             HDR-FLIP against `bounce reference --bounces 0`, voxelize and gather ms.
  vpls       256 vs 16,384 VPLs: moved to bench/area_light/vpls.py (record area-light-vpls-DATE).
  quality    relMSE / HDR-FLIP against `bounce reference --bounces 0` on cornell-box-area and the
             textured screen scene (area-screen), beside V = 1 and the shared centre-shadowed direct pass.
  baseline   at 1024 VPLs: incremental and brute-force voxel visibility against the rasterized
             baseline of §5.4.6 (one 64^2 paraboloid shadow map per VPL), error and time.
  threshold  frame ms and rendered fragments against the colour threshold (thesis: it dominates the
             cost when low, 0.005).
Frame times: GPU scope of the technique, median over the frames after the first (the first compiles
shaders on llvmpipe). The raw record goes to bench/results/area-light-<date>.json; bench/tables.py
makes the README table from it. llvmpipe times are indicative; counts and ratios are the result.
"""
import functools
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import compare as compare_metrics, rel, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402

# The metrics of `bounce compare` this record keeps (bench/cli.py compare).
compare = functools.partial(compare_metrics, keys=("relMse", "flipHdr", "nrmse"))

CORNELL = {"scene": "cornell-box-area", "params": []}
# The bouncing-square light of Fig. 5.15 (built-in scene area-screen, pattern=square).
SQUARE = {"scene": "area-screen", "params": ["pattern=square"]}
FRAMES = 3


def render(bounce, case, size, settings=None, out=None, frames=FRAMES):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "run.json")
        cmd = [bounce, "render", "--scene", case["scene"], "--technique", "area-light", "--size", f"{size}x{size}",
               "--frames", str(frames), "--out", out or os.path.join(tmp, "o.exr"), "--stats", stats]
        for p in case["params"]:
            cmd += ["--scene-param", p]
        for k, v in (settings or {}).items():
            cmd += ["--set", f"{k}={v}"]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        with open(stats) as f:
            return json.load(f), rel(cmd)


def reference(bounce, case, size, out, spp, frame):
    cmd = [bounce, "reference", "--scene", case["scene"], "--size", f"{size}x{size}", "--bounces", "0",
           "--spp", str(spp), "--frame", str(frame), "--out", out]
    for p in case["params"]:
        cmd += ["--scene-param", p]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return rel(cmd)


def later(rec):
    return rec["frames"][1:] if len(rec["frames"]) > 1 else rec["frames"]


def gpu(rec, scope):
    return [f["gpu_ms"].get(scope, 0.0) for f in later(rec)]


def counter(rec, name):
    return statistics.median(f["counters"].get(name, 0.0) for f in later(rec))


def has_scene(bounce, name):
    out = subprocess.run([bounce, "list"], capture_output=True, text=True).stdout
    return name in out


def main():
    args = list(sys.argv[1:])
    quick = "--quick" in args
    reps = 3
    if "--reps" in args:
        reps = int(args[args.index("--reps") + 1])
        del args[args.index("--reps"):args.index("--reps") + 2]
    args = [a for a in args if a != "--quick"]
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    rec = new_record("area-light", "bench/area_light/run.py" + (" --quick" if quick else "") + f" --reps {reps}", bounce)
    rec["reps"] = reps
    big = 512 if quick else 1024
    size = 128 if quick else 256

    # R8: fractions of rendered cells per level at big^2.
    r, cmd = render(bounce, CORNELL, big)
    levels = sorted(int(k.split("-")[-1]) for k in later(r)[0]["counters"] if k.startswith("renderedFraction/level-"))
    rec["fractions"] = {"size": big, "command": cmd,
                        "levels": {str(k): {"cells": f"{big >> k}x{big >> k}",
                                            "renderedFraction": counter(r, f"renderedFraction/level-{k}"),
                                            "fragments": counter(r, f"fragments/level-{k}")} for k in levels},
                        "partiallyVisibleFraction": counter(r, "partiallyVisibleFraction"),
                        "frameMs": summary(gpu(r, "area-light"))}
    print("fractions", {k: round(v["renderedFraction"], 3) for k, v in rec["fractions"]["levels"].items()}, flush=True)

    # Incremental vs brute force, interleaved.
    modes = {"incremental": {}, "brute": {"visibility": "brute"}}
    runs = {m: [] for m in modes}
    cmds = {}
    for _ in range(reps):
        for m, s in modes.items():
            r, c = render(bounce, CORNELL, size, s)
            runs[m].append(r)
            cmds[m] = c
    inc = {}
    for m in modes:
        inc[m] = {"command": cmds[m], "frameMs": summary([v for r in runs[m] for v in gpu(r, "area-light")]),
                  "gatherMs": summary([v for r in runs[m] for v in gpu(r, "area-light/gather-diffuse")]),
                  "raysCast": statistics.median(counter(r, "raysCast") for r in runs[m]),
                  "raysReused": statistics.median(counter(r, "raysReused") for r in runs[m])}
    inc["gatherSpeedupPerRep"] = [statistics.median(gpu(b, "area-light/gather-diffuse")) / statistics.median(gpu(a, "area-light/gather-diffuse"))
                                  for a, b in zip(runs["incremental"], runs["brute"])]
    inc["raysCastRatio"] = inc["incremental"]["raysCast"] / inc["brute"]["raysCast"]
    inc["size"] = size
    rec["incremental"] = inc
    print("incremental", inc["raysCastRatio"], inc["gatherSpeedupPerRep"], flush=True)

    with tempfile.TemporaryDirectory() as tmp:
        # Voxel grids against the reference.
        vsize = 256 if quick else 512
        ref = os.path.join(tmp, "ref.exr")
        refcmd = reference(bounce, CORNELL, vsize, ref, 256 if quick else 1024, FRAMES - 1)
        vox = {"size": vsize, "referenceCommand": refcmd}
        for cols in ([128, 256] if quick else [128, 512, 1024]):
            out = os.path.join(tmp, f"v{cols}.exr")
            r, c = render(bounce, CORNELL, vsize, {"voxelColumns": str(cols)}, out)
            vox[str(cols)] = {"command": c, "vsReference": compare(bounce, out, ref),
                              "voxelizeMs": summary(gpu(r, "area-light/voxelize")),
                              "gatherMs": summary(gpu(r, "area-light/gather-diffuse"))}
        rec["voxels"] = vox
        print("voxels", {k: round(v["vsReference"]["relMse"], 4) for k, v in vox.items() if isinstance(v, dict) and "vsReference" in v}, flush=True)

        # 256 vs 16,384 VPLs: bench/area_light/vpls.py (its own record, with voxel visibility).

    # Quality against the path tracer's direct light, on the Cornell box and the textured screen scene.
    with tempfile.TemporaryDirectory() as tmp:
        quality = {"size": size}
        cases = {"cornell-box-area": CORNELL}
        if has_scene(bounce, "area-screen"):
            cases["area-screen"] = {"scene": "area-screen", "params": []}
        for name, case in cases.items():
            ref = os.path.join(tmp, f"{name}-ref.exr")
            refcmd = reference(bounce, case, size, ref, 256 if quick else 1024, FRAMES - 1)
            entry = {"referenceCommand": refcmd}
            for label, st in {"area-light": {}, "no visibility": {"visibility": "none"}}.items():
                out = os.path.join(tmp, f"{name}-{label}.exr")
                r, c = render(bounce, case, size, st, out)
                entry[label] = {"command": c, "vsReference": compare(bounce, out, ref), "frameMs": summary(gpu(r, "area-light"))}
            # The shared direct pass (area lights shadowed from their centre, textures as their mean).
            out = os.path.join(tmp, f"{name}-direct.exr")
            cmd = [bounce, "render", "--scene", case["scene"], "--technique", "direct", "--size", f"{size}x{size}",
                   "--frames", str(FRAMES), "--component", "direct", "--out", out] + sum((["--scene-param", p] for p in case["params"]), [])
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            entry["direct pass"] = {"command": rel(cmd), "vsReference": compare(bounce, out, ref)}
            quality[name] = entry
        rec["quality"] = quality
        print("quality", {n: {k: round(v["vsReference"]["relMse"], 4) for k, v in e.items() if isinstance(v, dict)} for n, e in quality.items() if isinstance(e, dict)}, flush=True)

    # The rasterized baseline (§5.4.6: 1024 64^2 shadow maps) against the voxel visibility at 1024 VPLs.
    with tempfile.TemporaryDirectory() as tmp:
        ref = os.path.join(tmp, "ref.exr")
        refcmd = reference(bounce, CORNELL, size, ref, 256 if quick else 1024, FRAMES - 1)
        modes = {"incremental": {}, "brute": {"visibility": "brute"}, "shadow-maps": {"visibility": "shadow-maps"}}
        runs = {m: [] for m in modes}
        errs = {}
        cmds = {}
        for rep in range(reps):
            for m, st in modes.items():
                out = os.path.join(tmp, f"{m}.exr")
                r, c = render(bounce, CORNELL, size, {"vplsPerSide": "32", **st}, out)
                runs[m].append(r)
                cmds[m] = c
                if rep == 0:
                    errs[m] = compare(bounce, out, ref)
        base = {"size": size, "vpls": 1024, "referenceCommand": refcmd}
        for m in modes:
            base[m] = {"command": cmds[m], "vsReference": errs[m],
                       "frameMs": summary([v for r in runs[m] for v in gpu(r, "area-light")]),
                       "visibilityMs": summary([v for r in runs[m] for v in gpu(r, "area-light/gather-diffuse")]),
                       "mapsMs": summary([v for r in runs[m] for v in gpu(r, "area-light/vpl-shadow-maps")]),
                       "voxelizeMs": summary([v for r in runs[m] for v in gpu(r, "area-light/voxelize")])}
        base["frameRatioPerRep"] = [statistics.median(gpu(b, "area-light")) / statistics.median(gpu(a, "area-light"))
                                    for a, b in zip(runs["incremental"], runs["shadow-maps"])]
        rec["baseline"] = base
        print("baseline", {m: round(base[m]["frameMs"]["median"], 1) for m in modes}, flush=True)

    # Colour threshold.
    thr = {}
    for t in ["0.005", "0.02", "0.1", "1e9"]:
        r, c = render(bounce, CORNELL, size, {"colourThreshold": t})
        thr[t] = {"command": c, "frameMs": summary(gpu(r, "area-light")), "fragments": counter(r, "gatherFragments"),
                  "raysCast": counter(r, "raysCast")}
    rec["threshold"] = thr
    rec["thresholdSize"] = size
    print("threshold", {k: round(v["frameMs"]["median"], 1) for k, v in thr.items()}, flush=True)
    print(write_record(rec))


if __name__ == "__main__":
    main()
