#!/usr/bin/env python3
"""Error of `bounce photon-map` against `bounce reference` of the same scope as photons grow.

Usage: bench/photon-map/run.py [BOUNCE]    (BOUNCE defaults to build/src/app/bounce)

For each scene and scope: one reference (`bounce reference`, SPP samples per pixel), then photon maps
with N photons and k neighbours, k doubled when N is quadrupled (so r_k ~ sqrt(k/N) shrinks and the
estimate's noise ~1/k falls too), each compared with `bounce compare --json`. The raw record goes to
bench/results/photon-map-<date>.json with the command, git commit, date (UTC) and machine;
docs/techniques/photon-map.md quotes it.
"""
import datetime
import json
import os
import platform
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SIZE = 128
SPP = 4096
CASES = [
    # scene, bounces, [(photons, k), ...]
    ("cornell-box", "1", [(25_000, 25), (100_000, 50), (400_000, 100), (1_600_000, 200)]),
    ("cornell-box", "unbounded", [(25_000, 25), (100_000, 50), (400_000, 100), (1_600_000, 200)]),
]


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def main():
    bounce = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build/src/app/bounce")
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    now = datetime.datetime.now(datetime.timezone.utc)
    record = {"benchmark": "photon-map", "command": "bench/photon-map/run.py", "commit": commit,
              "date": now.isoformat(timespec="seconds"),
              "machine": f"vm {platform.machine()} {os.cpu_count()} cores, shared with other builds", "results": []}
    with tempfile.TemporaryDirectory() as tmp:
        for scene, bounces, schedule in CASES:
            ref = os.path.join(tmp, "ref.exr")
            ref_stats = os.path.join(tmp, "ref.json")
            ref_cmd = [bounce, "reference", "--scene", scene, "--size", f"{SIZE}x{SIZE}", "--spp", str(SPP),
                       "--bounces", bounces, "--indirect-only", "--seed", "1", "--out", ref, "--stats", ref_stats]
            run(ref_cmd)
            with open(ref_stats) as f:
                ref_rec = json.load(f)
            entry = {"scene": scene, "bounces": bounces, "indirectOnly": True,
                     "reference": {"command": " ".join(ref_cmd[1:]), "renderSeconds": ref_rec["result"]["renderSeconds"],
                                   "meanPixelRelativeStdError": ref_rec["noise"]["meanPixelRelativeStdError"]},
                     "rows": []}
            for photons, k in schedule:
                out = os.path.join(tmp, "pm.exr")
                stats = os.path.join(tmp, "pm.json")
                cmd = [bounce, "photon-map", "--scene", scene, "--size", f"{SIZE}x{SIZE}", "--photons", str(photons),
                       "--k", str(k), "--bounces", bounces, "--indirect-only", "--out", out, "--stats", stats]
                run(cmd)
                with open(stats) as f:
                    rec = json.load(f)
                cmp = subprocess.run([bounce, "compare", out, ref, "--json"], check=True, capture_output=True, text=True)
                m = json.loads(cmp.stdout)["metrics"]
                entry["rows"].append({"command": " ".join(cmd[1:]), "photons": photons, "k": k,
                                      "photonsStored": rec["result"]["photonsStored"],
                                      "mapBytes": rec["memory"]["mapBytes"],
                                      "traceSeconds": rec["result"]["traceSeconds"],
                                      "treeSeconds": rec["result"]["treeSeconds"],
                                      "gatherSeconds": rec["result"]["gatherSeconds"],
                                      "meanGatherRadius": rec["result"]["meanGatherRadius"],
                                      "relMse": m["relMse"], "rmse": m["rmse"], "flipHdr": m["flipHdr"], "ssim": m["ssim"]})
                print(scene, bounces, photons, k, f"relMSE {m['relMse']:.5f}", file=sys.stderr)
            record["results"].append(entry)
    path = os.path.join(ROOT, "bench/results", f"photon-map-{now.date().isoformat()}.json")
    with open(path, "w") as f:
        json.dump(record, f, indent=1)
        f.write("\n")
    print(path)


if __name__ == "__main__":
    main()
