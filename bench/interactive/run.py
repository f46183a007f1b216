#!/usr/bin/env python3
"""Issue 18: the multiresolution techniques where users run them. Frame times and fps of the Nichols
techniques (and iir) on `cornell-box-dynamic` at 256^2 / 512^2 / 1024^2, each against the brute-force
gather (`rsm`, the same 256 VPLs) and full-screen splatting (`rsm-splat`) in the same run; optionally the
same for a build of the commit before the issue ("before" column).

Usage: bench/interactive/run.py [BOUNCE] [--before BOUNCE_BEFORE [--before-commit SHA]] [--reps N] [--sizes 256,512,1024]
       (defaults: build/src/app/bounce, no before build, 3 repetitions, 256,512,1024)

A side is one `bounce render --stats` process with the default timers (GL timestamp queries: the mode
a user runs); its frame time is the run record's per-frame wall time (`cpu_ms`: renderFrame from its
first call to the glFinish that ends the frame), median over the frames after the first (which compiles
shaders), at 10 frames for 256^2 and 4 above. Every repetition runs every side once, in the same order
(A B C ... A B C ...): a ratio is formed per repetition and reported as min / median / max with the
count. Counts behind the ratios (VPLs, gathered fragments, splats) come from the same records.
At 256^2 a second pass runs every technique once with `renderer.timing=finish` (a glFinish at every
pass boundary: each pass's own wall-clock cost on llvmpipe, which otherwise charges deferred work to
later passes) for the per-pass table.
The raw record goes to bench/results/interactive-<date>.json; bench/tables.py makes the README table.
"""
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from cli import ROOT, counter_mean, later, option, render, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402

SCENE = "cornell-box-dynamic"
# side name -> (technique, settings); `rsm` and `isr regular` gather the same 16^2 regular VPLs.
SIDES = {
    "rsm": ("rsm", {}),
    # the brute-force gather with about as many VPLs as isr's light clusters make (~1250 on this scene)
    "rsm 1024 VPLs": ("rsm", {"rsm.vplGrid": "32"}),
    "rsm-splat": ("rsm-splat", {}),
    "isr": ("isr", {}),
    "isr regular": ("isr", {"isr.vplMode": "regular"}),
    "hisr": ("hisr", {}),
    # the default: splatPrimitive=auto (the stencilled splat of the shared list) and refinePass=compute;
    # before those existed, the default was the thesis's points with geometry-shader refinement
    "multires-splat": ("multires-splat", {}),
    # the thesis's point splats and geometry-shader refinement (same image); not in builds before both existed
    "multires-splat points": ("multires-splat", {"multires-splat.splatPrimitive": "points",
                                                 "multires-splat.refinePass": "geometry"}),
    "iir": ("iir", {}),
}
COUNTERS = ["vpls", "gatherFragments", "splats", "subsplats", "nodesPerFragment", "vplShadowMaps"]
# ratio name -> (numerator side, denominator side): the speed-up of the denominator over the numerator.
RATIOS = {
    "isr over rsm": ("rsm", "isr"),
    "isr over rsm 1024 VPLs": ("rsm 1024 VPLs", "isr"),
    "isr regular over rsm": ("rsm", "isr regular"),
    "hisr over rsm": ("rsm", "hisr"),
    "hisr over rsm 1024 VPLs": ("rsm 1024 VPLs", "hisr"),
    "multires-splat over rsm-splat": ("rsm-splat", "multires-splat"),
    "multires-splat points over rsm-splat": ("rsm-splat", "multires-splat points"),
    # R1: the thesis's multiresolution splatting (points, geometry-shader refinement) against isr's
    # stencilled gather of the same 256 VPLs (Table 4.1's refine + splat vs stencil + gather)
    "multires-splat points over isr regular (R1)": ("multires-splat points", "isr regular"),
}

# A side a before build cannot run -> the side that was the same thing there (its default then).
FALLBACK = {"multires-splat points": "multires-splat"}


