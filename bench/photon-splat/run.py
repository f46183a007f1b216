#!/usr/bin/env python3
"""Benchmarks of `photon-splat` against `bounce photon-map` (seed 004, results M1-M5), one raw record.

Usage: bench/photon-splat/run.py [BOUNCE] [--quick]   (BOUNCE defaults to build/src/app/bounce)

Quality is measured against `bounce reference --bounces 1 --indirect-only` (the light one bounce of
photons carries) at 128^2 with relMSE, LDR-FLIP and the document's RMS (8-bit display values, RMS per
channel summed: `rmsSum8`), and against the high-quality photon map. Times: run-record medians of 3
frames for photon-splat (frame 0 compiles shaders on llvmpipe), the photon map's own render seconds;
A and B sides interleaved. Writes bench/results/photon-splat-<date>.json; bench/tables.py makes the
README table.
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from record import new_record, write_record  # noqa: E402
SIZE = "128x128"


def compare(bounce, test, ref):
    out = subprocess.run([bounce, "compare", test, ref, "--json"], check=True, capture_output=True, text=True).stdout
    m = json.loads(out)["metrics"]
    return {"relMse": m["relMse"], "flipLdr": m["flipLdr"], "rmsSum8": m["rmsSum8"]}


def splat(bounce, tmp, scene, settings, frames=3):
    out, stats = os.path.join(tmp, "splat.exr"), os.path.join(tmp, "splat.json")
    cmd = [bounce, "render", "--scene", scene, "--technique", "photon-splat", "--size", SIZE, "--frames", str(frames),
           "--component", "indirect", "--out", out, "--stats", stats]
    for k, v in settings.items():
        cmd += ["--set", f"{k}={v}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(stats) as f:
        rec = json.load(f)
    c = rec["frames"][-1]["counters"]
    # CPU stages (injection, bundle rays) are counters in ms; GPU stages are timers.
    ms = rec["median_ms"]
    return out, {"frame_ms": ms["frame"], "depth_maps_ms": ms.get("photon-splat/depth-maps", 0.0),
                 "splat_ms": ms.get("photon-splat/splat", 0.0), "cpu_ms": c.get("injectMs", 0.0) + c.get("bundleMs", 0.0),
                 "bundles": c.get("bundles", 0), "photonBytes": c.get("photonBytes", 0), "gridBytes": c.get("gridBytes", 0),
                 "command": " ".join(cmd[1:])}


def photon_map(bounce, tmp, scene, photons, k):
    out, stats = os.path.join(tmp, "pm.exr"), os.path.join(tmp, "pm.json")
    cmd = [bounce, "photon-map", "--scene", scene, "--size", SIZE, "--photons", str(photons), "--k", str(k), "--bounces", "1",
           "--indirect-only", "--out", out, "--stats", stats]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(stats) as f:
        rec = json.load(f)
    return out, {"render_ms": 1000.0 * rec["result"]["renderSeconds"], "mapBytes": rec["memory"]["mapBytes"],
                 "bytesPerPhoton": rec["memory"]["bytesPerPhoton"], "command": " ".join(cmd[1:])}


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    record = new_record("photon-splat", " ".join(["bench/photon-splat/run.py"] + sys.argv[1:]), bounce)
    record.update({"size": SIZE, "results": {}})
    reps = 2 if quick else 3
    with tempfile.TemporaryDirectory() as tmp:
        for scene in ["cornell-box", "atrium"] if not quick else ["cornell-box"]:
            ref = os.path.join(tmp, f"{scene}-ref.exr")
            subprocess.run([bounce, "reference", "--scene", scene, "--size", SIZE, "--spp", "1024", "--bounces", "1", "--indirect-only",
                            "--out", ref], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            hq, hqrec = photon_map(bounce, tmp, scene, 1600000 if not quick else 400000, 200)
            hq_keep = os.path.join(tmp, f"{scene}-pm-hq.exr")
            os.replace(hq, hq_keep)
            res = {"reference": f"bounce reference --scene {scene} --size {SIZE} --spp 1024 --bounces 1 --indirect-only",
                   "photonMapHq": {**hqrec, "vsReference": compare(bounce, hq_keep, ref)}}
            # M2: quality levels, splatting (small and 3x larger maps, M3) interleaved with photon mapping.
            levels = [1024, 4096, 16384] if not quick else [1024, 4096]
            pm_levels = [(25000, 25), (100000, 50), (400000, 100)] if not quick else [(25000, 25)]
            # The auto map width is a tenth of the scene diagonal; "large" is three times it.
            splat(bounce, tmp, scene, {"estimate": "flux", "photons": 16}, frames=1)
            with open(os.path.join(tmp, "splat.json")) as f:
                half = json.load(f)["frames"][-1]["counters"]["bundleHalfSize"]
            splat_rows, pm_rows = {}, {}
            for rep in range(reps):
                for n in levels:
                    for size_label, factor in (("small", 1.0), ("large", 3.0)):
                        out, r = splat(bounce, tmp, scene, {"estimate": "flux", "photons": n, "mapSize": f"{2.0 * half * factor:.6f}"})
                        q = compare(bounce, out, ref)
                        q_pm = compare(bounce, out, hq_keep)
                        splat_rows.setdefault(f"{size_label}/{n}", []).append({**r, "vsReference": q, "vsPhotonMapHq": q_pm})
                for n, k in pm_levels:
                    out, r = photon_map(bounce, tmp, scene, n, k)
                    pm_rows.setdefault(f"{n}/k{k}", []).append({**r, "vsReference": compare(bounce, out, ref)})
            res["splat"] = splat_rows
            res["photonMap"] = pm_rows
            # M5: 4x4 vs 32x32 depth maps, same photons, interleaved.
            m5 = {}
            for rep in range(reps):
                for r in (4, 32):
                    _, rr = splat(bounce, tmp, scene, {"estimate": "flux", "photons": 4096, "mapResolution": r})
                    m5.setdefault(str(r), []).append(rr)
            res["mapResolution"] = m5
            record["results"][scene] = res
            print(scene, "done", flush=True)
        # M1: memory of the dense stratification grid at 16^3 .. 256^3 (the technique's counter).
        m1 = {}
        for g in (16, 64, 256):
            _, r = splat(bounce, tmp, "cornell-box", {"stratify": "true", "gridSize": g, "photons": 1024}, frames=1)
            m1[str(g)] = r["gridBytes"]
        record["results"]["gridBytes"] = m1
        record["results"]["photonBytesPerPhoton"] = 36
    print("wrote", write_record(record))


if __name__ == "__main__":
    main()
