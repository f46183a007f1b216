#!/usr/bin/env python3
"""`make demo`'s time: its rendering part (every built-in scene x every technique, scripts/demo.sh) and
its study, run as `make demo` runs them, into a temporary folder (issue 30: the rendering part within
3 minutes on 2 cores).

Usage: bench/demo/run.py [BOUNCE] [--size WxH] [--render-only]
       (BOUNCE defaults to build/src/app/bounce, WxH to the Makefile's DEMO_SIZE 512x512; any Python 3)

Records the rendering part's and the study's wall seconds, and each pair's wall milliseconds and exit
status (0 rendered, 1 refused in one line, `skipped` by the demo's own choice) from the demo's
demo-times.tsv, in bench/results/demo-<date>.json (bench/record.py). The slowest pairs are what to
look at when the rendering part grows.
"""
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from cli import ROOT, option, rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

# issue 30: `make demo`'s rendering part, after the build, on 2 cores.
RENDER_BUDGET_SECONDS = 180


def main():
    args = sys.argv[1:]
    size = option(args, "--size", "512x512", str)
    render_only = "--render-only" in args
    if render_only:
        args.remove("--render-only")
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        env = dict(os.environ, BOUNCE_DEMO_RENDER_ONLY="1" if render_only else "")
        cmd = [os.path.join(ROOT, "scripts/demo.sh"), bounce, out, size]
        start = time.monotonic()
        r = subprocess.run(cmd, capture_output=True, text=True, env=env)
        total = time.monotonic() - start
        if r.returncode != 0:
            sys.exit(f"bench/demo/run.py: scripts/demo.sh failed with status {r.returncode}: {r.stderr.strip()[-400:]}")
        with open(os.path.join(out, "demo-times.tsv")) as f:
            rows = [line.rstrip("\n").split("\t") for line in f][1:]
    pairs = [{"scene": s, "technique": t, "status": st, "ms": int(ms)} for s, t, st, ms in rows]
    render_s = sum(p["ms"] for p in pairs) / 1000.0
    rec = new_record("demo", f"bench/demo/run.py --size {size}" + (" --render-only" if render_only else ""), bounce)
    rec.update({
        "size": size,
        "demoCommand": rel(cmd),
        "renderSeconds": render_s,
        "renderBudgetSeconds": RENDER_BUDGET_SECONDS,
        "studySeconds": None if render_only else total - render_s,
        "totalSeconds": total,
        "rendered": sum(p["status"] == "0" for p in pairs),
        "refused": sum(p["status"] == "1" for p in pairs),
        "skipped": sum(p["status"] == "skipped" for p in pairs),
        "pairs": pairs,
    })
    print(f"demo: rendering part {render_s:.0f} s (budget {RENDER_BUDGET_SECONDS} s), {rec['rendered']} rendered, "
          f"{rec['refused']} refused, {rec['skipped']} skipped; total {total:.0f} s")
    for p in sorted(pairs, key=lambda p: -p["ms"])[:5]:
        print(f"  {p['ms'] / 1000:6.1f} s  {p['scene']} x {p['technique']}")
    print(write_record(rec))


if __name__ == "__main__":
    main()
