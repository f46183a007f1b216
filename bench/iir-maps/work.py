#!/usr/bin/env python3
"""iir R1 anomaly, the work behind a map: depth samples passed per paraboloid map (counter vplMapSamples, a
GL_SAMPLES_PASSED query over a frame's maps), for the comparison mode, the
incremental mode's frame 0 (a map for every VPL of the budget) and its later frames (maps of the VPLs just
added), on `atrium` (20K triangles) at 256 and 1024 VPLs, 256^2, 6 frames. Counts only (no timing), so the
host's load does not matter. Writes bench/results/iir-maps-work-<date>.json."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from cli import render, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402

bounce = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "build/src/app/bounce")
rec = new_record("iir-maps-work", "bench/iir-maps/work.py", bounce)
cases = {}
for lights in ["256", "1024"]:
    for inc in ["false", "true"]:
        r, cmd = render(bounce, "atrium", "iir", 256, 6, {"maxLights": lights, "incremental": inc}, ["triangles=20000"])
        groups = {"comparison": r["frames"]} if inc == "false" else {"incremental frame 0": r["frames"][:1],
                                                                      "incremental later frames": r["frames"][1:]}
        for name, frames in groups.items():
            rows = [f["counters"] for f in frames if f["counters"].get("vplShadowMaps", 0) > 0]
            maps = sum(c["vplShadowMaps"] for c in rows)
            case = {"command": cmd, "frames": len(rows), "mapsPerFrame": maps / max(len(rows), 1),
                    "samplesPerMap": summary(c["vplMapSamples"] / c["vplShadowMaps"] for c in rows)}
            cases[f"{lights} VPLs, {name}"] = case
            print(lights, name, round(case["mapsPerFrame"], 1), round(case["samplesPerMap"]["median"]),
                  case["samplesPerMap"], flush=True)
rec["cases"] = cases
print(write_record(rec))
