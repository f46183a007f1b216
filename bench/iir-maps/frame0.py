#!/usr/bin/env python3
"""iir: ms per paraboloid map in frame 0 (every VPL of the budget gets its map) against frames 1-3 (only the VPLs added that
frame), the same incremental run; writes bench/results/iir-maps-frame0-<date>.json. See docs/techniques/iir.md."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from cli import render, summary
from record import new_record, write_record
bounce = sys.argv[1] if len(sys.argv) > 1 else "build/src/app/bounce"
rec = new_record("iir-maps-frame0", f"bench/iir-maps/frame0.py {bounce}", bounce)
rec["description"] = ("bounce render --scene atrium --scene-param triangles=20000 --technique iir --size 256x256 --frames 4 --set renderer.timing=finish --set maxLights=256 --set incremental=true, 3 runs; iir/sm-rendering ms per map (counter vplShadowMaps) of frame 0 (the budget filled: every VPL's map) and of frames 1-3 (the VPLs added that frame)")
f0, later = [], []
cmds = None
for _ in range(3):
    r, cmds = render(bounce, "atrium", "iir", 256, 4, {"renderer.timing": "finish", "maxLights": 256, "incremental": "true"}, ["triangles=20000"])
    fr = r["frames"]
    f0.append(fr[0]["gpu_ms"]["iir/sm-rendering"] / fr[0]["counters"]["vplShadowMaps"])
    maps = sum(f["counters"].get("vplShadowMaps", 0.0) for f in fr[1:])
    later.append(sum(f["gpu_ms"].get("iir/sm-rendering", 0.0) for f in fr[1:]) / maps)
    rec.setdefault("mapsFrame0", fr[0]["counters"]["vplShadowMaps"]); rec["mapsLaterPerFrame"] = maps / 3
rec.update({"command_run": cmds, "msPerMapFrame0": summary(f0), "msPerMapLater": summary(later)})
print(rec["msPerMapFrame0"], rec["msPerMapLater"], write_record(rec))
