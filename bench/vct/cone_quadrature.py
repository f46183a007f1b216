#!/usr/bin/env python3
"""vct's energy against the ideal quadrature of its own six cones (docs/techniques/vct.md, "The six cones'
own bias").

Usage: bench/vct/cone_quadrature.py [BOUNCE] [--size N] [--spp N] [--scenes a,b]   (any Python 3, no numpy)

Per built-in scene vct accepts: `bounce reference` in vct's scope (--bounces 1 --indirect-only) with the
cosine lobe (the reference) and with `--first-reflection vct-cones` (the first reflection's direction
drawn from Rauwendaal 2013's six 60-degree cones with their Eq. 6.9 weights: the cone quadrature of the
exact incident light, vct without any voxel error), and vct's indirect output at its defaults. Recorded:
the quadrature's energy against the reference (the method's own bias: light from directions between
the cones is lost, light inside them weighted by W_k / Omega_k instead of cos theta), vct's against the
reference, and vct's against the quadrature (the voxel representation's part). The raw record goes to
bench/results/vct-cone-quadrature-<date>.json.
"""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import compare, option, rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

SCOPE = ["--bounces", "1", "--indirect-only"]


def main():
    args = sys.argv[1:]
    size = option(args, "--size", 128)
    spp = option(args, "--spp", 1024)
    only = option(args, "--scenes", "", str)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    scenes = subprocess.run([bounce, "list", "--scenes", "--names"], check=True, capture_output=True, text=True).stdout.split()
    scenes = [s for s in scenes if not only or s in only.split(",")]
    record = new_record("vct-cone-quadrature", " ".join(["bench/vct/cone_quadrature.py"] + sys.argv[1:]), bounce)
    record.update({"size": size, "spp": spp, "scope": " ".join(SCOPE), "results": {}})
    dims = f"{size}x{size}"
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            vct = os.path.join(tmp, "vct.exr")
            cmd = [bounce, "render", "--scene", scene, "--technique", "vct", "--size", dims, "--component", "indirect", "--out", vct]
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode != 0:
                record["results"][scene] = {"refused": (p.stderr.strip().splitlines() or [""])[-1]}
                print(f"{scene:22s} refused", flush=True)
                continue
            entry = {"vct": rel(cmd)}
            images = {}
            for mode in ("cosine", "vct-cones"):
                path = os.path.join(tmp, f"{mode}.exr")
                ref = [bounce, "reference", "--scene", scene, "--size", dims, "--spp", str(spp), "--first-reflection", mode,
                       "--out", path] + SCOPE
                subprocess.run(ref, check=True, capture_output=True, text=True)
                entry[mode] = rel(ref)
                images[mode] = path
            quad = compare(bounce, images["vct-cones"], images["cosine"], keys=("energy", "relMse"))
            tech = compare(bounce, vct, images["cosine"], keys=("energy", "relMse"))
            own = compare(bounce, vct, images["vct-cones"], keys=("energy", "relMse"))
            entry.update({"quadratureVsReference": quad, "vctVsReference": tech, "vctVsQuadrature": own})
            record["results"][scene] = entry
            print(f"{scene:22s} quadrature {quad['energy']:.3f}  vct {tech['energy']:.3f}  vct/quadrature {own['energy']:.3f} "
                  f"(relMSE vs its quadrature {own['relMse']:.3f}, vs the reference {tech['relMse']:.3f})", flush=True)
    print(write_record(record))


if __name__ == "__main__":
    main()
