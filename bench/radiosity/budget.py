#!/usr/bin/env python3
"""The shooting radiosity methods' per-frame shooting budget (frameBudgetMs, issue 30), measured.

Usage: bench/radiosity/budget.py [BOUNCE] [--frames N] [--size S] [--scenes a,b] [--name NAME]

Per scene (default two-rooms, furnished-room; both still):
  converge  radiosity-pr with no budget at all (frameBudgetMs=0, maxIterations=1000000), one frame:
            the shooting quads and shooters to convergence and what one frame holding all of them costs;
  before    radiosity-pr, -incremental, -cross with the budget off (frameBudgetMs=0, maxIterations 400,
            the defaults before the budget), 2 frames: the first frame's cost;
  after     the three at their defaults (frameBudgetMs on), N frames: per-frame ms, iterations per frame,
            the frame they converge in (or, if not within N, the frames it takes at the measured rate:
            the converge run's shooters / the mean shooters per frame, marked as estimated).
Still scenes shoot the same sequence of quads whatever the frames' budget (a still frame continues the
last one's shooting), so the converge run's count holds for every budget. Frame ms = the render's
per-frame CPU wall time (cpu_ms: up to the glFinish that ends the frame), the one a user waits for.
The raw record goes to bench/results/<name>-<date>.json (bench/record.py's envelope).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

TECHNIQUES = ("radiosity-pr", "radiosity-incremental", "radiosity-cross")


def render(bounce, scene, technique, size, frames, settings, work):
    out, stats = os.path.join(work, "o.exr"), os.path.join(work, "run.json")
    cmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", f"{size}x{size}", "--frames", str(frames),
           "--out", out, "--stats", stats]
    for k, v in settings.items():
        cmd += ["--set", f"{k}={v}"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"{rel(cmd)}: {p.stderr.strip().splitlines()[-1]}")
    with open(stats) as f:
        rec = json.load(f)
    per = [{"frame": fr["frame"], "cpuMs": round(fr["cpu_ms"], 1), "iterations": int(fr["counters"]["iterations"]),
            "shooters": int(fr["counters"]["shooters"]),
            "hemicubes": int(fr["counters"]["hemicubes"]), "converged": int(fr["counters"]["converged"]),
            "budgetHit": int(fr["counters"].get("budgetHit", 0))} for fr in rec["frames"]]
    return {"command": rel(cmd), "frames": per, "firstFrameMs": rec.get("first_frame_ms", {}),
            "medianMsExcludingFirst": rec.get("median_ms_excluding_first", {}), "elements": rec["frames"][0]["counters"]["elements"]}


def summarise(run, shootersToConverge=None):
    frames = run["frames"]
    rest = [f["cpuMs"] for f in frames[1:]]
    conv = next((f["frame"] for f in frames if f["converged"]), None)
    shot = sum(f["iterations"] for f in frames)
    shooters = sum(f["shooters"] for f in frames)
    s = {"firstFrameMs": frames[0]["cpuMs"], "iterationsFirstFrame": frames[0]["iterations"], "iterationsShot": shot,
         "shootersShot": shooters, "convergedFrame": conv}
    if rest:
        s.update({"medianMsExcludingFirst": statistics.median(rest), "maxMsExcludingFirst": max(rest),
                  "meanShootersPerFrame": round(shooters / len(frames), 2)})
    # Not converged within the frames: the frames the rest takes at this run's shooters per frame (the
    # cost of a batch of shooters is about the same all along: one reconstruction pass over every element).
    if conv is None and shootersToConverge and shooters:
        s["estimatedFramesToConverge"] = round(shootersToConverge / (shooters / len(frames)))
    return s


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bounce", nargs="?", default=os.path.join(ROOT, "build/src/app/bounce"))
    ap.add_argument("--frames", type=int, default=30)
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--scenes", default="two-rooms,furnished-room")
    ap.add_argument("--name", default="radiosity-budget")
    ap.add_argument("--before", default=",".join(TECHNIQUES),
                    help="techniques run with the budget off (on a still scene they shoot the same quads as radiosity-pr)")
    args = ap.parse_args()
    record = new_record(args.name, " ".join(["bench/radiosity/budget.py"] + sys.argv[1:]), args.bounce)
    record.update({"size": args.size, "frames": args.frames, "results": {}})
    with tempfile.TemporaryDirectory() as work:
        for scene in args.scenes.split(","):
            res = record["results"][scene] = {}
            run = render(args.bounce, scene, "radiosity-pr", args.size, 1, {"frameBudgetMs": 0, "maxIterations": 1000000}, work)
            res["converge"] = {"run": run, "summary": summarise(run)}
            shooters = run["frames"][0]["shooters"]
            print(scene, "converge", res["converge"]["summary"], flush=True)
            write_record(record)
            for t in TECHNIQUES:
                if t in args.before.split(","):
                    run = render(args.bounce, scene, t, args.size, 2, {"frameBudgetMs": 0}, work)
                    res.setdefault("before", {})[t] = {"run": run, "summary": summarise(run, shooters)}
                    print(scene, t, "before", res["before"][t]["summary"], flush=True)
                run = render(args.bounce, scene, t, args.size, args.frames, {}, work)
                res.setdefault("after", {})[t] = {"run": run, "summary": summarise(run, shooters)}
                print(scene, t, "after", res["after"][t]["summary"], flush=True)
                write_record(record)  # partial results survive an interrupted run
    print(write_record(record))


if __name__ == "__main__":
    main()
