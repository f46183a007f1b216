#!/usr/bin/env python3
"""The RSM-family gathers' optional VPL visibility (docs/techniques/rsm.md, "VPL visibility") on
furnished-room: the error it removes and the time it costs.

Usage: bench/vpl-visibility/run.py [BOUNCE] [--reps N] [--size N] [--frames N]
       (BOUNCE defaults to build/src/app/bounce; 3 repetitions, 128^2, 3 frames per run)

For each of rsm, isr and hisr (defaults: RSM 256^2, 256 VPLs / clusters / tree) the scene is rendered with
vplVisibility off and on, interleaved (off on off on ..., technique by technique within a repetition), each
run `bounce render --frames N --stats`. Frame time: the GPU "frame" scope of every frame after the first
(the first compiles shaders on llvmpipe), pooled over the repetitions: median (min-max); the voxelize and
gather scopes the same way. Error: relMSE (and RMSE) of the run's indirect image against the path tracer's
one-bounce indirect light (`bounce reference --bounces 1 --indirect-only`), and of a second reference
with another seed (the reference's own noise). The images are deterministic, so the error is the same in
every repetition (recorded per repetition all the same). The raw record goes to
bench/results/vpl-visibility-<date>.json; bench/tables.py makes the README section from it.
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
compare = functools.partial(compare_metrics, keys=("relMse", "rmse"))

TECHNIQUES = ["rsm", "isr", "hisr"]
SCENE = "furnished-room"
# Reference samples per pixel: at 128^2 the one-bounce image's per-pixel noise at 2048 spp is a few per
# cent; its relMSE against a second seed is recorded beside the techniques' (the noise floor).
REFERENCE_SPP = 2048


def option(args, name, default):
    if name in args:
        value = args[args.index(name) + 1]
        del args[args.index(name):args.index(name) + 2]
        return int(value)
    return default


def later_frames(record):
    # The frames after the first (the first compiles shaders on llvmpipe), or all of a one-frame run.
    return record["frames"][1:] or record["frames"]


def main():
    args = sys.argv[1:]
    reps = option(args, "--reps", 3)
    size = option(args, "--size", 128)
    frames = option(args, "--frames", 3)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    rec = new_record("vpl-visibility", f"bench/vpl-visibility/run.py --reps {reps} --size {size} --frames {frames}", bounce)
    rec.update({"scene": SCENE, "size": size, "reps": reps, "frames": frames, "referenceSpp": REFERENCE_SPP})
    with tempfile.TemporaryDirectory() as tmp:
        ref = os.path.join(tmp, "ref.exr")
        ref2 = os.path.join(tmp, "ref2.exr")
        refcmd = [bounce, "reference", "--scene", SCENE, "--size", f"{size}x{size}", "--spp", str(REFERENCE_SPP),
                  "--bounces", "1", "--indirect-only", "--out", ref]
        subprocess.run(refcmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        subprocess.run(refcmd[:-1] + [ref2, "--seed", "1"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        rec["referenceCommand"] = rel(refcmd)
        rec["referenceNoise"] = compare(bounce, ref2, ref)
        runs = {(t, v): [] for t in TECHNIQUES for v in ("off", "on")}
        commands = {}
        for rep in range(reps):
            for t in TECHNIQUES:
                for v in ("off", "on"):
                    out = os.path.join(tmp, f"{t}-{v}.exr")
                    stats = os.path.join(tmp, f"{t}-{v}.json")
                    cmd = [bounce, "render", "--scene", SCENE, "--technique", t, "--size", f"{size}x{size}",
                           "--frames", str(frames), "--component", "indirect", "--set",
                           f"vplVisibility={'true' if v == 'on' else 'false'}", "--out", out, "--stats", stats]
                    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                    with open(stats) as f:
                        record = json.load(f)
                    runs[(t, v)].append({"record": record, "error": compare(bounce, out, ref)})
                    commands[(t, v)] = rel(cmd)
            print("rep", rep + 1, "of", reps, flush=True)
    results = {}
    for (t, v), rs in runs.items():
        later = [f for r in rs for f in later_frames(r["record"])]
        scope = lambda name: [f["gpu_ms"].get(name, 0.0) for f in later]
        last = rs[-1]["record"]["frames"][-1]["counters"]
        results.setdefault(t, {})[v] = {
            "command": commands[(t, v)],
            "frameMs": summary(scope("frame")),
            "voxelizeMs": summary(scope(f"{t}/voxelize")),
            "gatherMs": summary(scope(f"{t}/gather")),
            "relMse": [r["error"]["relMse"] for r in rs],
            "rmse": [r["error"]["rmse"] for r in rs],
            "gatherDraws": last.get("gatherDraws"),
            "vpls": last.get("vpls"),
            "visibilityRays": last.get("visibilityRays"),
            "visibilityBlocked": last.get("visibilityBlocked"),
        }
    # Per-repetition cost ratio on / off (the interleaved pairs), for the spread behind the medians.
    for t in TECHNIQUES:
        pairs = zip(runs[(t, "off")], runs[(t, "on")])
        results[t]["onOverOffPerRep"] = [
            statistics.median(f["gpu_ms"]["frame"] for f in later_frames(b["record"])) /
            statistics.median(f["gpu_ms"]["frame"] for f in later_frames(a["record"])) for a, b in pairs]
        print(t, {v: (round(results[t][v]["frameMs"]["median"], 1), round(results[t][v]["relMse"][0], 4)) for v in ("off", "on")},
              flush=True)
    rec["results"] = results
    print(write_record(rec))


if __name__ == "__main__":
    main()
