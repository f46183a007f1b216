#!/usr/bin/env python3
"""multires-splat's refinePass: the thesis's geometry shader with transform feedback against the compute
pass (same subsplats, same image: MultiresSplatGpuTest.ComputeRefineEqualsGeometryRefine), interleaved
(A B A B ...), `refine` pass time with `renderer.timing=finish`, second frame of 2, on
`cornell-box-dynamic`: mode B (refinement=shared) at 256^2 and mode A (refinement=per-vpl, one list per
VPL) at 64^2, 256 VPLs. Ratio geometry / compute per repetition.
Usage: bench/multires-refine/run.py [BOUNCE] [--reps N]; writes bench/results/multires-refine-<date>.json."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from cli import ROOT, option, pass_ms, render, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402

args = sys.argv[1:]
reps = option(args, "--reps", 3)
bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
rec = new_record("multires-refine", f"bench/multires-refine/run.py --reps {reps}", bounce)
cases = {}
for mode, size in [("shared", 256), ("per-vpl", 64)]:
    times = {"geometry": [], "compute": []}
    commands = {}
    for _ in range(reps):
        for rp in times:
            r, cmd = render(bounce, "cornell-box-dynamic", "multires-splat", size, 2,
                            {"renderer.timing": "finish", "refinement": mode, "refinePass": rp})
            times[rp].append(pass_ms(r, "multires-splat/refine")[-1])
            commands[rp] = cmd
    cases[f"refinement={mode} {size}x{size}"] = {
        "commands": commands, "refineMs": {k: summary(v) for k, v in times.items()},
        "ratio": summary(g / c for g, c in zip(times["geometry"], times["compute"]))}
    print(mode, {k: round(summary(v)["median"], 1) for k, v in times.items()}, flush=True)
rec["reps"] = reps
rec["cases"] = cases
print(write_record(rec))
