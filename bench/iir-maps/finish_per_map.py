#!/usr/bin/env python3
"""iir experiment: does a glFinish after every paraboloid map change its cost? Needs a build with one extra line in
IirTechnique::renderShadowMaps after each map's draw, not committed:
    if (std::getenv("BOUNCE_EXPERIMENT_FINISH_PER_MAP")) glFinish();
Usage: bench/iir-maps/finish_per_map.py PATCHED_BOUNCE; writes bench/results/iir-maps-finish-<date>.json."""
import os, sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from cli import later, render, summary
from record import new_record, write_record
bounce = sys.argv[1]
rec = new_record("iir-maps-finish", f"bench/iir-maps/finish_per_map.py {bounce}", bounce)
rec["description"] = ("bounce render --scene atrium --scene-param triangles=20000 --technique iir --size 256x256 --frames 4 --set renderer.timing=finish --set maxLights=256 --set incremental=true|false, with and without BOUNCE_EXPERIMENT_FINISH_PER_MAP=1")
rec["binary"] = ("build of this commit with one experimental line in IirTechnique::renderShadowMaps, not committed: "
                 "'if (std::getenv(\"BOUNCE_EXPERIMENT_FINISH_PER_MAP\")) glFinish();' after each map's draw")
cases = {}
for _ in range(3):
    for inc in ["false", "true"]:
        for fin in ["0", "1"]:
            if fin == "1": os.environ["BOUNCE_EXPERIMENT_FINISH_PER_MAP"] = "1"
            else: os.environ.pop("BOUNCE_EXPERIMENT_FINISH_PER_MAP", None)
            r, cmd = render(bounce, "atrium", "iir", 256, 4, {"renderer.timing": "finish", "maxLights": 256, "incremental": inc}, ["triangles=20000"])
            fs = later(r)
            maps = sum(f["counters"].get("vplShadowMaps", 0.0) for f in fs)
            ms = sum(f["gpu_ms"].get("iir/sm-rendering", 0.0) for f in fs)
            key = f"incremental={inc} finishPerMap={fin}"
            c = cases.setdefault(key, {"command": cmd, "mapsPerFrame": maps / len(fs), "msPerMap": []})
            c["msPerMap"].append(ms / maps if maps else 0.0)
            print(key, maps / len(fs), round(ms / max(maps, 1), 3), flush=True)
os.environ.pop("BOUNCE_EXPERIMENT_FINISH_PER_MAP", None)
for c in cases.values(): c["msPerMap"] = summary(c["msPerMap"])
rec["cases"] = cases
print(write_record(rec))
