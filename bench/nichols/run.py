#!/usr/bin/env python3
"""The multiresolution image-space techniques (Nichols 2010 ch. 3-4): the thesis's results as ratios,
measured by interleaving the sides (A B A B ...) through `bounce render --stats`.

Usage: bench/nichols/run.py [BOUNCE] [--reps N] [--quick] [--big N] [--mid N] [--small N]
       (defaults: build/src/app/bounce, 5 repetitions, sizes 1024 / 512 / 256; --quick: big 512, 2 repetitions)

Every run renders 2 frames with `renderer.timing=finish` (a glFinish at every pass boundary: each pass's
own wall-clock cost on llvmpipe, which otherwise charges deferred rasterisation to later scopes) and
reports the second (the first compiles shaders). Ratios are formed per repetition and reported as
min / median / max with the repetition count. `cornell-box`, RSM 256^2, 256 VPLs (vplGrid 16) unless named.
  r1        Table 4.1 at 1024^2: multires-splat (geometry-shader refinement + splatting) against isr with
            regular VPLs (stencil set-up + gather): frame ratio (thesis 5-10x) and light-stage ratio,
            (refine + splat) / (stencil set-up + gather) (thesis 18-20x for the light stage; 14.7-18x
            in Table 4.1's refine + splat vs stencil + gather columns).
  gather    speed-ups over the full-resolution rsm gather at 1024^2 on cornell-box-dynamic: isr regular,
            isr clusters, hisr (the thesis: several times faster).
  splat     at 512^2: multires-splat against full-screen rsm-splat and fragment-matched rsm-splat
            (mode=matched, targetFragments = multires-splat's fragments per VPL).
  r2        subsplats per level as a fraction of full fill (counter fillFraction and subsplats/level-k),
            output sizes 32^2 .. 256^2 and 1024^2 (here the indirect buffer is the output size; Table 3.1:
            ~46 / 21 / 10 / 5 % at 32..256 in a 1024^2 window, which bench/nichols-cap/run.py measures with
            the indirectSize cap).
  r3        multires-splat frame time against triangle count (atrium 25K / 100K / 400K) at 256^2
            (Table 3.2: nearly flat at 1024^2 on a GPU).
  r4        multires-splat normalThreshold 0.25 vs 1.4 at 512^2 (Fig. 3.9: ~4x the fps on the Buddha).
  r5        multires-splat edgeNeighbours on vs off at 512^2 (sec. 3.4.2: up to 40 % slower).
The raw record goes to bench/results/nichols-<date>.json; bench/tables.py makes the README table.
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


def one(values):
    values = list(values)
    return sum(values) / len(values)


def interleaved(bounce, sides, reps, size, measure):
    """sides: name -> (scene, technique, settings, params). Returns per-side lists of measure(record)."""
    out = {name: [] for name in sides}
    commands = {}
    for _ in range(reps):
        for name, (scene, technique, settings, params) in sides.items():
            r, cmd = render(bounce, scene, technique, size, FRAMES, {**FINISH, **settings}, params)
            commands[name] = cmd
            out[name].append(measure(r))
    return out, commands


def frame_ms(r):
    return one(pass_ms(r, "frame"))


def ratio(a, b):
    return summary(x / y for x, y in zip(a, b))


def main():
    args = sys.argv[1:]
    quick = "--quick" in args
    args = [a for a in args if a != "--quick"]
    reps = option(args, "--reps", 2 if quick else 5)
    big = option(args, "--big", 512 if quick else 1024)
    mid = option(args, "--mid", 512)
    small = option(args, "--small", 256)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    rec = new_record("nichols", f"bench/nichols/run.py --reps {reps} --big {big} --mid {mid} --small {small}", bounce)
    rec.update({"reps": reps, "frames": FRAMES, "timing": "finish", "big": big})

    # r1: Table 4.1.
    def r1_measure(r):
        return {"frame": frame_ms(r),
                "light": one(pass_ms(r, "multires-splat/refine")) + one(pass_ms(r, "multires-splat/splat"))
                + one(pass_ms(r, "isr/stencil-setup")) + one(pass_ms(r, "isr/gather")),
                "fragments": counter_mean(r, "gatherFragments") or counter_mean(r, "subsplats")}
    runs, cmds = interleaved(bounce, {"multires-splat": ("cornell-box", "multires-splat", dict(THESIS), []),
                                      "isr": ("cornell-box", "isr", {"vplMode": "regular"}, [])}, reps, big, r1_measure)
    ms, isr = runs["multires-splat"], runs["isr"]
    rec["r1"] = {"size": big, "commands": cmds, "runs": runs,
                 "frameRatio": ratio([m["frame"] for m in ms], [i["frame"] for i in isr]),
                 "lightRatio": ratio([m["light"] for m in ms], [i["light"] for i in isr])}
    print("r1", round(rec["r1"]["frameRatio"]["median"], 2), round(rec["r1"]["lightRatio"]["median"], 2), flush=True)

    # gather: speed-ups over the rsm gather.
    sides = {"rsm": ("cornell-box-dynamic", "rsm", {}, []),
             "isr regular": ("cornell-box-dynamic", "isr", {"vplMode": "regular"}, []),
             "isr clusters": ("cornell-box-dynamic", "isr", {}, []),
             "hisr": ("cornell-box-dynamic", "hisr", {}, [])}
    runs, cmds = interleaved(bounce, sides, reps, big, frame_ms)
    rec["gather"] = {"size": big, "commands": cmds, "frameMs": {k: summary(v) for k, v in runs.items()},
                     "speedupOverRsm": {k: ratio(runs["rsm"], v) for k, v in runs.items() if k != "rsm"}}
    print("gather", {k: round(v["median"], 2) for k, v in rec["gather"]["speedupOverRsm"].items()}, flush=True)

    # splat: multires-splat against rsm-splat full and fragment-matched.
    probe, _ = render(bounce, "cornell-box", "multires-splat", mid, FRAMES, {**FINISH, **THESIS})
    per_vpl = counter_mean(probe, "fillFraction") * mid * mid  # multires fragments per VPL
    sides = {"multires-splat": ("cornell-box", "multires-splat", dict(THESIS), []),
             "rsm-splat full": ("cornell-box", "rsm-splat", {"mode": "full"}, []),
             "rsm-splat matched": ("cornell-box", "rsm-splat", {"mode": "matched", "targetFragments": f"{per_vpl:.0f}"}, [])}
    runs, cmds = interleaved(bounce, sides, max(2, reps - 2), mid, frame_ms)
    rec["splat"] = {"size": mid, "fragmentsPerVpl": per_vpl, "commands": cmds,
                    "frameMs": {k: summary(v) for k, v in runs.items()},
                    "multiresSpeedup": {k: ratio(v, runs["multires-splat"]) for k, v in runs.items() if k != "multires-splat"}}
    print("splat", {k: round(v["median"], 2) for k, v in rec["splat"]["multiresSpeedup"].items()}, flush=True)

    # r2: fill fractions (counts: one run per size).
    r2 = {}
    for size in sorted({32, 64, 128, 256, big}):
        r, cmd = render(bounce, "cornell-box", "multires-splat", size, FRAMES, {**FINISH, **THESIS})
        levels = sorted(int(k.split("-")[-1]) for k in r["frames"][-1]["counters"] if k.startswith("subsplats/level-"))
        r2[str(size)] = {"command": cmd, "fillFraction": counter_mean(r, "fillFraction"),
                         "subsplats": counter_mean(r, "subsplats"),
                         "levels": {str(k): counter_mean(r, f"subsplats/level-{k}") for k in levels}}
    rec["r2"] = r2
    print("r2", {k: round(100 * v["fillFraction"], 1) for k, v in r2.items()}, flush=True)

    # r3: triangles.
    sides = {t: ("atrium", "multires-splat", dict(THESIS), [f"triangles={t}"]) for t in ["25000", "100000", "400000"]}
    runs, cmds = interleaved(bounce, sides, max(2, reps - 2), small, lambda r: {"frame": frame_ms(r), "triangles": counter_mean(r, "triangles")})
    rec["r3"] = {"size": small, "commands": cmds,
                 "cases": {k: {"triangles": v[0]["triangles"], "frameMs": summary(x["frame"] for x in v)} for k, v in runs.items()}}
    print("r3", {k: round(v["frameMs"]["median"]) for k, v in rec["r3"]["cases"].items()}, flush=True)

    # r4, r5: thresholds and the edge-neighbour test.
    for key, sides in [("r4", {"0.25": ("cornell-box", "multires-splat", {**THESIS, "normalThreshold": "0.25"}, []),
                               "1.4": ("cornell-box", "multires-splat", {**THESIS, "normalThreshold": "1.4"}, [])}),
                       ("r5", {"off": ("cornell-box", "multires-splat", {**THESIS, "edgeNeighbours": "false"}, []),
                               "on": ("cornell-box", "multires-splat", {**THESIS, "edgeNeighbours": "true"}, [])})]:
        runs, cmds = interleaved(bounce, sides, max(2, reps - 2), mid,
                                 lambda r: {"frame": frame_ms(r), "subsplats": counter_mean(r, "subsplats")})
        a, b = list(sides)
        rec[key] = {"size": mid, "commands": cmds,
                    "frameMs": {k: summary(x["frame"] for x in v) for k, v in runs.items()},
                    "subsplats": {k: v[0]["subsplats"] for k, v in runs.items()},
                    "ratio": ratio([x["frame"] for x in runs[a]], [x["frame"] for x in runs[b]])}
        print(key, round(rec[key]["ratio"]["median"], 2), flush=True)
    print(write_record(rec))


if __name__ == "__main__":
    main()
