#!/usr/bin/env python3
"""Why iir's R1 at 1024 VPLs on `atrium` exceeds its map-count bound (docs/techniques/iir.md): the cost of
one paraboloid map against the number of maps a frame renders, in both modes, and against the map size.

Usage: bench/iir-maps/run.py [BOUNCE] [--reps N] [--frames N]   (defaults: build/src/app/bounce, 3, 6)

Each run: `bounce render --scene atrium --scene-param triangles=20000 --technique iir --size 256x256` with
`renderer.timing=finish`, frames after the first; per frame the `iir/sm-rendering` time over the counter
`vplShadowMaps` (maps rendered), summed over the frames. Cases maxLights 256 / 1024 x shadowMapSize
256 / 128 x incremental true / false, interleaved over the repetitions. If the comparison mode's cost per
map grows with the maps per frame only at the larger map size, the growth is the depth array's working
set (maps x size^2 x 2 bytes) leaving the CPU's caches rather than the maps' content.
The raw record goes to bench/results/iir-maps-<date>.json.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from cli import ROOT, later, option, render, summary  # noqa: E402
from record import new_record, write_record  # noqa: E402


def main():
    args = sys.argv[1:]
    reps = option(args, "--reps", 3)
    frames = option(args, "--frames", 6)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    rec = new_record("iir-maps", f"bench/iir-maps/run.py --reps {reps} --frames {frames}", bounce)
    rec.update({"reps": reps, "frames": frames, "timing": "finish", "scene": "atrium", "params": ["triangles=20000"], "size": 256})
    cases = {}
    for _ in range(reps):
        for lights in [256, 1024]:
            for size in [256, 128]:
                for inc in ["true", "false"]:
                    key = f"maxLights={lights} shadowMapSize={size} incremental={inc}"
                    r, cmd = render(bounce, "atrium", "iir", 256, frames,
                                    {"renderer.timing": "finish", "maxLights": lights, "shadowMapSize": size, "incremental": inc},
                                    ["triangles=20000"])
                    fs = later(r)
                    maps = sum(f["counters"].get("vplShadowMaps", 0.0) for f in fs)
                    ms = sum(f["gpu_ms"].get("iir/sm-rendering", 0.0) for f in fs)
                    c = cases.setdefault(key, {"command": cmd, "maxLights": lights, "shadowMapSize": size,
                                               "incremental": inc == "true", "mapsPerFrame": maps / len(fs), "msPerMap": []})
                    c["msPerMap"].append(ms / maps if maps else 0.0)
                    print(key, round(maps / len(fs), 1), round(ms / max(maps, 1), 3), flush=True)
    for c in cases.values():
        c["msPerMap"] = summary(c["msPerMap"])
    rec["cases"] = cases
    print(write_record(rec))


if __name__ == "__main__":
    main()
