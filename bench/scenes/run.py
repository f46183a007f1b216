#!/usr/bin/env python3
"""Load time and peak memory of the large built-in scenes (issue 30): `courtyard` (the Sponza-class
scene, default 150K triangles, sun and sky) and 1M-triangle variants of `courtyard` and `atrium`.
Each is one `bounce render --technique direct` frame at 256x256 under `/usr/bin/time -v`:
scene_load_seconds (the generator and finalizeScene) and setup_seconds (scene upload, shadow maps'
and the technique's set-up) come from the run record, peak_rss_mb is the process's maximum resident
set size (CPU memory; llvmpipe's GPU memory is CPU memory too), frame_ms the GPU frame time.
Each case runs REPEATS times (the machine is shared: the minimum is the cost, the median is shown too).
Usage: bench/scenes/run.py [--bounce PATH] [--name NAME] [--repeats N]
Writes bench/results/<name>-<date>.json."""
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from record import ROOT, new_record, write_record  # noqa: E402
from cli import option, rel  # noqa: E402

CASES = [
    ("courtyard", []),
    ("courtyard", ["light=sky"]),
    ("courtyard", ["triangles=1000000"]),
    ("atrium", []),
    ("atrium", ["triangles=1000000"]),
]


def run_case(bounce, scene, params):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "run.json")
        cmd = [bounce, "render", "--scene", scene, "--technique", "direct", "--size", "256x256",
               "--out", os.path.join(tmp, "o.exr"), "--stats", stats]
        for p in params:
            cmd += ["--scene-param", p]
        done = subprocess.run(["/usr/bin/time", "-v"] + cmd, check=True, capture_output=True, text=True)
        rss_kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", done.stderr).group(1))
        wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", done.stderr).group(1)
        with open(stats) as f:
            run = json.load(f)
    minutes, seconds = wall.split(":")[-2:]
    return {
        "scene": scene,
        "params": params,
        "command": rel(cmd),
        "triangles": run["scene"]["triangles"],
        "scene_load_seconds": round(run["scene_load_seconds"], 3),
        "setup_seconds": round(run["setup_seconds"], 3),
        "frame_ms": round(run["median_ms"].get("frame", 0.0), 1),
        "peak_rss_mb": round(rss_kb / 1024.0, 1),
        "wall_seconds": round(60 * float(minutes) + float(seconds), 2),
    }


def main():
    args = sys.argv[1:]
    bounce = option(args, "--bounce", os.path.join(ROOT, "build/src/app/bounce"), str)
    name = option(args, "--name", "scene-load", str)
    record = new_record(name, "bench/scenes/run.py " + " ".join(sys.argv[1:]), bounce)
    record["unit"] = "seconds (minimum of the repeats), MB (maximum), ms (GPU frame, minimum)"
    record["results"] = []
    repeats = option(args, "--repeats", 3)
    record["repeats"] = repeats
    for scene, params in CASES:
        runs = [run_case(bounce, scene, params) for _ in range(repeats)]
        r = dict(runs[0])
        for key in ("scene_load_seconds", "setup_seconds", "frame_ms", "wall_seconds"):
            values = sorted(x[key] for x in runs)
            r[key] = values[0]
            r["median_" + key] = values[len(values) // 2]
        r["peak_rss_mb"] = max(x["peak_rss_mb"] for x in runs)
        print(f"{scene:10} {' '.join(params):20} {r['triangles']:>8} triangles: load {r['scene_load_seconds']:.3f} s, "
              f"setup {r['setup_seconds']:.3f} s, frame {r['frame_ms']:.1f} ms, peak RSS {r['peak_rss_mb']:.0f} MB")
        record["results"].append(r)
    print("wrote", write_record(record))


if __name__ == "__main__":
    main()
