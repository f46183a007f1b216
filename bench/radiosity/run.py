#!/usr/bin/env python3
"""Benchmarks of the hemicube radiosity methods (van de Hoef 2013) through the CLI's run records.

Usage: bench/radiosity/run.py [BOUNCE] [--quick] [--reps N]   (BOUNCE defaults to build/src/app/bounce)

R2  speed order gather >> PR > incremental > cross in the thesis's four scenes, and cross over PR
    (thesis Table 5.2a: 16.6x in the many-bounce Indirect light scene); runs interleaved
    (gather PR incremental cross, gather PR ...), --reps repetitions.
R1  cross redistribution's frame time and hemicube count as the static element count grows 4x and
    16x with the moving patches fixed (incremental radiosity beside it, for contrast).
A   cross redistribution against PR's restart at frames 12, 100, 200 (error growth over frames) and
    the work of its progressive propagation.
R8  cross redistribution's per-patch cost: the GPU timer scopes radiosity.hemicubes,
    radiosity.crossProjection, radiosity.reconstruct and radiosity.integrate over the patches.
    Hemicubes per second of the gather method (indicative on llvmpipe).
Q   Table 5.1: NRMSE (display values' RMS difference / the reference's display range), relMSE and HDR-FLIP of every method at frame 12
    (the box turned; incremental and cross after redistributing every frame since frame 0) against
    the path tracer (every bounce, Lambert only) and against radiosity-gather at high settings (the
    thesis's metric: its Table 5.1 compares with a high-quality gather). Beside the defaults, variants
    of single settings (VARIANTS): cross without the progressive propagation after its redistributions,
    with form-factor-weighted cross-projection rays, without REPROJECT (R7); gather without the random
    hemicube rotation.

Frame times: a frame's GPU time of the technique's scope, the median over the frames after the
first (the first compiles shaders on llvmpipe and, for incremental and cross, holds the initial
progressive solution; the thesis discards 1-3 warm-up frames too). The raw record goes to
bench/results/radiosity-<date>.json; bench/tables.py makes the README table from it.
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
compare = functools.partial(compare_metrics, keys=("nrmse", "relMse", "flipHdr"))

METHODS = ["radiosity-gather", "radiosity-pr", "radiosity-incremental", "radiosity-cross"]
# The thesis's four scenes (sec. 5.1) as bounce built-ins; "low quality" is the large-light Cornell
# box with coarse elements. Settings apply to every method unless keyed by method.
SCENES = {
    "indirect-light": {"scene": "indirect-light", "params": [], "settings": {}},
    "cornell-large": {"scene": "cornell-box-rotating", "params": ["light=large"], "settings": {"elementSize": "0.05"}},
    "cornell-small": {"scene": "cornell-box-rotating", "params": ["light=small"], "settings": {"elementSize": "0.05"}},
    "low-quality": {"scene": "cornell-box-rotating", "params": ["light=large"],
                    "settings": {"elementSize": "0.1", "hemicubeSize": "32",
                                 "radiosity-cross.dynamicElementSize": "0.2"}},
}
# Thesis Table 5.2a (GTX 670, ms) and Table 5.1 (NRMSE), same scene order.
THESIS_MS = {"radiosity-gather": [4757, 2437, 2440, 150], "radiosity-pr": [265, 116, 87, 49],
             "radiosity-incremental": [52, 108, 70, 14], "radiosity-cross": [16, 24, 25, 7]}
THESIS_NRMSE = {"radiosity-gather": [0.0522469, 0.00225834, 0.0028034, 0.0110786],
                "radiosity-pr": [0.0631117, 0.00675699, 0.0098088, 0.0149107],
                "radiosity-incremental": [0.0472801, 0.00741281, 0.0106912, 0.0197874],
                "radiosity-cross": [0.0579452, 0.00694691, 0.0102216, 0.0147345]}


# Q's variants: (label, method, settings), each rendered like its method's default at frame 12.
VARIANTS = [("radiosity-cross propagate=false", "radiosity-cross", {"propagate": "false"}),
            ("radiosity-cross crossWeights=formFactor", "radiosity-cross", {"crossWeights": "formFactor"}),
            ("radiosity-cross reprojection=false", "radiosity-cross", {"reprojection": "false"}),
            ("radiosity-gather randomRotation=false", "radiosity-gather", {"randomRotation": "false"})]


def settings_for(case, method):
    # The shooting methods without their time budget per frame (bounce's, radiosity.md): these runs
    # measure a frame's whole work against the thesis's, and a time budget would cut it at a
    # host-dependent batch.
    out = {} if method == "radiosity-gather" else {"frameBudgetMs": "0"}
    for k, v in case["settings"].items():
        if "." in k:
            owner, name = k.split(".", 1)
            if owner == method:
                out[name] = v
        else:
            out[k] = v
    return out


def render(bounce, case, method, frames, size, extra=None, out_exr=None, start=0):
    with tempfile.TemporaryDirectory() as tmp:
        out = out_exr or os.path.join(tmp, "o.exr")
        stats = os.path.join(tmp, "run.json")
        cmd = [bounce, "render", "--scene", case["scene"], "--technique", method, "--size", f"{size}x{size}",
               "--frames", str(frames), "--start-frame", str(start), "--out", out, "--stats", stats]
        for p in case["params"]:
            cmd += ["--scene-param", p]
        for k, v in {**settings_for(case, method), **(extra or {})}.items():
            cmd += ["--set", f"{k}={v}"]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        with open(stats) as f:
            return json.load(f), rel(cmd)


def frame_values(rec, key, skip=1):
    frames = rec["frames"][skip:] if len(rec["frames"]) > skip else rec["frames"]
    return [f["gpu_ms"].get(key, 0.0) for f in frames]


def counter(rec, name, skip=1):
    frames = rec["frames"][skip:] if len(rec["frames"]) > skip else rec["frames"]
    return statistics.median(f["counters"].get(name, 0.0) for f in frames)


def main():
    args = [a for a in sys.argv[1:]]
    quick = "--quick" in args
    reps = 2
    if "--reps" in args:
        reps = int(args[args.index("--reps") + 1])
        del args[args.index("--reps"):args.index("--reps") + 2]
    args = [a for a in args if a != "--quick"]
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    size = 64 if quick else 128
    frames = {"radiosity-gather": 2, "radiosity-pr": 3, "radiosity-incremental": 4, "radiosity-cross": 4}
    rec = new_record("radiosity", "bench/radiosity/run.py" + (" --quick" if quick else "") + f" --reps {reps}", bounce)
    rec["size"] = size
    rec["reps"] = reps
    rec["thesisMs"] = THESIS_MS
    rec["thesisNrmse"] = THESIS_NRMSE
    scenes = ["cornell-large", "low-quality"] if quick else list(SCENES)

    # R2 (and R8 from the same runs).
    speed = {}
    for name in scenes:
        case = SCENES[name]
        runs = {m: [] for m in METHODS}
        cmds = {}
        for _ in range(reps):
            for m in METHODS:
                r, c = render(bounce, case, m, frames[m], size)
                runs[m].append(r)
                cmds[m] = c
        entry = {}
        for m in METHODS:
            ms = [v for r in runs[m] for v in frame_values(r, m)]
            entry[m] = {"frameMs": summary(ms), "command": cmds[m],
                        "hemicubes": statistics.median(counter(r, "hemicubes") for r in runs[m]),
                        "redistributionHemicubes": statistics.median(counter(r, "redistributionHemicubes") for r in runs[m]),
                        "iterations": statistics.median(counter(r, "iterations") for r in runs[m]),
                        "shooters": statistics.median(counter(r, "shooters") for r in runs[m]),
                        "elements": runs[m][0]["frames"][0]["counters"]["elements"],
                        "movingElements": runs[m][0]["frames"][0]["counters"].get("movingElements", 0)}
            scopes = {}
            for scope in ["radiosity.hemicubes", "radiosity.crossProjection", "radiosity.reconstruct", "radiosity.integrate",
                          "radiosity.select", "radiosity.display"]:
                vals = [v for r in runs[m] for v in frame_values(r, f"{m}/radiosity.solve/{scope}" if scope != "radiosity.display" else f"{m}/{scope}")]
                scopes[scope] = statistics.median(vals) if vals else 0.0
            entry[m]["scopesMs"] = scopes
        pr = statistics.median(v for r in runs["radiosity-pr"] for v in frame_values(r, "radiosity-pr"))
        cross = statistics.median(v for r in runs["radiosity-cross"] for v in frame_values(r, "radiosity-cross"))
        entry["crossOverPr"] = pr / cross if cross > 0 else None
        # Per-rep ratios (the interleaved pairs), for the spread behind the median.
        entry["crossOverPrPerRep"] = [statistics.median(frame_values(a, "radiosity-pr")) / statistics.median(frame_values(b, "radiosity-cross"))
                                      for a, b in zip(runs["radiosity-pr"], runs["radiosity-cross"])]
        c = entry["radiosity-cross"]
        patches = c["shooters"] or 1
        entry["r8"] = {"patches": patches,
                       "crossProjectionMsPerPatch": c["scopesMs"]["radiosity.crossProjection"] / patches,
                       "hemicubeMsPerPatch": c["scopesMs"]["radiosity.hemicubes"] / patches,
                       "hemicubeMsPerHemicube": c["scopesMs"]["radiosity.hemicubes"] / (c["hemicubes"] or 1)}
        g = entry["radiosity-gather"]
        entry["gatherHemicubesPerSecond"] = g["hemicubes"] / (g["scopesMs"]["radiosity.hemicubes"] / 1000.0) if g["scopesMs"]["radiosity.hemicubes"] else None
        speed[name] = entry
        print(name, {m: round(entry[m]["frameMs"]["median"], 1) for m in METHODS}, "cross/pr", entry["crossOverPr"], flush=True)
    rec["speed"] = speed

    # R1: static elements 1x, 4x, 16x; the moving patches fixed by dynamicElementSize.
    r1 = {}
    sizes = ["0.1", "0.05"] if quick else ["0.1", "0.05", "0.025"]
    case = SCENES["cornell-large"]
    runs = {(m, s): [] for m in ["radiosity-cross", "radiosity-incremental"] for s in sizes}
    cmds = {}
    for _ in range(reps):
        for s in sizes:
            for m in ["radiosity-cross", "radiosity-incremental"]:
                extra = {"elementSize": s}
                if m == "radiosity-incremental":
                    extra["dynamicElementSize"] = "0.15"  # the same moving patches as cross
                r, c = render(bounce, case, m, 4, size, extra)
                runs[(m, s)].append(r)
                cmds[(m, s)] = c
    for (m, s), rs in runs.items():
        r1.setdefault(m, {})[s] = {"frameMs": summary([v for r in rs for v in frame_values(r, m)]),
                                   "hemicubes": statistics.median(counter(r, "hemicubes") for r in rs),
                                   "redistributionHemicubes": statistics.median(counter(r, "redistributionHemicubes") for r in rs),
                                   "staticElements": rs[0]["frames"][0]["counters"]["elements"] - rs[0]["frames"][0]["counters"].get("movingElements", 0),
                                   "command": cmds[(m, s)]}
    rec["r1"] = r1
    print("R1", {m: {s: round(v["frameMs"]["median"], 1) for s, v in d.items()} for m, d in r1.items()}, flush=True)

    # Q: quality at frame 12.
    quality = {}
    with tempfile.TemporaryDirectory() as tmp:
        # A: does cross redistribution's error grow over frames? Its progressive propagation changes the
        # static shot radiosity between redistributions (sec. 4.5.2), so the negation of the old position
        # is exact only up to that change. Cross after redistributing every frame since 0 against PR's
        # restart at the same frame, and the frames' propagation work.
        acc = {}
        case = SCENES["cornell-large"]
        for frame in ([12, 60] if quick else [12, 100, 200]):
            pr_exr, cross_exr = os.path.join(tmp, "acc-pr.exr"), os.path.join(tmp, "acc-cross.exr")
            _, prc = render(bounce, case, "radiosity-pr", 1, size, None, pr_exr, start=frame)
            crec, cc = render(bounce, case, "radiosity-cross", frame + 1, size, None, cross_exr)
            later = crec["frames"][1:]
            acc[str(frame)] = {"prCommand": prc, "crossCommand": cc, "crossVsPr": compare(bounce, cross_exr, pr_exr),
                               "propagationIterationsMedian": statistics.median(f["counters"]["iterations"] for f in later),
                               "propagationIterationsTotal": sum(f["counters"]["iterations"] for f in later),
                               "hemicubesMedian": statistics.median(f["counters"]["hemicubes"] for f in later),
                               "redistributionHemicubesMedian": statistics.median(f["counters"]["redistributionHemicubes"] for f in later)}
            print("A", frame, acc[str(frame)]["crossVsPr"], flush=True)
        rec["accumulation"] = acc
        for name in scenes:
            case = SCENES[name]
            ref = os.path.join(tmp, f"{name}-ref.exr")
            ref2 = os.path.join(tmp, f"{name}-ref2.exr")
            spp = "128" if quick else "512"
            base = [bounce, "reference", "--scene", case["scene"], "--size", f"{size}x{size}", "--spp", spp,
                    "--diffuse-only", "--frame", "12"]
            for p in case["params"]:
                base += ["--scene-param", p]
            refcmd = base + ["--out", ref]
            subprocess.run(refcmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            # A second reference with another seed: the noise floor of the comparison.
            subprocess.run(base + ["--out", ref2, "--seed", "1"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            high = os.path.join(tmp, f"{name}-high.exr")
            hq = {"hemicubeSize": "128", "bounces": "32" if name == "indirect-light" else "16"}
            # Gather and PR restart every frame: frame 12 alone is their frame 12.
            _, hqcmd = render(bounce, case, "radiosity-gather", 1, size, hq, high, start=12)
            entry = {"referenceCommand": rel(refcmd), "referenceNoise": compare(bounce, ref2, ref), "gatherHighCommand": hqcmd,
                     "gatherHighVsReference": compare(bounce, high, ref)}
            for m in METHODS:
                exr = os.path.join(tmp, f"{name}-{m}.exr")
                restarts = m in ("radiosity-gather", "radiosity-pr")
                _, c = render(bounce, case, m, 1 if restarts else 13, size, None, exr, start=12 if restarts else 0)
                entry[m] = {"command": c, "vsReference": compare(bounce, exr, ref), "vsGatherHigh": compare(bounce, exr, high)}
            entry["variants"] = {}
            for label, m, extra in VARIANTS:
                exr = os.path.join(tmp, f"{name}-variant.exr")
                restarts = m in ("radiosity-gather", "radiosity-pr")
                _, c = render(bounce, case, m, 1 if restarts else 13, size, extra, exr, start=12 if restarts else 0)
                entry["variants"][label] = {"command": c, "vsReference": compare(bounce, exr, ref), "vsGatherHigh": compare(bounce, exr, high)}
            pr_high = entry["radiosity-pr"]["vsGatherHigh"]["nrmse"]
            entry["crossOverPrNrmseVsGatherHigh"] = entry["radiosity-cross"]["vsGatherHigh"]["nrmse"] / pr_high if pr_high else None
            entry["crossOverPrNrmseVsReference"] = entry["radiosity-cross"]["vsReference"]["nrmse"] / entry["radiosity-pr"]["vsReference"]["nrmse"]
            quality[name] = entry
            print("Q", name, {m: (round(entry[m]["vsReference"]["nrmse"], 4), round(entry[m]["vsGatherHigh"]["nrmse"], 4)) for m in METHODS},
                  {k: round(v["vsGatherHigh"]["nrmse"], 4) for k, v in entry["variants"].items()}, flush=True)
    rec["quality"] = quality
    print(write_record(rec))


if __name__ == "__main__":
    main()
