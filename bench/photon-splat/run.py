#!/usr/bin/env python3
"""Benchmarks of `photon-splat` against `bounce photon-map` (seed 004, results M1-M6, Graphs 2-4), one raw record.

Usage: bench/photon-splat/run.py [BOUNCE] [--quick]   (BOUNCE defaults to build/src/app/bounce)

Quality is measured against `bounce reference --bounces 1 --indirect-only` (the light one bounce of
photons carries) at 128^2 with relMSE, energy (image mean / reference mean), LDR-FLIP and the
document's RMS (8-bit display values, RMS per channel summed: `rmsSum8`), and against the
high-quality photon map. Times: run-record medians of 3 frames for photon-splat (frame 0 compiles
shaders on llvmpipe), the photon map's own render seconds; configurations interleaved within each
repetition. Sections:
  splat        Graphs 2/3, M2, M3: photon counts with the default (small) and 3x larger bundles;
               every row also has M6's overlap (bundles per pixel: mean and largest over the pixels
               some bundle reached)
  photonMap    Graph 1, M2: the photon map's quality levels
  stratified   Graph 4: stratification with more photons and more voxels (3x larger bundles: "a
               larger shadow map size" counterbalances the fewer splats, 5.3)
  mapResolution M5: 4^2 vs 32^2 depth maps, same photons
  bias         the kernel's remaining bias: energy over bundle width (seeds averaged, no blur) on
               the analytic furnace and cornell-box
  stepBack     bounce's b = d against the document's small step back (b = h/4)
  memory       M1: photonBytes per photon, gridBytes at 16^3 .. 256^3 (counters: what is allocated)
Writes bench/results/photon-splat-<date>.json; bench/tables.py makes the README table.
"""
import functools
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import compare as compare_metrics  # noqa: E402
from record import new_record, write_record  # noqa: E402

# The metrics of `bounce compare` this record keeps (bench/cli.py compare).
compare = functools.partial(compare_metrics, keys=("relMse", "energy", "flipLdr", "rmsSum8"))
SIZE = "128x128"


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
    # CPU stages (injection, bundle rays, culling or traced depth maps) are counters in ms; GPU stages are timers.
    ms = rec["median_ms"]
    keys = ("bundles", "photonsStored", "photonsStratified", "photonBytes", "gridBytes", "bundleHalfSize", "overlapMean",
            "overlapMax", "overlapPixels", "clusterDraws")
    # The depth maps' cost whichever path makes them: the GPU timer, plus the CPU trace (depthMaps=rays).
    return out, {"frame_ms": ms["frame"], "depth_maps_ms": ms.get("photon-splat/depth-maps", 0.0) + c.get("traceMs", 0.0),
                 "splat_ms": ms.get("photon-splat/splat", 0.0),
                 "cpu_ms": c.get("injectMs", 0.0) + c.get("stratifyMs", 0.0) + c.get("bundleMs", 0.0) + c.get("cullMs", 0.0) + c.get("traceMs", 0.0),
                 **{k: c.get(k, 0) for k in keys}, "command": " ".join(cmd[1:])}


def photon_map(bounce, tmp, scene, photons, k):
    out, stats = os.path.join(tmp, "pm.exr"), os.path.join(tmp, "pm.json")
    cmd = [bounce, "photon-map", "--scene", scene, "--size", SIZE, "--photons", str(photons), "--k", str(k), "--bounces", "1",
           "--indirect-only", "--out", out, "--stats", stats]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(stats) as f:
        rec = json.load(f)
    return out, {"render_ms": 1000.0 * rec["result"]["renderSeconds"], "mapBytes": rec["memory"]["mapBytes"],
                 "bytesPerPhoton": rec["memory"]["bytesPerPhoton"], "command": " ".join(cmd[1:])}


