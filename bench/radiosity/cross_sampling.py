#!/usr/bin/env python3
"""Cross redistribution's error against the high-settings gather, one setting at a time (review finding 6).

Usage: bench/radiosity/cross_sampling.py [BOUNCE]   (BOUNCE defaults to build/src/app/bounce)

`cornell-box-rotating` (large light, elementSize 0.05, 128², frame 12 after redistributing every frame
since 0), against `radiosity-gather hemicubeSize=128 bounces=16` at frame 12 (the thesis's reference, as in
bench/radiosity/run.py's Q): NRMSE and relMSE of cross redistribution at its defaults and with one
setting changed: the projection's sampling (crossGrid, backHemicubeSize, msaa, reprojection), the
visibility samples, the random rotation, the ray weights, the moving patches' size, and the
progressive propagation after each redistribution; PR beside them. The raw record goes to
bench/results/radiosity-cross-sampling-<date>.json.
"""
import functools
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import compare as compare_metrics, rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

# The metrics of `bounce compare` this record keeps (bench/cli.py compare).
compare = functools.partial(compare_metrics, keys=("nrmse", "relMse", "energy"))

BASE = ["--scene", "cornell-box-rotating", "--scene-param", "light=large", "--size", "128x128", "--set", "elementSize=0.05"]
VARIANTS = {"defaults": {}, "crossGrid=8": {"crossGrid": "8"}, "crossGrid=16": {"crossGrid": "16"},
            "backHemicubeSize=32": {"backHemicubeSize": "32"}, "backHemicubeSize=64 crossGrid=16": {"backHemicubeSize": "64", "crossGrid": "16"},
            "msaa=1": {"msaa": "1"}, "reprojection=false": {"reprojection": "false"}, "visibilitySamples=1": {"visibilitySamples": "1"},
            "randomRotation=false": {"randomRotation": "false"}, "crossWeights=formFactor": {"crossWeights": "formFactor"},
            "dynamicElementSize=0.05": {"dynamicElementSize": "0.05"}, "propagate=false": {"propagate": "false"},
            "propagate=false crossGrid=16 backHemicubeSize=64": {"propagate": "false", "crossGrid": "16", "backHemicubeSize": "64"}}


def render(bounce, technique, frames, start, settings, out):
    cmd = [bounce, "render", "--technique", technique, "--frames", str(frames), "--start-frame", str(start), "--out", out] + BASE
    if technique != "radiosity-gather":  # whole frames, not a host-dependent time budget's share
        settings = {"frameBudgetMs": "0", **settings}
    for k, v in settings.items():
        cmd += ["--set", f"{k}={v}"]
    subprocess.run(cmd, check=True, capture_output=True)
    return rel(cmd)


def main():
    bounce = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build/src/app/bounce"))
    rec = new_record("radiosity-cross-sampling", "bench/radiosity/cross_sampling.py", bounce)
    with tempfile.TemporaryDirectory() as tmp:
        high = os.path.join(tmp, "high.exr")
        rec["gatherHighCommand"] = render(bounce, "radiosity-gather", 1, 12, {"hemicubeSize": "128", "bounces": "16"}, high)
        pr = os.path.join(tmp, "pr.exr")
        rec["pr"] = {"command": render(bounce, "radiosity-pr", 1, 12, {}, pr), "vsGatherHigh": compare(bounce, pr, high)}
        rec["cross"] = {}
        for label, settings in VARIANTS.items():
            out = os.path.join(tmp, "cross.exr")
            cmd = render(bounce, "radiosity-cross", 13, 0, settings, out)
            rec["cross"][label] = {"command": cmd, "vsGatherHigh": compare(bounce, out, high)}
            m = rec["cross"][label]["vsGatherHigh"]
            print(f"{label:50s} NRMSE {m['nrmse']:.4f} relMSE {m['relMse']:.5f} energy {m['energy']:.4f}", flush=True)
    print("PR", rec["pr"]["vsGatherHigh"])
    print(write_record(rec))


if __name__ == "__main__":
    main()
