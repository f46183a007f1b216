#!/usr/bin/env python3
"""photon-splat's two estimates against the one-bounce reference, one raw record.

Usage: bench/photon-splat/estimates.py [BOUNCE]   (BOUNCE defaults to build/src/app/bounce)

Renders the defaults (estimate=flux) and the document's estimate=normalized (exposure 1, the other
settings at their defaults) on the Cornell scenes at 128^2 and compares each with
`bounce reference --bounces 1 --indirect-only` (energy = image mean / reference mean, relMSE).
docs/techniques/photon-splat.md quotes it for "the normalised estimate has no physical scale".
Writes bench/results/photon-splat-estimates-<date>.json.
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


def main():
    bounce = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build/src/app/bounce"))
    record = new_record("photon-splat-estimates", " ".join(["bench/photon-splat/estimates.py"] + sys.argv[1:]), bounce)
    record.update({"size": SIZE, "results": {}})
    with tempfile.TemporaryDirectory() as tmp:
        for scene in ("cornell-box", "cornell-box-area"):
            ref = os.path.join(tmp, "ref.exr")
            subprocess.run([bounce, "reference", "--scene", scene, "--size", SIZE, "--spp", "1024", "--bounces", "1", "--indirect-only",
                            "--out", ref], check=True, capture_output=True)
            for estimate in ("flux", "normalized"):
                out = os.path.join(tmp, "t.exr")
                cmd = [bounce, "render", "--scene", scene, "--technique", "photon-splat", "--size", SIZE, "--component", "indirect",
                       "--set", f"estimate={estimate}", "--out", out]
                subprocess.run(cmd, check=True, capture_output=True)
                m = json.loads(subprocess.run([bounce, "compare", "--json", out, ref], check=True, capture_output=True,
                                              text=True).stdout)["metrics"]
                record["results"].setdefault(scene, {})[estimate] = {"energy": m["energy"], "relMse": m["relMse"],
                                                                     "command": " ".join(cmd[1:-2])}
                print(scene, estimate, f"energy {m['energy']:.3f} relMSE {m['relMse']:.4f}", flush=True)
    print("wrote", write_record(record))


if __name__ == "__main__":
    main()
