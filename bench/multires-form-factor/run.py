#!/usr/bin/env python3
"""Where multires-splat's light comes from against the path tracer: its form factor, not its refinement.

Usage: bench/multires-form-factor/run.py [BOUNCE] [--size N] [--spp N]   (BOUNCE defaults to build/src/app/bounce)

On `atrium` (100K triangles, sun through the open roof), `cornell-box` and `cornell-box-area`, against
`bounce reference --bounces 1 --indirect-only` (multires-splat's reference scope): multires-splat at
its defaults and at full refinement (depthThreshold = normalThreshold = 0), each with Eq. 4.1's disk
form factor (formFactor=disk, the default since 2026-12-06) and Eq. 3.2's point form factor with the
5 cm r^2 clamp (formFactor=point, the default before), beside the `rsm` gather with the same two form
factors (same RSM, same 16^2 VPLs). Full refinement equals the gather of the same form factor, so the
gap between the two form factors, not the upsampling or the refinement criteria, is the light a
technique adds. Also each image against the gather with its own form factor (relative RMS).
The raw record goes to bench/results/multires-form-factor-<date>.json.
"""
import functools
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from cli import compare as compare_metrics, option, rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

# The metrics of `bounce compare` this record keeps (bench/cli.py compare).
compare = functools.partial(compare_metrics, keys=("energy", "relMse", "relRms"))

SCENES = ["atrium", "cornell-box", "cornell-box-area"]
FULL = {"depthThreshold": "0", "normalThreshold": "0"}


def main():
    args = sys.argv[1:]
    size = option(args, "--size", 128)
    spp = option(args, "--spp", 1024)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    record = new_record("multires-form-factor", " ".join(["bench/multires-form-factor/run.py"] + sys.argv[1:]), bounce)
    record.update({"size": size, "spp": spp, "scenes": {}})
    with tempfile.TemporaryDirectory() as tmp:
        for scene in SCENES:
            ref = os.path.join(tmp, f"{scene}-ref.exr")
            refcmd = [bounce, "reference", "--scene", scene, "--size", f"{size}x{size}", "--spp", str(spp), "--bounces", "1",
                      "--indirect-only", "--out", ref]
            subprocess.run(refcmd, check=True, capture_output=True)
            entry = {"reference": rel(refcmd), "runs": {}}
            images = {}
            for form in ("disk", "point"):
                cases = {f"rsm {form}": ("rsm", {"formFactor": form}),
                         f"multires-splat {form}": ("multires-splat", {"formFactor": form}),
                         f"multires-splat {form} full refinement": ("multires-splat", {"formFactor": form, **FULL})}
                for label, (technique, settings) in cases.items():
                    out = os.path.join(tmp, label.replace(" ", "_") + ".exr")
                    cmd = [bounce, "render", "--scene", scene, "--technique", technique, "--size", f"{size}x{size}",
                           "--component", "indirect", "--out", out]
                    for k, v in settings.items():
                        cmd += ["--set", f"{k}={v}"]
                    subprocess.run(cmd, check=True, capture_output=True)
                    images[label] = out
                    entry["runs"][label] = {"command": rel(cmd), "vsReference": compare(bounce, out, ref)}
                for label in (f"multires-splat {form}", f"multires-splat {form} full refinement"):
                    entry["runs"][label]["vsRsmSameFormFactor"] = compare(bounce, images[label], images[f"rsm {form}"])
            record["scenes"][scene] = entry
            for label, r in entry["runs"].items():
                m = r["vsReference"]
                print(f"{scene:18s} {label:40s} energy {m['energy']:.3f} relMSE {m['relMse']:.4f}"
                      + (f"  vs rsm same form: relRms {r['vsRsmSameFormFactor']['relRms']:.2e}" if "vsRsmSameFormFactor" in r else ""),
                      flush=True)
    print(write_record(record))


if __name__ == "__main__":
    main()