def reference(bounce, tmp, scene):
    ref = os.path.join(tmp, f"{scene}-ref.exr")
    if not os.path.exists(ref):
        subprocess.run([bounce, "reference", "--scene", scene, "--size", SIZE, "--spp", "1024", "--bounces", "1", "--indirect-only",
                        "--out", ref], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return ref


def half_width(bounce, tmp, scene):
    splat(bounce, tmp, scene, {"photons": 16}, frames=1)
    with open(os.path.join(tmp, "splat.json")) as f:
        return json.load(f)["frames"][-1]["counters"]["bundleHalfSize"]


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    record = new_record("photon-splat", " ".join(["bench/photon-splat/run.py"] + sys.argv[1:]), bounce)
    record.update({"size": SIZE, "results": {}})
    reps = 2 if quick else 3
    # Photon counts per scene: the atrium's 3x bundles at 65,536 photons take minutes a frame on llvmpipe.
    levels_of = {"cornell-box": [4096, 16384] if quick else [4096, 16384, 65536], "atrium": [4096, 16384]}
    strat = [(16384, 16), (16384, 32)] if quick else [(16384, 16), (16384, 32), (16384, 64), (65536, 32), (65536, 64)]
    with tempfile.TemporaryDirectory() as tmp:
        for scene in ["cornell-box"] if quick else ["cornell-box", "atrium"]:
            ref = reference(bounce, tmp, scene)
            hq, hqrec = photon_map(bounce, tmp, scene, 1600000 if not quick else 400000, 200)
            hq_keep = os.path.join(tmp, f"{scene}-pm-hq.exr")
            os.replace(hq, hq_keep)
            res = {"reference": f"bounce reference --scene {scene} --size {SIZE} --spp 1024 --bounces 1 --indirect-only",
                   "photonMapHq": {**hqrec, "vsReference": compare(bounce, hq_keep, ref)}}
            pm_levels = [(25000, 25), (100000, 50), (400000, 100)] if not quick else [(25000, 25)]
            half = half_width(bounce, tmp, scene)
            res["bundleHalfSize"] = half
            rows = {"splat": {}, "photonMap": {}, "stratified": {}, "mapResolution": {}}
            for rep in range(reps):
                # Graphs 2/3 (M2, M3, M6): small (default) and 3x larger bundles.
                for n in levels_of[scene]:
                    for size_label, factor in (("small", 1.0), ("large", 3.0)):
                        out, r = splat(bounce, tmp, scene, {"photons": n, "mapSize": f"{2.0 * half * factor:.6f}"})
                        rows["splat"].setdefault(f"{size_label}/{n}", []).append(
                            {**r, "vsReference": compare(bounce, out, ref), "vsPhotonMapHq": compare(bounce, out, hq_keep)})
                # Graph 4: stratified, more photons and more voxels, 3x larger bundles.
                for n, g in strat:
                    out, r = splat(bounce, tmp, scene, {"photons": n, "stratify": "true", "gridSize": g, "mapSize": f"{6.0 * half:.6f}"})
                    rows["stratified"].setdefault(f"{g}/{n}", []).append(
                        {**r, "vsReference": compare(bounce, out, ref), "vsPhotonMapHq": compare(bounce, out, hq_keep)})
                # Graph 1 (M2).
                for n, k in pm_levels:
                    out, r = photon_map(bounce, tmp, scene, n, k)
                    rows["photonMap"].setdefault(f"{n}/k{k}", []).append({**r, "vsReference": compare(bounce, out, ref)})
                # M5: 4x4 vs 32x32 depth maps, same photons.
                for res_ in (4, 32):
                    out, r = splat(bounce, tmp, scene, {"photons": 16384, "mapResolution": res_})
                    rows["mapResolution"].setdefault(str(res_), []).append({**r, "vsReference": compare(bounce, out, ref)})
            res.update(rows)
            # The document's small step back (b = h/4) against bounce's b = d, at the defaults.
            res["stepBack"] = {}
            for label, sb in (("d", None), ("h/4", 0.25 * half)):
                out, r = splat(bounce, tmp, scene, {} if sb is None else {"stepBack": f"{sb:.6f}"}, frames=1)
                res["stepBack"][label] = {**r, "vsReference": compare(bounce, out, ref)}
            record["results"][scene] = res
            print(scene, "done", flush=True)
        # The kernel's remaining bias: energy over bundle width, seeds averaged, no blur.
        bias = {}
        for scene in ["furnace", "cornell-box"]:
            ref = reference(bounce, tmp, scene)
            half = half_width(bounce, tmp, scene)
            for factor in ((2.0, 1.0) if quick else (2.0, 1.0, 0.5)):
                for seed in ((1,) if quick else (1, 2, 3)):
                    out, r = splat(bounce, tmp, scene, {"photons": 32768, "blur": 0, "seed": seed, "mapSize": f"{2.0 * half * factor:.6f}"},
                                   frames=1)
                    bias.setdefault(scene, {}).setdefault(f"{factor:g}", []).append(
                        {"energy": compare(bounce, out, ref)["energy"], "mapSize": 2.0 * half * factor, "command": r["command"]})
        record["results"]["bias"] = bias
        # M1: memory the counters report (what is allocated).
        m1 = {}
        for g in (16, 64, 256):
            _, r = splat(bounce, tmp, "cornell-box", {"stratify": "true", "gridSize": g}, frames=1)
            m1[str(g)] = {"gridBytes": r["gridBytes"], "photonsStored": r["photonsStored"]}
        record["results"]["memory"] = {"gridBytes": m1, "photonBytesPerPhoton": r["photonBytes"] / max(r["photonsStored"], 1)}
    print("wrote", write_record(record))


if __name__ == "__main__":
    main()
