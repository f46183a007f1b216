#!/usr/bin/env python3
"""Frame times of every technique at its defaults on the Sponza-class `courtyard` (issue 30: the GPU
techniques within 1 s a frame at 256^2 on llvmpipe, the progressive radiosity methods within 2 s a frame
while they converge over frames; `radiosity-gather`, the expensive reference, is timed, not budgeted).

Usage: bench/large-scene/run.py [BOUNCE] [--size N] [--frames N] [--lights sun,sky] [--techniques a,b] [--timeout S]
       (defaults: build/src/app/bounce, 256, 6 frames, both lights, every technique, 600 s; any Python 3)

Each (technique, light) is one `bounce render --stats` process at the technique's defaults (the mode a
user runs: GL timestamp queries, no debug context); recorded per pair: the first frame's wall ms (shader
compilation, the technique's first build of its structures: the radiosity methods' first shooting),
the median and the maximum of the later frames' wall ms (`cpu_ms`, renderFrame to its closing glFinish),
the set-up seconds (scene upload, the technique's set-up), and whether the later frames meet the budget
of the technique's kind -- or the one-line refusal, or that it was stopped after RUN_TIMEOUT_S. `radiosity-gather` runs one frame (each is a full
gather). The raw record goes to bench/results/large-scene-<date>.json; bench/tables.py makes the README
table.
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from cli import ROOT, option, rel  # noqa: E402
from record import new_record, write_record  # noqa: E402

SCENE = "courtyard"
# issue 30's frame budgets at 256^2 on llvmpipe, milliseconds of wall time per frame after the first.
GPU_BUDGET_MS = 1000.0
RADIOSITY_BUDGET_MS = 2000.0
# Techniques timed but held to no frame budget: the gather computes the whole solution in every frame
# (the expensive reference); the baselines are here for scale.
UNBUDGETED = {"radiosity-gather"}
ONE_FRAME = {"radiosity-gather"}
# A run past this is stopped and recorded as such (a technique that needs longer is no interactive
# technique on this scene; the radiosity methods once took hours here).
RUN_TIMEOUT_S = 600  # seconds; --timeout overrides


def render(bounce, technique, size, frames, light, timeout):
    """One `bounce render --stats` process: (run record, None, command) or (None, (kind, message), command)."""
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "run.json")
        cmd = [bounce, "render", "--scene", SCENE, "--scene-param", f"light={light}", "--technique", technique,
               "--size", f"{size}x{size}", "--frames", str(frames), "--out", os.path.join(tmp, "o.exr"), "--stats", stats]
        try:
            r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return None, ("timedOut", f"stopped after {timeout:g} s"), rel(cmd)
        if r.returncode != 0:
            lines = r.stderr.strip().splitlines()
            return None, ("refused" if r.returncode == 1 else "error", lines[-1] if lines else f"status {r.returncode}"), rel(cmd)
        with open(stats) as f:
            return json.load(f), None, rel(cmd)


def techniques(bounce):
    out = subprocess.run([bounce, "list", "--techniques", "--names"], check=True, capture_output=True, text=True).stdout
    return [t for t in out.split() if t]


def budget_of(technique):
    if technique in UNBUDGETED:
        return None
    return RADIOSITY_BUDGET_MS if technique.startswith("radiosity-") else GPU_BUDGET_MS


def main():
    args = sys.argv[1:]
    size = option(args, "--size", 256)
    frames = option(args, "--frames", 6)
    lights = option(args, "--lights", "sun,sky", str).split(",")
    only = option(args, "--techniques", "", str)
    timeout = option(args, "--timeout", RUN_TIMEOUT_S, float)
    bounce = os.path.abspath(args[0] if args else os.path.join(ROOT, "build/src/app/bounce"))
    names = [t for t in techniques(bounce) if not only or t in only.split(",")]
    rec = new_record("large-scene", f"bench/large-scene/run.py --size {size} --frames {frames} --lights {','.join(lights)} --timeout {timeout:g}"
                     + (f" --techniques {only}" if only else ""), bounce)
    rec.update({"scene": SCENE, "size": size, "frames": frames, "gpuBudgetMs": GPU_BUDGET_MS,
                "radiosityBudgetMs": RADIOSITY_BUDGET_MS, "runTimeoutSeconds": timeout, "results": {}})
    for light in lights:
        rows = rec["results"].setdefault(light, {})
        for t in names:
            n = 1 if t in ONE_FRAME else frames
            record, failure, cmd = render(bounce, t, size, n, light, timeout)
            if failure:
                rows[t] = {failure[0]: failure[1], "command": cmd}
                print(f"{light:4} {t:22} {failure[0]}: {failure[1]}", flush=True)
                continue
            ms = [f["cpu_ms"] for f in record["frames"]]
            later = ms[1:]
            budget = budget_of(t)
            row = {"command": cmd, "frames": n, "firstFrameMs": ms[0], "setupSeconds": record.get("setup_seconds"),
                   "medianLaterMs": statistics.median(later) if later else None, "maxLaterMs": max(later) if later else None,
                   "budgetMs": budget,
                   "withinBudget": None if budget is None or not later else max(later) <= budget}
            rows[t] = row
            print(f"{light:4} {t:22} first {ms[0]:8.0f} ms  later median "
                  + (f"{row['medianLaterMs']:7.0f} max {row['maxLaterMs']:7.0f} ms" if later else "   -") +
                  (f"  budget {budget:.0f}: {'ok' if row['withinBudget'] else 'OVER'}" if budget and later else ""), flush=True)
    print(write_record(rec))


if __name__ == "__main__":
    main()
