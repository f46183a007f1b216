#!/usr/bin/env python3
"""How much light the RSM gathers add by having no indirect visibility (Nichols 2010 ch. 3-4, as
Dachsbacher & Stamminger 2005): the converged gather (`rsm` with vplGrid 128, every 2nd RSM texel a
VPL) with and without `vplVisibility` (a voxel march per receiver-VPL pair, beyond the thesis), and
the defaults of isr / hisr, against the one-bounce reference, on the built-in scenes where the RSM
family's energy leaves +-15 % (bench/fidelity/run.py).

Usage: bench/fidelity/visibility.py [BOUNCE] [--size N] [--spp N] [--scenes a,b] [--name NAME]   (any Python 3)
Writes bench/results/<NAME>-<date>.json (NAME defaults to rsm-visibility); docs/techniques/rsm.md quotes it.
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import option, rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

SCENES = ["cornell-box-area", "atrium", "furnished-room", "courtyard"]
CASES = [
    ("rsm converged", "rsm", {"vplGrid": 128}),
    ("rsm converged + vplVisibility", "rsm", {"vplGrid": 128, "vplVisibility": "true"}),
    ("isr", "isr", {}),
    ("hisr", "hisr", {}),
    ("multires-splat", "multires-splat", {}),
]


def main():
    args = sys.argv[1:]
    size = option(args, "--size", 128)
    spp = option(args, "--spp", 1024)
    only = option(args, "--scenes", "", str)
    name = option(args, "--name", "rsm-visibility", str)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    record = new_record(name, " ".join(["bench/fidelity/visibility.py"] + sys.argv[1:]), bounce)
    record.update({"size": size, "spp": spp, "results": {}})
    with tempfile.TemporaryDirectory() as tmp:
        for scene in [s for s in SCENES if not only or s in only.split(",")]:
            ref = os.path.join(tmp, "ref.exr")
            cmd = [bounce, "reference", "--scene", scene, "--size", f"{size}x{size}", "--spp", str(spp), "--bounces", "1",
                   "--indirect-only", "--out", ref]
            subprocess.run(cmd, check=True, capture_output=True)
            record["results"][scene] = {"reference": rel(cmd), "cases": {}}
            for label, technique, settings in CASES:
                out = os.path.join(tmp, "t.exr")
                rcmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", f"{size}x{size}",
                        "--component", "indirect", "--out", out]
                for k, v in settings.items():
                    rcmd += ["--set", f"{k}={v}"]
                subprocess.run(rcmd, check=True, capture_output=True)
                m = json.loads(subprocess.run([bounce, "compare", "--json", out, ref], check=True, capture_output=True,
                                              text=True).stdout)["metrics"]
                record["results"][scene]["cases"][label] = {"command": rel(rcmd), "energy": m["energy"], "relMse": m["relMse"]}
                print(f"{scene:18s} {label:32s} energy {m['energy']:.3f} relMSE {m['relMse']:.4f}", flush=True)
    print(write_record(record))


if __name__ == "__main__":
    main()
