#!/usr/bin/env python3
"""A technique's frame time on the courtyard scene (issue 30), two binaries interleaved A B A B.

Each run renders `--frames N` at 256^2 with renderer.timing=finish (each pass's own wall time) and
is timed with getrusage: the frame's CPU seconds (all threads; llvmpipe is the CPU) is
(CPU of an N-frame run - CPU of a 1-frame run) / (N - 1), which a loaded machine inflates far less
than wall time. Per pass: the wall ms of the last frame (renderer.timing=finish). Also checks that the
two binaries' images are byte-identical.

  bench/large-scene/ab.py --technique photon-splat --a /tmp/bounce-before --b build/src/app/bounce --reps 3 --name photon-splat-perf
  (--set-a / --set-b: settings for one side's runs, e.g. one binary with two values of a setting)
"""
import argparse
import filecmp
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import record  # noqa: E402

COUNTERS = {"photon-splat": ["clusterDraws", "cullMs", "traceMs", "tracedRays", "bundles"],
            "area-light": ["raysCast", "raysReused", "raysCulled", "gatherFragments", "renderedFraction/level-0"],
            "isr": ["vpls"]}


def run(binary, technique, light, frames, out, sets=()):
    stats = out + ".json"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([binary, "render", "--scene", "courtyard", "--scene-param", f"light={light}", "--technique", technique,
                    "--size", "256x256", "--frames", str(frames), "--out", out + ".exr", "--stats", stats,
                    "--set", "renderer.timing=finish"] + [a for kv in sets for a in ("--set", kv)], check=True,
                   capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with open(stats) as f:
        last = json.load(f)["frames"][-1]
    return cpu, last


def summary(values):
    return {"min": min(values), "median": statistics.median(values), "max": max(values), "n": len(values)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--technique", default="photon-splat")
    ap.add_argument("--a", required=True, help="binary before")
    ap.add_argument("--b", required=True, help="binary after")
    ap.add_argument("--lights", default="sun,sky")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--name", required=True)
    ap.add_argument("--note", default="")
    ap.add_argument("--set-a", action="append", default=[], help="setting name=value for binary a's runs (repeatable)")
    ap.add_argument("--set-b", action="append", default=[], help="setting name=value for binary b's runs (repeatable)")
    args = ap.parse_args()
    rec = record.new_record(args.name, " ".join(sys.argv), args.b)
    rec["note"] = args.note
    rec["binaries"] = {"a": args.a, "b": args.b}
    rec["settings"] = {"a": args.set_a, "b": args.set_b}
    rec["loadavg_start"] = os.getloadavg()
    tmp = tempfile.mkdtemp(prefix="ps-perf-")
    results = {}
    for light in args.lights.split(","):
        samples = {"a": [], "b": []}
        identical = True
        for rep in range(args.reps):
            for tag in ("a", "b"):
                binary = args.a if tag == "a" else args.b
                sets = args.set_a if tag == "a" else args.set_b
                base = os.path.join(tmp, f"{light}-{tag}-{rep}")
                cpu1, _ = run(binary, args.technique, light, 1, base + "-1", sets)
                cpuN, last = run(binary, args.technique, light, args.frames, base + "-n", sets)
                s = {"frameCpuS": (cpuN - cpu1) / (args.frames - 1)}
                s.update({p + ".wallMs": ms for p, ms in last["gpu_ms"].items() if p.startswith(args.technique)})
                s.update({c: last["counters"].get(c, 0.0) for c in COUNTERS.get(args.technique, [])})
                samples[tag].append(s)
                print(light, tag, rep, json.dumps(s), flush=True)
            identical = identical and filecmp.cmp(os.path.join(tmp, f"{light}-a-{rep}-n.exr"), os.path.join(tmp, f"{light}-b-{rep}-n.exr"), shallow=False)
        # b's last image against a's (the same frame): how far apart the two are when not byte-identical.
        cmp = json.loads(subprocess.run([args.b, "compare", "--json", os.path.join(tmp, f"{light}-b-0-n.exr"),
                                         os.path.join(tmp, f"{light}-a-0-n.exr")], check=True, capture_output=True,
                                        text=True).stdout)["metrics"]
        results[light] = {"imagesByteIdentical": identical, "bAgainstA": {k: cmp[k] for k in ("relMse", "energy", "flipLdr")},
                          "raw": samples,
                          **{tag: {k: summary([s[k] for s in samples[tag]]) for k in samples[tag][0]} for tag in ("a", "b")}}
    rec["results"] = results
    rec["loadavg_end"] = os.getloadavg()
    print(record.write_record(rec))


if __name__ == "__main__":
    main()