def frame_ms(record):
    return statistics.median(f["cpu_ms"] for f in later(record))


def measure(builds, sizes, reps):
    """builds: label -> bounce binary. Every repetition runs every side of every build once (interleaved)."""
    out = {label: {} for label in builds}
    for size in sizes:
        frames = 10 if size <= 256 else 4
        times = {(label, name): [] for label in builds for name in SIDES}
        # At 1024^2 the 1024-VPL brute-force gather costs about half a minute a run; its ratios are
        # measured at 256^2 and 512^2, where isr's lead over it is smallest.
        missing = {(label, "rsm 1024 VPLs") for label in builds} if size >= 1024 else set()
        counts, commands = {}, {}
        for _ in range(reps):
            for label, bounce in builds.items():
                for name, (technique, settings) in SIDES.items():
                    if (label, name) in missing:
                        continue
                    try:
                        r, cmd = render(bounce, SCENE, technique, size, frames, settings)
                    except subprocess.CalledProcessError as e:
                        if label == "after":
                            raise
                        # A side the before build cannot run (a setting it did not have): left out.
                        print(f"{label} {name}: {e.stderr.decode().strip()}", file=sys.stderr)
                        missing.add((label, name))
                        continue
                    times[(label, name)].append(frame_ms(r))
                    counts[(label, name)] = {c: counter_mean(r, c) for c in COUNTERS
                                             if any(c in f["counters"] for f in later(r))}
                    commands[(label, name)] = cmd
        for label in builds:
            sides = {}
            for name in SIDES:
                if (label, name) in missing:
                    continue
                s = summary(times[(label, name)])
                sides[name] = {"frameMs": s, "fps": 1000.0 / s["median"], "counts": counts[(label, name)],
                               "command": commands[(label, name)]}
            ratios = {}
            for key, (a, b) in RATIOS.items():
                # A before build without the points side ran the thesis's points as its default side.
                a = FALLBACK.get(a, a) if (label, a) in missing and label != "after" else a
                if (label, a) in missing or (label, b) in missing:
                    continue
                ratios[key] = summary(times[(label, a)][i] / times[(label, b)][i] for i in range(reps))
            out[label][str(size)] = {"frames": frames, "sides": sides, "ratios": ratios}
    return out


def passes(bounce, size):
    out = {}
    for name, (technique, settings) in SIDES.items():
        r, cmd = render(bounce, SCENE, technique, size, 6, {**settings, "renderer.timing": "finish"})
        scopes = sorted({k for f in later(r) for k in f["gpu_ms"]})
        out[name] = {"command": cmd, "passMs": {k: statistics.median(f["gpu_ms"].get(k, 0.0) for f in later(r)) for k in scopes}}
    return out


def main():
    args = sys.argv[1:]
    reps = option(args, "--reps", 3)
    sizes = [int(s) for s in option(args, "--sizes", "256,512,1024", str).split(",")]
    before = option(args, "--before", "", str)
    before_commit = option(args, "--before-commit", "", str)  # when BOUNCE_BEFORE is not inside a checkout
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    command = f"bench/interactive/run.py --reps {reps} --sizes {','.join(map(str, sizes))}"
    if before:
        command += " --before BEFORE"
    rec = new_record("interactive", command, bounce)
    rec.update({"scene": SCENE, "reps": reps, "sizes": sizes, "timing": "queries (frame = run record cpu_ms)"})
    builds = {"after": bounce}
    if before:
        b = os.path.abspath(before)
        rec["beforeCommit"] = before_commit or subprocess.run(["git", "-C", os.path.dirname(b), "rev-parse", "--short", "HEAD"],
                                                              capture_output=True, text=True).stdout.strip()
        builds["before"] = b
    rec.update(measure(builds, sizes, reps))
    rec["passes256"] = passes(bounce, 256) if 256 in sizes else {}
    print(write_record(rec))


if __name__ == "__main__":
    main()
