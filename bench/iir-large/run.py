#!/usr/bin/env python3
"""iir on the large built-in scenes (issue 30): the paper's n x m box filter (`filter=box`, the code
before the fix) against the tent filter (`filter=tent`, the default since) on `courtyard` (sun) and
`atrium`, each after FRAMES frames at its other defaults, against iir's reference scope (one diffuse
bounce, indirect only) at the last frame: energy (image mean / reference mean), relMSE, LDR-FLIP, and
the run record's median frame and filter-pass times. Writes bench/results/iir-large-<date>.json.

Usage: bench/iir-large/run.py [BOUNCE] [--size 256] [--spp 1024] [--frames 60] [--scenes courtyard,atrium]"""
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from record import ROOT, new_record, write_record  # noqa: E402

SCOPE = ["--bounces", "1", "--indirect-only", "--diffuse-only"]  # `bounce list`: iir's reference scope
FILTERS = ["box", "tent"]


def option(args, name, default, kind=int):
    return kind(args[args.index(name) + 1]) if name in args else default


def rel(cmd):
    return " ".join(os.path.relpath(c, ROOT) if os.path.isabs(c) else c for c in cmd)


def main():
    args = sys.argv[1:]
    size = option(args, "--size", 256)
    spp = option(args, "--spp", 1024)
    frames = option(args, "--frames", 60)
    scenes = option(args, "--scenes", "courtyard,atrium", str).split(",")
    bounce = os.path.abspath(args[0] if args and not args[0].startswith("--") else os.path.join(ROOT, "build/src/app/bounce"))
    record = new_record("iir-large", " ".join(["bench/iir-large/run.py"] + sys.argv[1:]), bounce)
    record.update({"size": size, "spp": spp, "frames": frames, "scope": " ".join(SCOPE), "results": {}})
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            ref = os.path.join(tmp, f"ref-{scene}.exr")
            cmd = [bounce, "reference", "--scene", scene, "--size", f"{size}x{size}", "--spp", str(spp),
                   "--frame", str(frames - 1), "--out", ref] + SCOPE
            p = subprocess.run(cmd, capture_output=True, text=True, check=True)
            noise = re.search(r"noise ([\d.]+)% per pixel, ([\d.]+)% image mean", p.stdout + p.stderr)
            entry = {"reference": rel(cmd), "referenceNoise": float(noise.group(2)) / 100 if noise else None}
            for kernel in FILTERS:
                out, stats = os.path.join(tmp, f"{scene}-{kernel}.exr"), os.path.join(tmp, f"{scene}-{kernel}.json")
                cmd = [bounce, "render", "--scene", scene, "--technique", "iir", "--size", f"{size}x{size}", "--frames",
                       str(frames), "--component", "indirect", "--set", f"filter={kernel}", "--out", out, "--stats", stats]
                subprocess.run(cmd, capture_output=True, text=True, check=True)
                metrics = json.loads(subprocess.run([bounce, "compare", "--json", out, ref], capture_output=True, text=True,
                                                    check=True).stdout)["metrics"]
                run = json.load(open(stats))
                last = run["frames"][-1]["counters"]
                entry[kernel] = {"command": rel(cmd), "energy": metrics["energy"], "relMse": metrics["relMse"],
                                 "flipLdr": metrics["flipLdr"], "medianFrameMs": run["median_ms"]["frame"],
                                 "medianFilterMs": run["median_ms"].get("iir/filter"), "vpls": last.get("vpls"),
                                 "vplMisses": last.get("vplMisses"), "derived": run.get("derived", {})}
                print(f"{scene:10s} filter={kernel:4s} energy {metrics['energy']:.3f} relMSE {metrics['relMse']:.4f} "
                      f"FLIP {metrics['flipLdr']:.3f} frame {run['median_ms']['frame']:.0f} ms "
                      f"(filter {run['median_ms'].get('iir/filter', 0):.0f} ms)", flush=True)
            record["results"][scene] = entry
    print(write_record(record))


if __name__ == "__main__":
    main()
