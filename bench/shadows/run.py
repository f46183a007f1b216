#!/usr/bin/env python3
"""Directional-light shadows on large scenes (issue 30; docs/rendering.md "Shadows on large scenes",
docs/techniques/direct.md): `direct` against `bounce reference --bounces 0` per scene, at SIZE^2 as
rendered (pixel centres) and at SSxSS samples per pixel (--supersample, default 4) box-filtered to SIZE^2 (the reference integrates
each pixel's footprint, so this leaves the shadows' error without the geometric edges' aliasing),
for each binary (label=path: the code before and after) and each settings variant.

usage: bench/shadows/run.py --bin after=build/src/app/bounce [--bin before=/path/to/old/bounce
       --shaders before=/path/to/old/shaders]
       [--scenes courtyard,atrium,cornell-box,two-rooms] [--size 256] [--spp 256] [--refs DIR]
       [--variant NAME=renderer.k=v,...] [--supersample SS] [--name shadows]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from record import ROOT, new_record, write_record  # noqa: E402

sys.path.insert(0, os.path.join(ROOT, "build/python"))
import bounce as bp  # noqa: E402

EPS = 0.01  # relMSE's epsilon (metrics/ErrorMetrics.h kRelMseEpsilon)
SS = 4      # samples per pixel per axis of the supersampled render (--supersample)


def run(cmd, shaders=None):
    env = dict(os.environ, BOUNCE_SHADER_DIR=shaders) if shaders else None
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}: {r.stderr.strip()}")
    return r.stdout


def metrics(x, r):
    return {"relMse": float(np.mean((x - r) ** 2 / (r ** 2 + EPS))), "energy": float(x.mean() / r.mean())}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", action="append", required=True)
    ap.add_argument("--shaders", action="append", default=[], help="label=DIR: that binary's shaders (BOUNCE_SHADER_DIR)")
    ap.add_argument("--scenes", default="courtyard,atrium,cornell-box,two-rooms")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--refs", default=None, help="folder with ref-SCENE.exr/.json/-var.exr to reuse")
    ap.add_argument("--variant", action="append", default=[])
    ap.add_argument("--name", default="shadows")
    ap.add_argument("--supersample", type=int, default=SS)
    a = ap.parse_args()
    ss = a.supersample
    bins = dict(b.split("=", 1) for b in a.bin)
    shaders = dict(b.split("=", 1) for b in a.shaders)
    variants = {"defaults": []}
    for v in a.variant:
        name, sets = v.split("=", 1)
        variants[name] = sets.split(",")
    tmp = tempfile.mkdtemp(prefix="bounce-shadows-")
    refs = a.refs or tmp
    first = next(iter(bins.values()))
    rec = new_record(a.name, " ".join(sys.argv), first)
    rec.update({"size": a.size, "spp": a.spp, "supersample": ss, "binaries": bins, "shaders": shaders, "variants": variants, "scenes": {}})
    n = a.size
    for scene in a.scenes.split(","):
        ref_exr = os.path.join(refs, f"ref-{scene}.exr")
        if not os.path.exists(ref_exr):
            run([first, "reference", "--scene", scene, "--size", f"{n}x{n}", "--bounces", "0", "--spp", str(a.spp),
                 "--out", ref_exr, "--stats", ref_exr[:-4] + ".json", "--variance", ref_exr[:-4] + "-var.exr"])
        ref = np.asarray(bp.read_image(ref_exr), dtype=np.float64)
        entry = {"reference": ref_exr, "results": {}}
        for label, path in bins.items():
            for vname, sets in variants.items():
                extra = [arg for s in sets for arg in ("--set", s)]
                out = os.path.join(tmp, f"{scene}-{label}-{vname}")
                run([path, "render", "--scene", scene, "--technique", "direct", "--component", "direct",
                     "--size", f"{n}x{n}", "--out", out + ".exr"] + extra, shaders.get(label))
                run([path, "render", "--scene", scene, "--technique", "direct", "--component", "direct",
                     "--size", f"{n * ss}x{n * ss}", "--out", out + "-ss.exr"] + extra, shaders.get(label))
                cmp = json.loads(run([path, "compare", "--json", out + ".exr", ref_exr]))
                x = np.asarray(bp.read_image(out + ".exr"), dtype=np.float64)
                xs = np.asarray(bp.read_image(out + "-ss.exr"), dtype=np.float64).reshape(n, ss, n, ss, 3).mean(axis=(1, 3))
                res = {"pixelCentres": metrics(x, ref), "supersampled": metrics(xs, ref)}
                floor = cmp.get("noiseFloor", {}).get("floor", {})
                if floor:
                    entry["relMseFloor"] = floor.get("relMse")
                entry["results"][f"{label}/{vname}"] = res
                print(scene, label, vname, json.dumps(res), flush=True)
        rec["scenes"][scene] = entry
    print(write_record(rec))


if __name__ == "__main__":
    main()
