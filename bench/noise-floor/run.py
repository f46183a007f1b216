#!/usr/bin/env python3
"""How many of the demo study's comparisons are inside the reference-noise floor, per reference spp
(docs/studies.md "A complete example", docs/metrics.md "Reference noise floor").

Runs the demo study's still comparisons (scripts/demo-study.json without its temporal part) with the
references at each --spp, then the demo study itself as `make demo` runs it, and records per run: the
sweep's wall time, the references' tracing time, and per scene how many comparisons have relMSE,
relRMS or LDR-FLIP within 2x of the floor (the report's grey points), with their names.

usage: bench/noise-floor/run.py BOUNCE [--spp 64,256,1024] [--jobs 2] [--name noise-floor]
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from record import ROOT, new_record, write_record  # noqa: E402

SHOWN = ("relMse", "relRms", "flipLdr")  # the metrics the report's plots and table flag


def sweep(bounce, study, out, jobs):
    start = time.perf_counter()
    r = subprocess.run([bounce, "sweep", study, "--out", out, "--jobs", str(jobs)], capture_output=True, text=True)
    wall = time.perf_counter() - start
    if r.returncode != 0:
        sys.exit(f"sweep failed: {r.stderr.strip()}")
    return wall


def summarize(out):
    references = [json.load(open(f)) for f in glob.glob(os.path.join(out, "reference/*/*/*/record.json"))]
    per_scene, inside, closest = {}, [], {}
    for f in sorted(glob.glob(os.path.join(out, "compare/*/*/*/record.json"))):
        c = json.load(open(f))
        if c.get("status") != "ok":
            continue
        s = per_scene.setdefault(c["scene"], {"compares": 0, "inside": 0, **{m: 0 for m in SHOWN}})
        s["compares"] += 1
        flags = {m: bool(c["insideFloor"].get(m)) for m in SHOWN}
        # The margin: each metric's smallest error / floor over the scene's comparisons (2 = the flag's edge).
        for m in SHOWN:
            value, floor = c["metrics"].get(m), c["floor"].get(m)
            if value is not None and floor:
                best = closest.setdefault(c["scene"], {}).get(m)
                if best is None or value / floor < best["ratio"]:
                    closest[c["scene"]][m] = {"ratio": round(value / floor, 3), "job": c["job"], "value": value, "floor": floor}
        for m in SHOWN:
            s[m] += flags[m]
        if any(flags.values()):
            s["inside"] += 1
            inside.append({"job": c["job"], **{m: [c["metrics"].get(m), c["floor"].get(m)] for m in SHOWN},
                           "flags": [m for m in SHOWN if flags[m]]})
    return {
        "references": len(references),
        "referenceSeconds": round(sum(r["result"]["renderSeconds"] + r["result"]["buildSeconds"] for r in references), 2),
        # The still references' mean per-pixel relative standard error (docs/reference.md).
        "referenceNoisePerPixel": {r["job"]: round(r["noise"]["meanPixelRelativeStdError"], 4)
                                   for r in references if r["job"].endswith("f0000")},
        "perScene": per_scene,
        "insideTotal": sum(s["inside"] for s in per_scene.values()),
        "compares": sum(s["compares"] for s in per_scene.values()),
        "inside": inside,
        "closest": closest,
    }


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("bounce")
    p.add_argument("--spp", default="64,256,1024")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--name", default="noise-floor")
    a = p.parse_args()
    demo_path = os.path.join(ROOT, "scripts/demo-study.json")
    demo = json.load(open(demo_path))
    record = new_record(a.name, " ".join(sys.argv), a.bounce)
    record["study"] = "scripts/demo-study.json"
    record["stillOnly"] = []
    work = tempfile.mkdtemp(prefix="bounce-noise-floor-")
    try:
        previous = None
        for spp in [int(x) for x in a.spp.split(",")]:
            study = dict(demo, name=f"floor{spp}", reference=dict(demo["reference"], spp=spp))
            study.pop("temporal", None)
            path = os.path.join(work, f"floor{spp}.json")
            json.dump(study, open(path, "w"))
            out = os.path.join(work, f"out{spp}")
            reused = previous is not None
            if previous:
                # The renders do not depend on the references' spp (their records' spec is the same):
                # the sweep finds them finished and only traces and compares again.
                shutil.copytree(os.path.join(previous, "render"), os.path.join(out, "render"))
            previous = out
            wall = sweep(a.bounce, path, out, a.jobs)
            entry = {"spp": spp, "sweepSeconds": round(wall, 1), "rendersReused": reused, **summarize(out)}
            record["stillOnly"].append(entry)
            print(f"{spp} spp: {entry['insideTotal']}/{entry['compares']} inside, sweep {wall:.1f} s, "
                  f"references {entry['referenceSeconds']} s", flush=True)
        out = os.path.join(work, "demo")
        wall = sweep(a.bounce, demo_path, out, a.jobs)
        record["demo"] = {"spp": demo["reference"]["spp"], "temporal": demo.get("temporal"), "sweepSeconds": round(wall, 1),
                          **summarize(out)}
        print(f"demo study ({demo['reference']['spp']} spp): {record['demo']['insideTotal']}/{record['demo']['compares']} "
              f"inside, sweep {wall:.1f} s", flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(write_record(record))


if __name__ == "__main__":
    main()
