#!/usr/bin/env python3
"""Interleaved frame times of hisr against the plain rsm gather (issue 10, "hisr's stencil does not cull
its gather").

Each side is one `bounce render ... --frames N --stats run.json` process; the sides run round-robin
(A B [C] A B [C] ...) so that load from other users of the machine falls on all of them alike. Per run
the record keeps the run record's median_ms.frame (GPU timer scope "frame", median over the frames)
and median_ms.cpu, the process's wall time, and the last frame's counters; per side min/median/max;
per round the ratio of each side to each later one, with min/median/max.

Usage:
  bench/hisr-stencil/run.py --out bench/results/hisr-stencil-DATE.json [--rounds 7] [--size 256x256]
      [--frames 10] [--scene cornell-box-dynamic]
      --side LABEL=BINARY:COMMIT:TECHNIQUE[:name=value,...] ...   (COMMIT: the one BINARY was built from)
"""
import argparse
import functools
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from datetime import datetime, timezone

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from cli import summary as summary_n  # noqa: E402

# min, median, max without the count (bench/cli.py summary).
summary = functools.partial(summary_n, n=False)


def parse_side(text):
    label, rest = text.split("=", 1)
    parts = rest.split(":")
    binary, commit, technique = parts[0], parts[1], parts[2]
    settings = [s for s in parts[3].split(",") if s] if len(parts) > 3 else []
    return {"label": label, "binary": os.path.realpath(binary), "commit": commit, "technique": technique,
            "settings": settings}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--side", action="append", required=True, type=parse_side)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--size", default="256x256")
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--scene", default="cornell-box-dynamic")
    args = ap.parse_args()

    repo_commit = subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    record = {
        "command": " ".join([os.path.relpath(sys.argv[0])] + sys.argv[1:]),
        "commit": repo_commit,
        "date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "machine": {"uname_n": platform.node(), "cores": os.cpu_count(),
                    "loadavg_start": list(os.getloadavg())},
        "scene": args.scene, "size": args.size, "frames": args.frames, "rounds": args.rounds,
        "metric": "median_ms.frame of each run record (GPU timer scope 'frame', median over the frames)",
        "sides": [{k: s[k] for k in ("label", "commit", "technique", "settings")} for s in args.side],
        "runs": [],
    }
    renderer = None
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(args.rounds):
            for s in args.side:
                stats = os.path.join(tmp, f"{s['label']}-{r}.json")
                cmd = [s["binary"], "render", "--scene", args.scene, "--technique", s["technique"], "--size", args.size,
                       "--frames", str(args.frames), "--component", "indirect", "--out", os.path.join(tmp, "out.exr"),
                       "--stats", stats]
                for kv in s["settings"]:
                    cmd += ["--set", kv]
                t0 = time.monotonic()
                subprocess.run(cmd, check=True)
                wall = time.monotonic() - t0
                with open(stats) as f:
                    run = json.load(f)
                renderer = run["gpu"]["renderer"]
                entry = {"round": r, "side": s["label"], "frame_ms": run["median_ms"]["frame"],
                         "cpu_ms": run["median_ms"]["cpu"], "wall_s": round(wall, 3),
                         "counters": run["frames"][-1]["counters"]}
                record["runs"].append(entry)
                print(f"round {r} {s['label']:>12}: frame {entry['frame_ms']:9.1f} ms  wall {wall:6.1f} s", flush=True)
    record["gpu"] = {"renderer": renderer}
    record["machine"]["loadavg_end"] = list(os.getloadavg())
    labels = [s["label"] for s in args.side]
    record["summary"] = {}
    for label in labels:
        frames = [e["frame_ms"] for e in record["runs"] if e["side"] == label]
        record["summary"][label] = {"frame_ms": summary(frames), "frame_ms_values": frames}

    def frame(r, label):
        return next(e["frame_ms"] for e in record["runs"] if e["round"] == r and e["side"] == label)

    # Per-round ratios of every earlier side to every later one (the same round's runs are adjacent).
    record["ratios"] = {}
    for i, a in enumerate(labels):
        for b in labels[i + 1:]:
            values = [frame(r, a) / frame(r, b) for r in range(args.rounds)]
            record["ratios"][f"{a}/{b}"] = {**summary(values), "values": values}
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(record, f, indent=1)
        f.write("\n")
    print(json.dumps({k: v["frame_ms"] for k, v in record["summary"].items()}, indent=1))
    print(json.dumps({k: {m: v[m] for m in ("min", "median", "max")} for k, v in record["ratios"].items()}, indent=1))


if __name__ == "__main__":
    main()
